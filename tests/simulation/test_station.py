"""The simulated cell: suction holds, drops and ignores objects as it should."""

from __future__ import annotations

import numpy as np
import pytest
from motion_helpers import IkMotions, min_jerk
from pydrake.math import RigidTransform, RollPitchYaw
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import Demultiplexer, TrajectorySource
from pydrake.trajectories import PiecewisePolynomial

from rt_drake.model.object_model import OBJECT_BODY
from rt_drake.model.plant import CUP_FRAME
from rt_drake.model.scenario import load_scenario
from rt_drake.simulation._station import MakeStation
from rt_drake.simulation._suction import find_seal

#: rad; the PD + inverse-dynamics arm tracks a 1 s, 15 cm lift within this.
TRACKING_TOLERANCE = 2e-3
LIFT = 0.15  # m
T_LIFT = 1.0  # s, duration of the lift
T_HOLD = 0.5  # s, wait before the lift


def _hold_then_lift(q_start, q_end):
    """Stand still for T_HOLD, then a minimum-jerk joint motion over T_LIFT."""
    hold = PiecewisePolynomial.FirstOrderHold(
        [0.0, T_HOLD], np.column_stack([q_start, q_start])
    )
    lift = min_jerk([q_start, q_end], [T_LIFT])
    lift.shiftRight(T_HOLD)
    hold.ConcatenateInTime(lift)
    return hold


def _run_lift(scenario_path, valve_times, valve_values, t_final):
    """Cup on the notebook, wait, lift 15 cm; return samples of the run."""
    scenario = load_scenario(scenario_path)
    ik = IkMotions(scenario)
    X_WC = ik.grasp(scenario.object("notebook"))
    q_grasp = ik.ik(X_WC, np.array(scenario.robot.home))
    q_up = ik.ik(ik.raised(X_WC, LIFT), q_grasp)
    q_traj = _hold_then_lift(q_grasp, q_up)

    station = MakeStation(scenario)
    builder = DiagramBuilder()
    cell = builder.AddSystem(station.diagram)
    source = builder.AddSystem(
        TrajectorySource(
            q_traj, output_derivative_order=2, zero_derivatives_beyond_limits=True
        )
    )
    split = builder.AddSystem(Demultiplexer([12, 6]))
    builder.Connect(source.get_output_port(), split.get_input_port())
    builder.Connect(split.get_output_port(0), cell.GetInputPort("robot.desired_state"))
    builder.Connect(
        split.get_output_port(1), cell.GetInputPort("robot.desired_acceleration")
    )
    valve = builder.AddSystem(
        TrajectorySource(
            PiecewisePolynomial.ZeroOrderHold(valve_times, np.atleast_2d(valve_values))
        )
    )
    builder.Connect(valve.get_output_port(), cell.GetInputPort("suction.valve"))
    diagram = builder.Build()

    simulator = Simulator(diagram)
    context = simulator.get_mutable_context()
    plant = station.plant
    plant_context = plant.GetMyMutableContextFromRoot(context)
    plant.SetPositions(plant_context, station.models.robot, q_grasp)
    body = plant.GetBodyByName(OBJECT_BODY, station.models.objects["notebook"])
    cup = plant.GetFrameByName(CUP_FRAME)
    samples = []
    for t in np.arange(0.0, t_final + 1e-9, 0.02):
        simulator.AdvanceTo(t)
        q = plant.GetPositions(plant_context, station.models.robot)
        samples.append(
            dict(
                t=t,
                X_CO=cup.CalcPoseInWorld(plant_context).inverse()
                @ plant.EvalBodyPoseInWorld(plant_context, body),
                z_object=plant.EvalBodyPoseInWorld(plant_context, body).translation()[
                    2
                ],
                tracking=np.abs(q - q_traj.value(t).ravel()).max(),
            )
        )
    return samples


#: s, the valve of the lift run opens (the suction stops): 0.5 s after the lift.
T_OFF = T_HOLD + T_LIFT + 0.51


@pytest.fixture(scope="module")
def lift_run(scenario_paths):
    """Suction on, wait, lift, hold 0.5 s; then the valve opens mid-air."""
    return _run_lift(
        scenario_paths["random_transport"],
        [0.0, T_OFF, 10.0],
        [[1.0, 0.0, 0.0]],
        T_OFF + 0.4,
    )


@pytest.fixture(scope="module")
def held_run(lift_run):
    """The lift run's samples while the valve is on (to 0.5 s after the lift)."""
    return [s for s in lift_run if s["t"] <= T_HOLD + T_LIFT + 0.5 + 1e-9]


def test_object_follows_the_cup_while_the_valve_is_on(held_run):
    X_CO_0 = held_run[0]["X_CO"]
    for sample in held_run:
        drift = np.linalg.norm(sample["X_CO"].translation() - X_CO_0.translation())
        assert drift < 5e-4, (sample["t"], drift)
    assert held_run[-1]["z_object"] - held_run[0]["z_object"] == pytest.approx(
        LIFT, abs=2e-3
    )


def test_arm_tracks_the_commanded_trajectory(held_run):
    worst = max(s["tracking"] for s in held_run)
    assert worst < TRACKING_TOLERANCE


def test_object_stays_in_the_bin_without_suction(scenario_paths):
    run = _run_lift(
        scenario_paths["random_transport"],
        [0.0, 10.0],
        [[0.0, 0.0]],
        T_HOLD + T_LIFT + 0.3,
    )
    assert abs(run[-1]["z_object"] - run[0]["z_object"]) < 2e-3
    # ... while the cup went up: the object is now far below it.
    assert np.linalg.norm(run[-1]["X_CO"].translation()) > LIFT - 0.01


def test_object_falls_when_the_valve_opens_mid_air(lift_run):
    lifted = [s for s in lift_run if s["t"] <= T_OFF][-1]["z_object"]
    assert lifted > lift_run[0]["z_object"] + LIFT - 0.01
    # Dropped: back down on the bin floor (or what lies in it).
    assert lift_run[-1]["z_object"] < lifted - 0.1


def _box_cup(yaw=0.0, gap=0.0, tilt_deg=0.0, offset=(0.0, 0.0)):
    half = np.array([0.1, 0.07, 0.0125])
    X_WO = RigidTransform(RollPitchYaw(0, 0, yaw), [0.4, -0.3, 0.0])
    X_OC = RigidTransform(
        RollPitchYaw(np.pi + np.radians(tilt_deg), 0, 0),
        [offset[0], offset[1], half[2] + gap],
    )
    return X_WO @ X_OC, X_WO, half


def test_seal_gap_and_point_on_the_top_face():
    X_WC, X_WO, half = _box_cup(yaw=0.7, gap=0.003, offset=(0.02, -0.01))
    seal = find_seal(X_WC, X_WO, half)
    assert seal.gap == pytest.approx(0.003)
    np.testing.assert_allclose(seal.p_OQ_O, [0.02, -0.01, half[2]], atol=1e-12)


def test_no_seal_when_tilted_or_off_the_face():
    assert find_seal(*_box_cup(tilt_deg=30.0)) is None
    assert find_seal(*_box_cup(offset=(0.15, 0.0))) is None
    assert find_seal(*_box_cup(tilt_deg=10.0)) is not None
