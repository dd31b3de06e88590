"""The simulated cell as a Drake Diagram: ``MakeStation(scenario) -> Diagram``.

A discrete MultibodyPlant (SAP solver) holds the arm, the suction tool, the
cell and the objects as free bodies. The scenario's ``cup_physics`` picks how
the tool holds an object: ``rim`` (rims: spheres at the contact points of each
of the scenario's cups, with the planner's friction) or ``bellows`` (a
compliant bellows cup from the catalogue, :mod:`._bellows` and
:mod:`._bellows_suction`, independent of the planner's cup model). Objects are
compliant hydroelastic boxes against the rigid cell and each other (area
contact, so they rest and stack flat); the rim spheres touch them through point
contact. The arm tracks a commanded state through the plant's implicit PD
actuators, with an inverse-dynamics feedforward (gravity, Coriolis and the
commanded acceleration, for the arm and tool without payload) computed on a
separate controller plant. The vacuum is a
:class:`~rt_drake.simulation._suction.SuctionCup` with the scenario's
:class:`~rt_drake.model.vacuum.Vacuum` model: one vacuum force and one seal per
cup of the scenario's ``cup`` or ``tool``.

Exported ports of the Diagram:

- inputs ``robot.desired_state`` ([q; v], 12), ``robot.desired_acceleration``
  (6), ``suction.valve`` (1; on when > 0.5);
- outputs ``robot.state`` ([q; v] measured), ``body_poses``,
  ``body_spatial_velocities``, ``suction.sealed`` (per object, 1 while the
  vacuum of a cup holds it), ``suction.suction_force`` (N, the vacuum's
  current force, summed over the cups), ``suction.part_present`` (the vacuum
  switch, 1 or 0: every cup's),
  ``contact_results``, ``query_object``.
"""

from __future__ import annotations

import dataclasses

import numpy as np
from pydrake.geometry import (
    Box,
    Meshcat,
    MeshcatVisualizer,
    MeshcatVisualizerParams,
    Role,
)
from pydrake.multibody.plant import (
    AddMultibodyPlant,
    MultibodyPlant,
    MultibodyPlantConfig,
)
from pydrake.multibody.tree import JointActuatorIndex, PdControllerGains
from pydrake.systems.controllers import InverseDynamics
from pydrake.systems.framework import Diagram, DiagramBuilder

from rt_drake import arguments
from rt_drake.errors import InputError
from rt_drake.model.cup_physics import BellowsCup, CupPhysics, load_bellows_cup
from rt_drake.model.object_model import OBJECT_BODY
from rt_drake.model.plant import (
    ObjectMode,
    ScenarioModels,
    add_scenario_models,
    cup_poses_in_body,
    home_configuration,
    make_arm_plant,
    scenario_cup_frame,
)
from rt_drake.model.scenario import Scenario
from rt_drake.simulation._bellows import Lip, add_bellows_lips, place_lips
from rt_drake.simulation._bellows_suction import BellowsSuction
from rt_drake.simulation._suction import (
    CupOnTool,
    SuctionCup,
    SuctionTarget,
)


@dataclasses.dataclass
class StationOptions:
    """Simulation settings of the station.

    Attributes:
        time_step: s, the plant's discrete step.
        kp: N m/rad, PD stiffness per arm joint.
        kd: N m s/rad, PD damping per arm joint.
        seal_distance: m, largest cup-face gap at which the vacuum seals.
    """

    time_step: float = 1e-3
    kp: tuple[float, ...] = (6000.0, 6000.0, 3000.0, 800.0, 800.0, 300.0)
    kd: tuple[float, ...] = (190.0, 190.0, 80.0, 12.0, 12.0, 5.0)
    seal_distance: float = 0.005


@dataclasses.dataclass(frozen=True)
class Station:
    """The built station: its Diagram and the parts callers look into."""

    diagram: Diagram
    plant: MultibodyPlant
    models: ScenarioModels
    object_names: tuple[str, ...]
    #: The arm-and-tool plant of the feedforward; InverseDynamics keeps only
    #: a pointer to it, so the Station keeps it alive.
    controller_plant: MultibodyPlant
    #: The bellows cup's lips (``cup_physics: bellows``), one per cup; empty
    #: for the rim cup.
    lips: tuple[Lip, ...] = ()
    #: The catalogue cup of the lips (``cup_physics: bellows``), else None.
    bellows: BellowsCup | None = None


def MakeStation(
    scenario: Scenario,
    meshcat: Meshcat | None = None,
    options: StationOptions | None = None,
) -> Station:
    """Build the simulated cell of ``scenario`` (see the module docstring)."""
    arguments.instance(scenario, "scenario", Scenario, where="MakeStation")
    options = options or StationOptions()
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlant(
        MultibodyPlantConfig(
            time_step=options.time_step,
            discrete_contact_approximation="sap",
            contact_model="hydroelastic_with_fallback",
        ),
        builder,
    )
    plant.set_name("plant")
    physics = scenario.cup_physics.physics
    models = add_scenario_models(
        plant, scenario, ObjectMode.FREE, rims=physics is CupPhysics.RIM
    )
    cup_frame = scenario_cup_frame(plant, scenario)
    tool = scenario.tool_parameters()
    lips: list[Lip] = []
    if physics is CupPhysics.BELLOWS:
        bellows = load_bellows_cup(scenario.cup_physics.cup)
        lips = add_bellows_lips(
            plant,
            scene_graph,
            cup_frame.body(),
            cup_poses_in_body(cup_frame, tool),
            bellows,
        )
    _set_pd_gains(plant, models, options)
    plant.Finalize()
    if lips:
        place_lips(plant, lips, models.robot, home_configuration(plant, scenario))

    controller_plant = make_arm_plant(scenario)
    feedforward = builder.AddNamedSystem(
        "inverse_dynamics", InverseDynamics(controller_plant)
    )
    builder.Connect(
        plant.get_state_output_port(models.robot),
        feedforward.get_input_port_estimated_state(),
    )
    builder.Connect(
        feedforward.get_output_port_generalized_force(),
        plant.get_actuation_input_port(models.robot),
    )
    builder.ExportInput(
        feedforward.get_input_port_desired_acceleration(), "robot.desired_acceleration"
    )
    builder.ExportInput(
        plant.get_desired_state_input_port(models.robot), "robot.desired_state"
    )

    targets = [
        _suction_target(plant, scene_graph, models, o.name) for o in scenario.objects
    ]
    if lips:
        system: SuctionCup = BellowsSuction(
            lips, bellows, targets, scenario.vacuum, options.time_step
        )
    else:
        cups = [
            CupOnTool(X_TC=X_BC, suction_force=mount.cup.suction_force)
            for mount, X_BC in zip(
                tool.cups, cup_poses_in_body(cup_frame, tool), strict=True
            )
        ]
        system = SuctionCup(
            tool_body_index=cup_frame.body().index(),
            cups=cups,
            targets=targets,
            seal_distance=options.seal_distance,
            vacuum=scenario.vacuum,
            time_step=options.time_step,
        )
    suction = builder.AddNamedSystem("suction", system)
    builder.Connect(plant.get_body_poses_output_port(), suction.body_poses_input_port())
    builder.Connect(
        suction.GetOutputPort("spatial_forces"),
        plant.get_applied_spatial_force_input_port(),
    )
    builder.ExportInput(suction.valve_input_port(), "suction.valve")

    builder.ExportOutput(plant.get_state_output_port(models.robot), "robot.state")
    builder.ExportOutput(plant.get_body_poses_output_port(), "body_poses")
    builder.ExportOutput(
        plant.get_body_spatial_velocities_output_port(), "body_spatial_velocities"
    )
    for name in ("sealed", "suction_force", "part_present"):
        builder.ExportOutput(suction.GetOutputPort(name), f"suction.{name}")
    builder.ExportOutput(plant.get_contact_results_output_port(), "contact_results")
    builder.ExportOutput(scene_graph.get_query_output_port(), "query_object")
    if meshcat is not None:
        MeshcatVisualizer.AddToBuilder(
            builder,
            scene_graph,
            meshcat,
            MeshcatVisualizerParams(role=Role.kIllustration, prefix="visual"),
        )
    diagram = builder.Build()
    diagram.set_name("station")
    return Station(
        diagram=diagram,
        plant=plant,
        models=models,
        object_names=tuple(o.name for o in scenario.objects),
        controller_plant=controller_plant,
        lips=tuple(lips),
        bellows=bellows if lips else None,
    )


def _set_pd_gains(
    plant: MultibodyPlant, models: ScenarioModels, options: StationOptions
) -> None:
    # GetJointActuatorIndices(instance) needs a finalized plant; gains must be
    # set before Finalize.
    actuators = [
        JointActuatorIndex(i)
        for i in range(plant.num_actuators())
        if plant.get_joint_actuator(JointActuatorIndex(i)).model_instance()
        == models.robot
    ]
    if len(actuators) != len(options.kp) or len(options.kd) != len(options.kp):
        raise InputError(
            f"station gains: {len(options.kp)=} and {len(options.kd)=} but the robot "
            f"has {len(actuators)} actuators"
        )
    for index, kp, kd in zip(actuators, options.kp, options.kd, strict=True):
        plant.get_joint_actuator(index).set_controller_gains(
            PdControllerGains(p=kp, d=kd)
        )


def _suction_target(
    plant, scene_graph, models: ScenarioModels, name: str
) -> SuctionTarget:
    body = plant.GetBodyByName(OBJECT_BODY, models.objects[name])
    inspector = scene_graph.model_inspector()
    boxes = [
        inspector.GetShape(g)
        for g in plant.GetCollisionGeometriesForBody(body)
        if isinstance(inspector.GetShape(g), Box)
    ]
    if len(boxes) != 1:
        raise InputError(f"object '{name}': the suction model needs one box geometry")
    return SuctionTarget(
        body_index=body.index(), half_extents=np.array(boxes[0].size()) / 2
    )
