"""A test rig for the bellows cup alone: a fixed tool, one lip, one box.

No arm and no planner: the tool body is welded to the world with its cup
frame C pointing down (+z_C = -z_W), a box hangs on the lip, the vacuum is
on, and an external wrench ramps on the box. The box has a point-contact
stiffness far above the lip's and no dissipation of its own, so the lip's
springs alone set the contact.
"""

from __future__ import annotations

import dataclasses

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.geometry import AddContactMaterial, Box, ProximityProperties
from pydrake.math import RigidTransform, RollPitchYaw
from pydrake.multibody.math import SpatialForce
from pydrake.multibody.plant import (
    AddMultibodyPlant,
    CoulombFriction,
    ExternallyAppliedSpatialForce,
    ExternallyAppliedSpatialForceMultiplexer,
    MultibodyPlantConfig,
)
from pydrake.multibody.tree import SpatialInertia
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder, LeafSystem
from pydrake.systems.primitives import ConstantVectorSource

from rt_drake.model.cup_physics import BellowsCup
from rt_drake.simulation._bellows import add_bellows_lips
from rt_drake.simulation._bellows_suction import BellowsSuction
from rt_drake.simulation._suction import SuctionTarget

#: The box: the notebook's mass and size (0.551 kg, 0.213 x 0.14 x 0.025 m).
MASS = 0.551
SIZE = np.array([0.213, 0.14, 0.025])
GRAVITY = 9.81
#: X_WC: the cup frame 0.5 m up, pointing down.
X_WC = RigidTransform(RollPitchYaw(np.pi, 0.0, 0.0), [0.0, 0.0, 0.5])


class _Ramp(LeafSystem):
    """A wrench on the box: ``F(t) = F_C clip(t - t0, 0, t_hold - t0)``.

    ``F_C``: the wrench per second, [torque; force] in C, applied at the
    face point under the lip centre; it grows from t0 and stays at t_hold.
    """

    def __init__(self, body_index, F_C: np.ndarray, t_start: float, t_hold: float):
        super().__init__()
        self._body = body_index
        self._F_W = np.concatenate(
            [X_WC.rotation() @ F_C[:3], X_WC.rotation() @ F_C[3:]]
        )
        self._t0 = t_start
        self._t1 = t_hold
        self.DeclareAbstractOutputPort(
            "forces",
            lambda: AbstractValue.Make([ExternallyAppliedSpatialForce()]),
            self._Calc,
        )

    def _Calc(self, context, output):
        scale = float(np.clip(context.get_time(), self._t0, self._t1)) - self._t0
        force = ExternallyAppliedSpatialForce()
        force.body_index = self._body
        force.p_BoBq_B = np.array([0.0, 0.0, SIZE[2] / 2])
        force.F_Bq_W = SpatialForce(scale * self._F_W[:3], scale * self._F_W[3:])
        output.set_value([force])


@dataclasses.dataclass
class Rig:
    """The built rig and its simulator."""

    simulator: Simulator
    plant: object
    suction: BellowsSuction
    lip: object
    box: object

    def X_CL(self) -> RigidTransform:
        """The lip's pose in the cup frame C (the bushing's deflection)."""
        context = self.plant.GetMyContextFromRoot(self.simulator.get_context())
        return X_WC.inverse() @ self.plant.EvalBodyPoseInWorld(context, self.lip)

    def X_LO(self) -> RigidTransform:
        """The box's pose on the lip."""
        context = self.plant.GetMyContextFromRoot(self.simulator.get_context())
        X_WL = self.plant.EvalBodyPoseInWorld(context, self.lip)
        return X_WL.inverse() @ self.plant.EvalBodyPoseInWorld(context, self.box)

    def sealed(self) -> bool:
        """Whether the vacuum holds the box."""
        context = self.suction.GetMyContextFromRoot(self.simulator.get_context())
        return bool(self.suction.GetOutputPort("sealed").Eval(context)[0] > 0.5)


def make_rig(
    cup: BellowsCup,
    F_C: np.ndarray,
    t_start: float = 0.1,
    t_hold: float = np.inf,
    gravity: bool = True,
) -> Rig:
    """The rig with the wrench ramp of :class:`_Ramp` ([torque; force] in C).

    The lip and box start at rest in equilibrium under gravity: the
    bellows stretched by ``m g / k_axial`` along +z_C (down).
    """
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlant(
        MultibodyPlantConfig(time_step=1e-3, discrete_contact_approximation="sap"),
        builder,
    )
    if not gravity:
        plant.mutable_gravity_field().set_gravity_vector(np.zeros(3))
    tool = plant.AddRigidBody(
        "tool", SpatialInertia.SolidBoxWithMass(1.0, 0.1, 0.1, 0.1)
    )
    plant.WeldFrames(plant.world_frame(), tool.body_frame(), X_WC)
    (lip_info,) = add_bellows_lips(plant, scene_graph, tool, [RigidTransform()], cup)
    inertia = SpatialInertia.SolidBoxWithMass(MASS, *SIZE)
    box = plant.AddRigidBody("box", plant.AddModelInstance("box"), inertia)
    properties = ProximityProperties()
    AddContactMaterial(None, 1e9, CoulombFriction(1.0, 1.0), properties)
    properties.AddProperty("material", "relaxation_time", 0.0)
    plant.RegisterCollisionGeometry(
        box, RigidTransform(), Box(*SIZE), "box", properties
    )
    plant.Finalize()
    lip = plant.get_body(lip_info.body_index)
    sag = MASS * GRAVITY / cup.axial_stiffness if gravity else 0.0
    X_WL = X_WC @ RigidTransform([0.0, 0.0, sag])
    plant.SetDefaultFloatingBaseBodyPose(lip, X_WL)
    # The box's top face on the lip plane: X_LO = (0, 0, h/2), turned over.
    X_LO = RigidTransform(RollPitchYaw(np.pi, 0.0, 0.0), [0.0, 0.0, SIZE[2] / 2])
    plant.SetDefaultFloatingBaseBodyPose(box, X_WL @ X_LO)
    suction = builder.AddSystem(
        BellowsSuction(
            [lip_info], cup, [SuctionTarget(box.index(), SIZE / 2)], time_step=1e-3
        )
    )
    builder.Connect(plant.get_body_poses_output_port(), suction.body_poses_input_port())
    valve = builder.AddSystem(ConstantVectorSource([1.0]))
    builder.Connect(valve.get_output_port(), suction.valve_input_port())
    ramp = builder.AddSystem(
        _Ramp(box.index(), np.asarray(F_C, float), t_start, t_hold)
    )
    mux = builder.AddSystem(ExternallyAppliedSpatialForceMultiplexer(2))
    builder.Connect(suction.GetOutputPort("spatial_forces"), mux.get_input_port(0))
    builder.Connect(ramp.get_output_port(), mux.get_input_port(1))
    builder.Connect(mux.get_output_port(), plant.get_applied_spatial_force_input_port())
    simulator = Simulator(builder.Build())
    simulator.Initialize()
    return Rig(simulator, plant, suction, lip, box)
