"""Jerk-limited retiming: every limit, the jerk and the grasp held at 1 kHz.

References: the jerk from third differences of positions sampled at 1 kHz
(a weighted mean of q''' over the three steps, so within the limit when
q''' is); the velocity, acceleration, grasp and torques by
:func:`check_trajectory` (body accelerations and Newton-Euler); the
duration against Ruckig's time-optimal phase-synchronised rest-to-rest
motion, which on a straight line in joint space is the path's optimum.
"""

from __future__ import annotations

import numpy as np
import pytest
from pydrake.trajectories import PiecewisePolynomial
from ruckig import InputParameter, Result, Ruckig, Synchronization
from ruckig import Trajectory as RuckigTrajectory

from rt_drake.experiments._transport_experiment import (
    move_from_the_cup,
    transport_scenario,
)
from rt_drake.model.held import held_object_of
from rt_drake.model.plant import make_arm_plant
from rt_drake.model.resources import scenarios_dir
from rt_drake.model.scenario import load_scenario
from rt_drake.planning import sample_transports
from rt_drake.retiming import (
    GraspConstraint,
    JerkTimedPath,
    JointLimits,
    Margin,
    RetimeInputError,
    TimedPath,
    check_trajectory,
    retime,
)
from rt_drake.simulation import OnlineMotions

HOME = np.array([0.0, 0.35, 1.75, 0.0, 1.04, 0.0])
#: Jerk limits of the tests: the acceleration limits reached in 50 ms.
PER_SECOND = 20.0


@pytest.fixture(scope="module")
def limits(plant, scenario):
    plain = JointLimits.from_plant(plant, scenario.robot)
    return JointLimits(
        plain.velocity, plain.acceleration, jerk=PER_SECOND * plain.acceleration
    )


@pytest.fixture(scope="module")
def grasp(scenario):
    return GraspConstraint.for_cup(
        held_object_of(scenario.object("carton_box")), scenario.cup
    )


def _difference_jerk(trajectory) -> np.ndarray:
    """q''' from third differences of q sampled at 1 kHz, (M - 3, n)."""
    step = 1e-3
    t = trajectory.start_time() + step * np.arange(
        int(trajectory.end_time() / step) + 1
    )
    q = np.array([trajectory.value(ti).ravel() for ti in t])
    return np.diff(q, 3, axis=0) / step**3


def _assert_all_limits(plant, result, limits, grasp):
    assert isinstance(result.trajectory, JerkTimedPath)
    jerk = _difference_jerk(result.trajectory)
    ratio = np.abs(jerk) / limits.jerk
    assert ratio.max() <= 1.0 + 1e-3, ratio.max()
    assert ratio.max() > 0.9  # the jerk binds somewhere: the limit is used
    check = check_trajectory(plant, result.trajectory, limits, grasp)
    assert Margin.JERK in check.margins
    assert check.passed(), check.summary()


@pytest.mark.parametrize("seed", [0, 1])
def test_a_straight_line_takes_ruckigs_time_within_a_few_percent(plant, limits, seed):
    """Rest to rest on a line, no grasp: Ruckig's phase-synchronised motion
    stays on the line and is time-optimal there, so it bounds ours below."""
    step = np.random.default_rng(seed).uniform(-0.8, 0.8, 6)
    line = PiecewisePolynomial.FirstOrderHold(
        [0.0, 1.0], np.column_stack([HOME, HOME + step])
    )
    result = retime(plant, line, limits)
    setup = InputParameter(6)
    setup.current_position, setup.target_position = HOME, HOME + step
    setup.max_velocity = limits.velocity
    setup.max_acceleration = limits.acceleration
    setup.max_jerk = limits.jerk
    setup.synchronization = Synchronization.Phase
    reference = RuckigTrajectory(6)
    assert Ruckig(6).calculate(setup, reference) == Result.Working
    assert result.duration >= reference.duration * (1.0 - 1e-3)
    assert result.duration <= reference.duration * 1.04
    # Ruckig's motion is on the line: the same positions at its mid-time.
    middle = np.array(reference.at_time(0.5 * reference.duration)[0])
    direction = (middle - HOME) / np.linalg.norm(middle - HOME)
    assert np.allclose(direction, step / np.linalg.norm(step), atol=1e-9)
    _assert_all_limits(plant, result, limits, None)


@pytest.mark.parametrize("with_grasp", [False, True])
def test_a_random_path_keeps_every_limit_and_the_jerk(plant, limits, grasp, with_grasp):
    rng = np.random.default_rng(3)
    path = np.cumsum(np.vstack([HOME, rng.uniform(-0.4, 0.4, (3, 6))]), axis=0)
    held = grasp if with_grasp else None
    result = retime(plant, path, limits, held)
    _assert_all_limits(plant, result, limits, held)
    # The jerk costs little time. TOPP-RA's profile (s'' constant per
    # segment) is optimal among its own discretisation only: under the grasp,
    # whose rows mix s'' and s'^2, a continuous s'' can follow the rows more
    # closely and be a little faster (1.1 % here).
    free = retime(plant, path, limits.without_jerk(), held)
    assert 0.97 * free.duration <= result.duration <= 1.15 * free.duration


@pytest.fixture(scope="module")
def planned_move():
    """Table I's first MOVE (random_transport_paper, seed 0), planned."""
    scenario = load_scenario(scenarios_dir() / "random_transport_paper.yaml")
    X_start, X_goal = sample_transports(scenario, 1, seed=0)[0]
    one = transport_scenario(scenario, "notebook", X_start, X_goal)
    motions = OnlineMotions(one, grasp_constraint=True, seed=0, optimize=False)
    move = move_from_the_cup(motions, one.objects[0], X_start)
    assert move.planned is not None and move.grasp is not None
    return one, move


@pytest.mark.parametrize("with_grasp", [False, True])
def test_a_planned_move_keeps_every_limit_and_the_jerk(planned_move, with_grasp):
    scenario, move = planned_move
    plant = make_arm_plant(scenario)
    limits = JointLimits.from_plant(plant, scenario.robot, jerk=True)
    assert limits.jerk is not None
    held = move.grasp if with_grasp else None
    result = retime(plant, move.planned.path, limits, held)
    _assert_all_limits(plant, result, limits, held)


def test_without_jerk_limits_the_retimer_is_todays(plant, limits, grasp):
    path = np.array([HOME, HOME + [0.5, -0.2, 0.3, 0.1, 0.2, 0.4]])
    plain = retime(plant, path, JointLimits(limits.velocity, limits.acceleration))
    dropped = retime(plant, path, limits.without_jerk())
    assert isinstance(dropped.trajectory, TimedPath)
    assert dropped.path_acceleration is None and dropped.jerk_lps == 0
    for name in ("gridpoints", "sd", "sdd", "margin"):
        np.testing.assert_array_equal(getattr(plain, name), getattr(dropped, name))


def test_the_motion_is_what_the_profile_says(plant, limits):
    """q', q'' of the trajectory match differences of q; s passes the grid."""
    path = np.array([HOME, HOME + [0.6, -0.3, 0.2, 0.0, 0.3, 0.5]])
    result = retime(plant, path, limits)
    trajectory = result.trajectory
    t = np.linspace(0.0, trajectory.end_time(), 4001)
    q, v, a, j = trajectory.sample(t, order=3)
    h = t[1] - t[0]
    np.testing.assert_allclose(np.gradient(q, h, axis=0)[1:-1], v[1:-1], atol=1e-4)
    np.testing.assert_allclose(np.gradient(v, h, axis=0)[1:-1], a[1:-1], atol=2e-2)
    s_at_grid = trajectory.path_state(trajectory.times)[0]
    np.testing.assert_allclose(s_at_grid, result.gridpoints, atol=1e-12)
    np.testing.assert_allclose(a[0], 0.0, atol=1e-12)  # starts at rest ...
    np.testing.assert_allclose(a[-1], 0.0, atol=1e-12)  # ... and stops there


def test_the_file_and_its_export_keep_the_jerk_limited_motion(
    plant, limits, scenario, tmp_path
):
    """``.npz`` round trip: the export rebuilds the jerk-limited motion from
    the file's path and profile, not TOPP-RA's constant-s'' motion."""
    from rt_drake.export import export_trajectory
    from rt_drake.retiming import load_trajectory, sample_trajectory, save_trajectory
    from rt_drake.types.path import path_waypoints_and_knots

    path = np.array([HOME, HOME + [0.6, -0.3, 0.2, 0.0, 0.3, 0.5]])
    result = retime(plant, path, limits)
    waypoints, knots = path_waypoints_and_knots(path)
    held = held_object_of(scenario.object("carton_box"))
    saved = sample_trajectory(
        plant, result, held, None, scenario.cup, "carton_box", waypoints, knots
    )
    file = save_trajectory(tmp_path / "jerk.npz", saved)
    loaded = load_trajectory(file)
    np.testing.assert_array_equal(loaded.path_acceleration, result.path_acceleration)
    csv = export_trajectory(
        file, tmp_path / "jerk.csv", format="csv", period=0.004, plant=plant
    )
    table = np.loadtxt(csv, delimiter=",", skiprows=1)
    t = table[:, 0]
    inside = t <= result.duration
    q, qd, qdd = result.trajectory.sample(t[inside], order=2)
    np.testing.assert_allclose(table[inside, 1:7], q, atol=1e-9)
    np.testing.assert_allclose(table[inside, 7:13], qd, atol=1e-9)
    np.testing.assert_allclose(table[inside, 13:19], qdd, atol=1e-7)


def test_a_path_whose_curvature_jumps_is_refused(plant, limits):
    """Two rest-to-rest cubics joined at s = 0.5: q'' jumps there, so the
    joint acceleration would jump unless the motion stopped."""
    from pydrake.trajectories import CompositeTrajectory

    waypoints = [HOME, HOME + [0.4, 0, 0, 0, 0, 0], HOME + [0.8, 0, 0, 0, 0, 0]]
    pieces = [
        PiecewisePolynomial.CubicWithContinuousSecondDerivatives(
            [k, k + 1.0],
            np.column_stack(waypoints[k : k + 2]),
            np.zeros(6),
            np.zeros(6),
        )
        for k in range(2)
    ]
    path = CompositeTrajectory(pieces)
    with pytest.raises(RetimeInputError, match=r"q'' of joint 1 jumps .* s = 0\.5000"):
        retime(plant, path, limits)
    assert retime(plant, path, limits.without_jerk()).duration > 0.0


def test_c2_splines_with_uneven_knots_are_not_refused():
    """A very short piece makes q'' steep, not discontinuous: no false jump
    (on Table I, seed 0, MOVE 17 was refused before each side was
    extrapolated to the break)."""
    from rt_drake.retiming._jerk import check_smooth
    from rt_drake.retiming._joint_path import as_joint_path

    rng = np.random.default_rng(1)
    for _ in range(50):
        steps = rng.uniform(-0.5, 0.5, size=(rng.integers(2, 8), 6))
        steps[rng.integers(len(steps))] *= 1e-3  # one piece 1000x shorter
        check_smooth(as_joint_path(np.cumsum(np.vstack([HOME, steps]), axis=0)))
    # A last piece 1e6 times shorter (waypoints bunched at the end): its
    # third derivative is so large that the step^2 / 2 q''' term counts;
    # extrapolated by q'' alone, 43 of these 50 paths were refused ("q'
    # jumps").
    for _ in range(50):
        steps = rng.uniform(-0.5, 0.5, size=(rng.integers(2, 8), 6))
        steps[-1] *= 1e-6
        check_smooth(as_joint_path(np.cumsum(np.vstack([HOME, steps]), axis=0)))
