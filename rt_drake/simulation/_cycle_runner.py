"""Run the pick-and-place cycle in simulation: station + sequencer.

``run_cycle(scenario, motions)`` builds the Diagram (the station of
:mod:`._station` driven by a :class:`~._sequencer.Sequencer`), simulates until
every object is placed, and returns what the sequencer measured. With a
Meshcat, the run is recorded for offline replay. ``object_inertias``
replaces the inertia of objects in the simulated plant (a parameter of its
context): the object the robot holds may differ from the one it planned for.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

import numpy as np
from pydrake.geometry import Meshcat
from pydrake.multibody.tree import SpatialInertia
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import Context, DiagramBuilder, EventStatus

from rt_drake import arguments
from rt_drake.errors import RtDrakeError
from rt_drake.model.object_model import OBJECT_BODY
from rt_drake.model.plant import (
    home_configuration,
    scenario_cup_frame,
)
from rt_drake.model.scenario import Scenario
from rt_drake.simulation._held_start import hang_on_lips
from rt_drake.simulation._sequencer import Sequencer
from rt_drake.simulation._station import (
    MakeStation,
    Station,
    StationOptions,
)
from rt_drake.simulation.motion import MotionSource
from rt_drake.simulation.records import ObjectRecord
from rt_drake.types.phase import Phase


class CycleTimeout(RtDrakeError):
    """The cycle did not finish within the simulated time limit."""


@dataclasses.dataclass(frozen=True)
class CycleResult:
    """The outcome of one simulated cycle.

    Attributes:
        records: per object, planning wall times, plan waits, phase
            durations, slip and placement error.
        sim_time: s of simulated time the cycle took.
        max_tracking_error: rad, worst |q - q_desired| of the arm, sampled
            at the sequencer's rate.
    """

    records: tuple[ObjectRecord, ...]
    sim_time: float
    max_tracking_error: float


def build_cycle(
    scenario: Scenario,
    motions: MotionSource,
    meshcat: Meshcat | None = None,
    options: StationOptions | None = None,
    pipelined: bool = True,
    held_at_start: bool = False,
):
    """Return (diagram, station, sequencer) of the cycle of ``scenario``.

    ``pipelined``: the sequencer plans each motion ahead (:mod:`._sequencer`).
    ``held_at_start``: under the bellows cup, the first object starts sealed
    on the lips, the valve on from t = 0 (:func:`hold_at_start` poses it).
    """
    station: Station = MakeStation(scenario, meshcat=meshcat, options=options)
    plant = station.plant
    cup = scenario_cup_frame(plant, scenario)
    bodies = [
        plant.GetBodyByName(OBJECT_BODY, station.models.objects[o.name])
        for o in scenario.objects
    ]
    gravity = float(np.linalg.norm(plant.gravity_field().gravity_vector()))
    # Slip is the object's motion on what touches it: the cup frame of the
    # tool, or each bellows cup's lip (its bellows deflection apart), the
    # largest; the motion on the tool's cup frame is measured too.
    builder = DiagramBuilder()
    cell = builder.AddNamedSystem("station", station.diagram)
    sequencer = builder.AddNamedSystem(
        "sequencer",
        Sequencer(
            motions=motions,
            objects=list(scenario.objects),
            object_bodies=[body.index() for body in bodies],
            object_weights=[body.default_mass() * gravity for body in bodies],
            tool_body=cup.body().index(),
            X_TC=cup.GetFixedPoseInBodyFrame(),
            q_home=home_configuration(plant, scenario),
            vacuum=scenario.vacuum,
            pipelined=pipelined,
            command_period=scenario.robot.command_period_s,
            lip_bodies=[lip.body_index for lip in station.lips],
            held_at_start=held_at_start and bool(station.lips),
        ),
    )
    for name in ("body_poses", "body_spatial_velocities"):
        builder.Connect(cell.GetOutputPort(name), sequencer.GetInputPort(name))
    for name in ("suction_force", "part_present"):
        builder.Connect(
            cell.GetOutputPort(f"suction.{name}"), sequencer.GetInputPort(name)
        )
    for name in ("desired_state", "desired_acceleration"):
        builder.Connect(
            sequencer.GetOutputPort(name), cell.GetInputPort(f"robot.{name}")
        )
    builder.Connect(
        sequencer.GetOutputPort("valve"), cell.GetInputPort("suction.valve")
    )
    return builder.Build(), station, sequencer


def hold_at_start(scenario: Scenario, station: Station, root: Context) -> None:
    """Pose the first object held on the bellows lips, sealed, in ``root``.

    The object and the lips sag to their static equilibrium on the bushings
    (:func:`~._held_start.hang_on_lips`) and every lip starts SEALED
    (:meth:`~._bellows_suction.BellowsSuction.start_sealed`): the state an
    object already picked and at rest is in. ``root`` is the cycle's root
    context, the arm posed.
    """
    assert station.bellows is not None, "hold_at_start needs the bellows cup"
    plant = station.plant
    name = scenario.objects[0].name
    body = plant.GetBodyByName(OBJECT_BODY, station.models.objects[name])
    plant_context = plant.GetMyMutableContextFromRoot(root)
    hang_on_lips(plant, plant_context, station.lips, station.bellows, body)
    suction = station.diagram.GetSubsystemByName("suction")
    suction.start_sealed(suction.GetMyMutableContextFromRoot(root))


def run_cycle(
    scenario: Scenario,
    motions: MotionSource,
    meshcat: Meshcat | None = None,
    options: StationOptions | None = None,
    max_sim_time: float = 120.0,
    pipelined: bool = True,
    progress: Callable[[int, Phase], None] | None = None,
    object_inertias: dict[str, SpatialInertia] | None = None,
    held_at_start: bool = False,
) -> CycleResult:
    """Simulate the whole cycle; raise CycleTimeout past ``max_sim_time`` s.

    Args:
        scenario: The cell and its objects.
        motions: Plans and retimes each phase.
        meshcat: Records the run for replay, if given.
        options: Simulation settings.
        max_sim_time: s of simulated time at most.
        pipelined: Plan each motion ahead (:mod:`._sequencer`).
        progress: Called with (object index, phase) whenever the phase
            changes.
        object_inertias: Per object name, its true spatial inertia ``M_OOo_O``
            (about its body origin, in its body frame), in place of its
            model's.
        held_at_start: Under the bellows cup, the first object starts held:
            sealed on the lips, at rest at its static equilibrium on the
            bellows, the valve on from t = 0 (:func:`hold_at_start`; the
            object must start on the lips). The rim cup ignores it.
    """
    arguments.instance(scenario, "scenario", Scenario, where="run_cycle")
    arguments.having(
        motions, "motions", "MotionSource", ("pick", "move"), where="run_cycle"
    )
    arguments.number(max_sim_time, "max_sim_time", where="run_cycle", above=0.0)
    diagram, station, sequencer = build_cycle(
        scenario, motions, meshcat, options, pipelined, held_at_start
    )
    simulator = Simulator(diagram)
    context = simulator.get_mutable_context()
    plant = station.plant
    plant_context = plant.GetMyMutableContextFromRoot(context)
    plant.SetPositions(
        plant_context, station.models.robot, home_configuration(plant, scenario)
    )
    for name, M_OOo_O in (object_inertias or {}).items():
        body = plant.GetBodyByName(OBJECT_BODY, station.models.objects[name])
        body.SetSpatialInertiaInBodyFrame(plant_context, M_OOo_O)
    if held_at_start and station.lips:
        hold_at_start(scenario, station, context)
    sequencer_context = sequencer.GetMyContextFromRoot(context)
    worst = [0.0]
    seen: list[tuple[int, Phase]] = []

    def monitor(root_context):
        state = sequencer.sequencer_state(sequencer_context)
        if progress is not None and (
            not seen or seen[-1] != (state.object_index, state.phase)
        ):
            seen.append((state.object_index, state.phase))
            progress(state.object_index, state.phase)
        q = plant.GetPositions(plant_context, station.models.robot)
        q_desired = sequencer.GetOutputPort("desired_state").Eval(sequencer_context)[
            : len(q)
        ]
        worst[0] = max(worst[0], float(np.abs(q - q_desired).max()))
        if sequencer.is_done(sequencer_context):
            return EventStatus.ReachedTermination(sequencer, "every object placed")
        return EventStatus.Succeeded()

    simulator.set_monitor(monitor)
    if meshcat is not None:
        visualizer = station.diagram.GetSubsystemByName("meshcat_visualizer(visual)")
        visualizer.StartRecording()
    simulator.Initialize()
    simulator.AdvanceTo(max_sim_time)
    if meshcat is not None:
        visualizer.StopRecording()
        visualizer.PublishRecording()
    if not sequencer.is_done(sequencer_context):
        state = sequencer.sequencer_state(sequencer_context)
        raise CycleTimeout(
            f"cycle not finished after {max_sim_time} s of simulation (object "
            f"{state.object_index}, phase {state.phase.value})"
        )
    return CycleResult(
        records=sequencer.sequencer_state(sequencer_context).records,
        sim_time=context.get_time(),
        max_tracking_error=worst[0],
    )


__all__ = ["CycleResult", "CycleTimeout", "build_cycle", "hold_at_start", "run_cycle"]
