"""``planning.grasp_ramp_s``: a margin of the grasp-constrained MOVE, not a robot limit.

The MOVE retimed under the grasp constraint reaches each joint's
acceleration limit a_j in ``grasp_ramp_s`` at the earliest (jerk at most
``a_j / grasp_ramp_s``); the same path retimed without the constraint keeps
the robot's own jerk limits (``robot.jerk_limits``). Both checked on the
sampled trajectories by finite differences of the acceleration.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from rt_drake.errors import ScenarioError
from rt_drake.model.plant import make_arm_plant
from rt_drake.model.resources import resolve_scenario_path
from rt_drake.model.scenario import load_scenario
from rt_drake.retiming import JointLimits
from rt_drake.simulation import OnlineMotions
from rt_drake.types.path import GeometricPath

HOME = np.array([0.0, 0.35, 1.75, 0.0, 1.04, 0.0])
#: rad: a short sideways swing with the cup facing down.
SWING = np.array([HOME, HOME + [0.5, 0.05, -0.1, 0.0, 0.05, -0.3]])
#: s, the sampling step of the finite differences.
DT = 1e-3


def test_the_ramp_caps_each_joint_jerk_at_acceleration_over_ramp():
    """``min(jerk, a / ramp)``, the robot's jerk None counting as unlimited."""
    limits = JointLimits(
        velocity=np.ones(3),
        acceleration=np.array([10.0, 20.0, 40.0]),
        jerk=np.array([100.0, 20.0, 1000.0]),
    )
    ramped = limits.with_acceleration_ramp(0.25)
    # a / 0.25 = (40, 80, 160), each against the robot's own jerk.
    assert ramped.jerk.tolist() == [40.0, 20.0, 160.0]
    assert limits.without_jerk().with_acceleration_ramp(0.5).jerk.tolist() == [
        20.0,
        40.0,
        80.0,
    ]
    assert ramped.acceleration.tolist() == limits.acceleration.tolist()


@pytest.mark.parametrize("value", [0, -0.1, 2.5])
def test_a_ramp_out_of_range_is_refused_naming_the_key(tmp_path, value):
    path = tmp_path / "ramp.yaml"
    base = resolve_scenario_path("random_transport_paper_bellows").read_text()
    path.write_text(base.replace("grasp_ramp_s: 0.343", f"grasp_ramp_s: {value}"))
    with pytest.raises(ScenarioError, match="planning.grasp_ramp_s.*got"):
        load_scenario(path)


def _max_jerk(trajectory) -> np.ndarray:
    """Per joint, the largest |change of acceleration| / DT over the samples."""
    t = np.arange(trajectory.start_time(), trajectory.end_time(), DT)
    vdot = np.array([trajectory.EvalDerivative(ti, 2).ravel() for ti in t])
    return np.abs(np.diff(vdot, axis=0)).max(axis=0) / DT


@pytest.fixture(scope="module")
def swing():
    """The swing retimed with and without the grasp of the notebook."""
    scenario = load_scenario(resolve_scenario_path("random_transport_paper_bellows"))
    scenario = dataclasses.replace(
        scenario, robot=dataclasses.replace(scenario.robot, home=HOME.tolist())
    )
    motions = OnlineMotions(scenario, optimize=False, jerk_limits=True)
    obj = scenario.objects[0]
    grasp = motions.grasp_for(obj, obj.grasp.GetDeterministicValue())
    path = GeometricPath.from_waypoints(SWING)
    with_grasp = motions.retime_path(path, grasp)
    without = motions.retime_path(path, None)
    # The shaped MOVE's retime: on points placed by a profile of the path.
    on_profile = motions.retime_on_profile(path, grasp, without)
    return scenario, with_grasp, without, on_profile


def test_only_the_grasp_constrained_move_ramps_over_the_cup_period(swing):
    scenario, with_grasp, without, on_profile = swing
    acceleration = JointLimits.from_plant(
        make_arm_plant(scenario), scenario.robot
    ).acceleration
    robot_jerk = np.array(scenario.robot.jerk_limits)
    # The scenario's ramp: the jerk that reaches a_j in grasp_ramp_s.
    tight = np.minimum(robot_jerk, acceleration / scenario.planning.grasp_ramp_s)
    assert np.all(tight < robot_jerk)
    assert np.all(_max_jerk(with_grasp.trajectory) <= 1.01 * tight)
    # The shaped MOVE's retime (on the optimiser's profile) ramps as well.
    assert np.all(_max_jerk(on_profile.trajectory) <= 1.01 * tight)
    # Without the grasp constraint: the robot's jerk only, and it uses more.
    free = _max_jerk(without.trajectory)
    assert np.all(free <= 1.01 * robot_jerk)
    assert np.any(free > 1.5 * tight)
    assert without.duration < with_grasp.duration
