"""rt_drake.retiming: protective stops under jerk limits.

References independent of the stop code: the joint jerk by finite
differences of the 1 kHz samples' accelerations, the path spline rebuilt
with scipy, Drake's Newton-Euler wrench (``check_trajectory``) and, on a
straight joint-space line, the closed-form time-optimal jerk-limited stop of
a triple integrator (ramp the acceleration down at the jerk limit, hold it at
the acceleration limit, ramp it back to 0).
"""

from __future__ import annotations

import numpy as np
import pytest
from grasp_paths import BACK, HOME
from pydrake.trajectories import PiecewisePolynomial
from stop_helpers import (
    assert_at_rest_on_back,
    jerk_by_differences,
    notebook_fixtures,
)

from rt_drake.retiming import (
    Margin,
    check_trajectory,
    joint_brake_stop,
    protective_stop,
    retime,
)
from rt_drake.retiming._stop import path_state_at

limits, grasp, move = notebook_fixtures(jerk=True)


def test_a_jerk_limited_stop_rests_on_the_path_in_the_grasp_set(
    plant, limits, grasp, move
):
    """At 15 % the MOVE accelerates, the grasp bound (by 6e-5 over, inside
    the contract, between grid points): the stop starts from there."""
    t = 0.15 * move.duration
    stop = protective_stop(plant, BACK, limits, move, t, grasp)
    whole = stop.trajectory
    assert 0.0 < stop.duration and stop.s_start < stop.s_stop < 1.0
    # It starts from the MOVE's own state at t: q, q', q'' continuous.
    for order in (0, 1, 2):
        np.testing.assert_allclose(
            stop.stop.EvalDerivative(t, order),
            move.trajectory.EvalDerivative(t, order),
            atol=1e-7,
        )
    # At rest (q' and q''), on the path (a spline built apart), at s_stop.
    end = whole.end_time()
    assert end == pytest.approx(t + stop.duration, abs=1e-9)
    assert np.abs(whole.EvalDerivative(end, 2)).max() < 1e-6
    assert_at_rest_on_back(whole, stop.s_stop, t, at_rest=1e-6)
    # Every limit and the grasp at 1 kHz, the whole motion through t.
    check = check_trajectory(plant, whole, limits, grasp)
    assert check.passed(), check.summary()
    jerk = jerk_by_differences(whole, whole.start_time(), end)
    assert np.max(np.abs(jerk) / limits.jerk) <= 1.0 + 1e-3


def test_the_jerk_limited_joint_brake_leaves_the_grasp_set_where_it_binds(
    plant, limits, grasp, move
):
    t = 0.45 * move.duration
    held = protective_stop(plant, BACK, limits, move, t, grasp)
    brake = joint_brake_stop(plant, BACK, limits, move, t)
    assert brake.duration < held.duration and brake.s_stop < held.s_stop
    joints = check_trajectory(plant, brake.trajectory, limits)
    assert joints.passed(), joints.summary()
    jerk = jerk_by_differences(brake.trajectory, t - 0.05, brake.end_time)
    assert np.max(np.abs(jerk) / limits.jerk) <= 1.0 + 1e-3
    thrown = check_trajectory(plant, brake.stop, limits, grasp)
    assert thrown.margins[Margin.GRASP].value < -0.05
    kept = check_trajectory(plant, held.stop, limits, grasp)
    assert kept.margins[Margin.GRASP].value >= -1e-3


def _closed_form_stop(v: float, a: float, amax: float, jmax: float) -> float:
    """Time-optimal stop of s''' in [-J, J], |s''| <= A from (v > 0, a) to rest.

    The acceleration ramps from a down to a_min at -J, stays, then ramps to 0
    at +J; the velocity lost, ``(a^2 - 2 a_min^2) / (2 J) + a_min T2 = -v``.
    """
    low = -np.sqrt(0.5 * a * a + jmax * v)
    hold = 0.0
    if low < -amax:
        low = -amax
        hold = (v + (a * a - 2.0 * amax**2) / (2.0 * jmax)) / amax
    return (a - low) / jmax + hold - low / jmax


def test_a_straight_line_stops_in_the_closed_form_jerk_limited_time(plant, limits):
    """q(s) = q0 + s d: the path's own velocity, acceleration and jerk limits
    are the tightest joint's, ``min_j limit_j / |d_j|``."""
    d = np.array([0.6, -0.3, 0.4, 0.2, -0.5, 0.7])
    q0 = HOME - 0.3 * d
    line = PiecewisePolynomial.FirstOrderHold([0.0, 1.0], np.column_stack([q0, q0 + d]))
    move = retime(plant, line, limits)
    a_path = np.min(limits.acceleration / np.abs(d))
    j_path = np.min(limits.jerk / np.abs(d))
    for fraction in (0.3, 0.5):
        t = fraction * move.duration
        _, v, a = path_state_at(move, t)
        stop = joint_brake_stop(plant, line, limits, move, t)
        expected = _closed_form_stop(v, a, a_path, j_path)
        # No faster than the optimum (the 1e-3 contract), within 3 % of it.
        assert expected * (1.0 - 1e-3) <= stop.duration <= 1.03 * expected
        check = check_trajectory(plant, stop.trajectory, limits)
        assert check.passed(), check.summary()


def test_at_and_next_to_the_ends_a_jerk_limited_stop_is_at_rest_or_the_move(
    plant, limits, grasp, move
):
    start, end = move.trajectory.start_time(), move.trajectory.end_time()
    for t in (start, start + 1e-6, end - 1e-6, end):
        stop = protective_stop(plant, BACK, limits, move, t, grasp)
        assert stop.duration <= 1e-5
        assert np.abs(stop.stop.EvalDerivative(stop.end_time, 1)).max() < 1e-6
        check = check_trajectory(plant, stop.trajectory, limits, grasp)
        assert check.passed(), check.summary()
