"""rt_drake.retiming: protective stops along the path, grasp-aware and joint-brake.

References independent of the stop code: the dense 1 kHz check (Drake's
Newton-Euler, not the retimer's coefficients), the path spline rebuilt with
scipy, a HiGHS LP over the whole stop profile (the shortest stop distance on
the grid), and the closed-form bang-bang stop on a straight joint-space line.
"""

from __future__ import annotations

import numpy as np
import pytest
from grasp_paths import BACK, HOME
from pydrake.trajectories import PiecewisePolynomial
from scipy.optimize import linprog
from stop_helpers import (
    assert_at_rest_on_back,
    back_spline,
    notebook_fixtures,
)

from rt_drake.dynamics.cup_frame import CupFrame
from rt_drake.dynamics.wrench import path_wrench_coefficients
from rt_drake.retiming import (
    JointLimits,
    Margin,
    PathNotControllableError,
    RetimeInputError,
    StopNotFoundError,
    check_trajectory,
    joint_brake_stop,
    protective_stop,
    retime,
)
from rt_drake.retiming._joint_path import as_joint_path
from rt_drake.retiming._samples import sample_path
from rt_drake.retiming._stop import state_at
from rt_drake.retiming._stop_pass import grid_constraints, stop_pass

#: Fractions of the MOVE's duration at which the stops begin.
FRACTIONS = (0.15, 0.45)


limits, grasp, move = notebook_fixtures(jerk=False)


@pytest.mark.parametrize("fraction", FRACTIONS)
def test_a_grasp_aware_stop_rests_on_the_path_inside_every_limit(
    plant, limits, grasp, move, fraction
):
    t = fraction * move.duration
    stop = protective_stop(plant, BACK, limits, move, t, grasp)
    whole = stop.trajectory
    assert stop.duration > 0.0 and stop.s_stop > stop.s_start
    assert whole.end_time() == pytest.approx(stop.end_time, abs=1e-9)
    # Up to t, the retimed MOVE itself.
    before = np.linspace(move.trajectory.start_time(), t, 50)
    for tk in before:
        assert np.allclose(whole.value(tk), move.trajectory.value(tk), atol=1e-9)
        assert np.allclose(
            whole.EvalDerivative(tk, 1), move.trajectory.EvalDerivative(tk, 1),
            atol=1e-7,
        )  # fmt: skip
    # At rest on the path (a spline built apart), every sample of it on the path.
    assert_at_rest_on_back(whole, stop.s_stop, t, at_rest=1e-9)
    end = whole.end_time()
    # Every limit and the grasp.
    check = check_trajectory(plant, whole, limits, grasp)
    assert check.passed(), check.summary()
    # The stop alone is the whole motion from t on.
    alone = stop.stop
    assert alone.start_time() == pytest.approx(t, abs=1e-9)
    assert alone.end_time() == pytest.approx(end, abs=1e-9)
    for tk in np.linspace(t, end, 7):
        assert np.allclose(alone.value(tk), whole.value(tk), atol=1e-9)


def test_the_joint_brake_stop_is_shorter_and_leaves_the_grasp_set(
    plant, limits, grasp, move
):
    t = FRACTIONS[1] * move.duration
    held = protective_stop(plant, BACK, limits, move, t, grasp)
    brake = joint_brake_stop(plant, BACK, limits, move, t)
    assert brake.duration < held.duration and brake.s_stop < held.s_stop
    joints = check_trajectory(plant, brake.trajectory, limits)
    assert joints.passed(), joints.summary()
    # Some joint brakes at its acceleration limit.
    assert joints.margins[Margin.ACCELERATION].value < 0.01
    with_grasp = check_trajectory(plant, brake.stop, limits, grasp)
    assert with_grasp.margins[Margin.GRASP].value < -0.05


def _lp_reaches_rest(s, dq, ddq, wrench, limits, F, g, x_start, index):
    """HiGHS: is there a profile from x_start at s_0 to rest at s_index?

    Variables x_0..x_index; ``u_i = (x_{i+1} - x_i) / (2 ds_i)``; at every
    grid point the joint velocity, acceleration and grasp rows with the u of
    the segments on either side (TOPP-RA's interpolation discretization).
    """
    a, b, c = wrench
    count = index + 1
    rows, bounds = [], []
    for i in range(index):
        u = np.zeros(count)
        u[i], u[i + 1] = -1.0 / (2 * (s[i + 1] - s[i])), 1.0 / (2 * (s[i + 1] - s[i]))
        for j in (i, i + 1):
            x = np.zeros(count)
            x[j] = 1.0
            accel = dq[j][:, None] * u + ddq[j][:, None] * x  # (n, count)
            rows += [accel, -accel]
            bounds += [limits.acceleration, limits.acceleration]
            rows.append(F @ (a[j][:, None] * u + b[j][:, None] * x))
            bounds.append(g - F @ c[j])
    with np.errstate(divide="ignore"):
        cap = np.min(limits.velocity**2 / dq[:count] ** 2, axis=1)
    box = [(x_start, x_start)]
    box += [(0.0, min(hi, 1e6)) for hi in cap[1:-1]] + [(0.0, 0.0)]
    answer = linprog(
        np.zeros(count),
        A_ub=np.vstack(rows),
        b_ub=np.concatenate(bounds),
        bounds=box,
        method="highs",
    )
    return answer.status == 0


def test_the_maximal_braking_pass_finds_the_nearest_rest_an_lp_finds(
    plant, limits, grasp, move
):
    spline = back_spline()
    context = plant.CreateDefaultContext()
    cup = CupFrame.of(plant)
    for fraction in FRACTIONS:
        s_t, sd_t = state_at(move, fraction * move.duration)
        s = np.concatenate([[s_t], move.gridpoints[move.gridpoints > s_t + 1e-9]])
        samples = sample_path(
            plant, as_joint_path(BACK), s, limits.velocity, False, grasp.held,
            context, cup,
        )  # fmt: skip
        braking = stop_pass(
            grid_constraints(samples, limits, grasp.F, grasp.g), s, sd_t**2
        )
        index = braking.stop_index
        assert index is not None and index >= 2
        # The LP's own path derivatives and wrench (Drake's general route).
        q, dq, ddq = spline(s), spline(s, 1), spline(s, 2)
        wrench = path_wrench_coefficients(plant, grasp.held, q, dq, ddq, context, cup)
        lp = (s, dq, ddq, wrench, limits, grasp.F, grasp.g, sd_t**2)
        assert _lp_reaches_rest(*lp, index)
        assert not _lp_reaches_rest(*lp, index - 1)


def test_a_straight_line_brakes_in_the_closed_form_time(plant, limits):
    """q(s) = q0 + s d: rest in exactly v^2 / (2 a) along s, in v / a."""
    d = np.array([0.6, -0.3, 0.4, 0.2, -0.5, 0.7])
    q0 = HOME - 0.3 * d
    line = PiecewisePolynomial.FirstOrderHold([0.0, 1.0], np.column_stack([q0, q0 + d]))
    move = retime(plant, line, limits, gridpoints=400)
    a_path = np.min(limits.acceleration / np.abs(d))
    v_path = np.min(limits.velocity / np.abs(d))
    for fraction in (0.2, 0.5):
        stop = joint_brake_stop(plant, line, limits, move, fraction * move.duration)
        v = stop.sd_start
        shortest = v * v / (2.0 * a_path)
        travelled = stop.s_stop - stop.s_start
        # The finer braking pass ends within a quarter step (two at most, if
        # the retime of the sub-path needs the next point).
        step = np.diff(move.gridpoints).max()
        assert shortest - 1e-9 <= travelled <= shortest + 0.5 * step + 1e-9
        # Bang-bang from v to rest over exactly that distance.
        peak = min(np.sqrt(a_path * travelled + 0.5 * v * v), v_path)
        cruise = (travelled - (2 * peak**2 - v * v) / (2 * a_path)) / peak
        expected = (2 * peak - v) / a_path + cruise
        assert stop.duration == pytest.approx(expected, rel=2e-3)


@pytest.mark.parametrize(
    "t,words",
    [
        (float("nan"), ["t must be a finite number", "nan"]),
        (-0.5, ["t = -0.5 s is outside the trajectory"]),
        (99.0, ["t = 99.0 s is outside the trajectory"]),
        ("now", ["t must be a finite number", "'now'"]),
    ],
)
def test_a_bad_instant_is_refused_in_one_line(plant, limits, grasp, move, t, words):
    for stop in (
        lambda: protective_stop(plant, BACK, limits, move, t, grasp),
        lambda: joint_brake_stop(plant, BACK, limits, move, t),
    ):
        with pytest.raises(RetimeInputError) as info:
            stop()
        message = str(info.value)
        assert "\n" not in message
        for word in words:
            assert word in message, message


def test_at_the_ends_the_robot_is_already_at_rest(plant, limits, grasp, move):
    for t in (move.trajectory.start_time(), move.trajectory.end_time()):
        stop = protective_stop(plant, BACK, limits, move, t, grasp)
        assert stop.duration == 0.0 and stop.s_stop == stop.s_start
        end = stop.trajectory.end_time()
        assert np.abs(stop.trajectory.EvalDerivative(end, 1)).max() == 0.0


@pytest.mark.parametrize("offset", [1e-6, -1e-6])
def test_a_stop_a_microsecond_from_either_end_rests_within_the_limits(
    plant, limits, grasp, move, offset
):
    times = move.trajectory.times
    t = (times[0] if offset > 0 else times[-1]) + offset
    stop = protective_stop(plant, BACK, limits, move, t, grasp)
    whole = stop.trajectory
    assert 0.0 < stop.duration < 0.05 and stop.sd_start > 0.0
    assert whole.start_time() == pytest.approx(times[0], abs=1e-12)
    assert np.allclose(whole.value(t), move.trajectory.value(t), atol=1e-12)
    end = whole.end_time()
    assert np.abs(whole.EvalDerivative(end, 1)).max() < 1e-9
    check = check_trajectory(plant, stop.stop, limits, grasp, rate_hz=1e5)
    assert check.passed(), check.summary()


def test_a_state_beyond_the_limits_has_no_stop_and_says_so(plant, limits, grasp):
    """A MOVE retimed under twice the joint limits, stopped under the real
    ones where it runs 20 % and more above a velocity limit: no admissible profile
    starts there, so no stop exists."""
    fast = JointLimits(2.0 * limits.velocity, 2.0 * limits.acceleration)
    move = retime(plant, BACK, fast)
    samples = np.linspace(0.3, 0.7, 9) * move.duration
    speeds = [
        np.max(np.abs(move.trajectory.EvalDerivative(t, 1).ravel()) / limits.velocity)
        for t in samples
    ]
    t = float(samples[int(np.argmax(speeds))])
    assert max(speeds) > 1.2  # above what the real limits allow at all
    with pytest.raises(StopNotFoundError) as info:
        protective_stop(plant, BACK, limits, move, t, grasp)
    message = str(info.value)
    assert "\n" not in message and f"t = {t:.4f} s" in message
    assert "no stop to rest within the path" in message


def test_no_later_stop_point_is_reached_sooner(plant, limits, grasp, move):
    """The retimer itself, on sub-paths built apart (Drake cubic Hermite
    pieces of the scipy spline, exact), from the state at t to rest at
    points beyond the stop's: none is faster than the stop."""
    spline = back_spline()
    t = FRACTIONS[1] * move.duration
    stop = protective_stop(plant, BACK, limits, move, t, grasp)
    reached = 0
    for extra in (0.01, 0.03, 0.06, 0.1):
        end = stop.s_stop + extra
        breaks = np.unique(
            np.concatenate([[stop.s_start, end], spline.x[spline.x > stop.s_start]])
        )
        breaks = breaks[breaks <= end]
        sub = PiecewisePolynomial.CubicHermite(
            breaks, spline(breaks).T, spline(breaks, 1).T
        )
        length = end - stop.s_start
        try:
            later = retime(
                plant, sub, limits, grasp, 60, sd_start=stop.sd_start / length
            )
        except PathNotControllableError:
            continue
        reached += 1
        assert later.duration >= stop.duration * (1.0 - 1e-3), (extra, later.duration)
    assert reached >= 2
