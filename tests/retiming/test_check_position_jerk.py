"""check_trajectory knows the plant's position limits and, when given, the jerk.

References are closed forms: a sine's peak position and its jerk amplitude
``A w^3``; a TOPP-RA profile's acceleration jumps at its grid points.
"""

from __future__ import annotations

import numpy as np
import pytest
from pydrake.trajectories import PiecewisePolynomial

from rt_drake.retiming import JointLimits, Margin, check_trajectory, retime

HOME = np.array([0.0, 0.35, 1.75, 0.0, 1.04, 0.0])


def _sine(amplitude: float, omega: float, joint: int, duration: float):
    """q_j(t) = HOME_j + A sin(w t) as a dense cubic Hermite PiecewisePolynomial."""
    t = np.linspace(0.0, duration, 4001)
    q = np.tile(HOME, (len(t), 1))
    v = np.zeros_like(q)
    q[:, joint] += amplitude * np.sin(omega * t)
    v[:, joint] = amplitude * omega * np.cos(omega * t)
    return PiecewisePolynomial.CubicHermite(t, q.T, v.T)


@pytest.fixture(scope="module")
def limits(plant, scenario):
    return JointLimits.from_plant(plant, scenario.robot)


def test_a_slow_motion_beyond_joint_1s_limit_fails_naming_it(plant, limits):
    upper = plant.GetPositionUpperLimits()[0]
    amplitude = upper + 2.0  # peaks 2 rad beyond the upper limit at t = 5 s
    omega = np.pi / 10.0
    check = check_trajectory(plant, _sine(amplitude, omega, 0, 10.0), limits)
    position = check.margins[Margin.POSITION]
    assert not check.passed()
    assert position.index == 0
    assert position.time == pytest.approx(5.0, abs=1e-3)
    half = 0.5 * (upper - plant.GetPositionLowerLimits()[0])
    assert position.value == pytest.approx(1.0 - amplitude / half, abs=1e-6)
    words = check.summary()
    assert f"{amplitude:.4f} rad, limit {upper:.4f} rad" in words
    assert "joint 1" in words and "t = 5.0000 s" in words
    # The joint limits alone are far from binding on so slow a motion.
    assert check.margins[Margin.VELOCITY].value > 0.5


def test_a_motion_inside_the_position_limits_passes(plant, limits):
    check = check_trajectory(plant, _sine(1.0, np.pi / 10.0, 0, 10.0), limits)
    assert check.passed()
    lower, upper = plant.GetPositionLowerLimits(), plant.GetPositionUpperLimits()
    peak = HOME + [1.0, 0, 0, 0, 0, 0]  # every joint's farthest position
    ratio = np.abs(peak - 0.5 * (lower + upper)) / (0.5 * (upper - lower))
    assert check.margins[Margin.POSITION].value == pytest.approx(
        1.0 - ratio.max(), abs=1e-6
    )


@pytest.mark.parametrize(("factor", "passes"), [(1.01, True), (0.98, False)])
def test_the_jerk_of_a_sine_is_checked_against_its_amplitude(
    plant, limits, factor, passes
):
    amplitude, omega = 0.5, 6.0
    peak = amplitude * omega**3  # |q'''| = A w^3 |cos(w t)|
    jerk = np.full(6, 1e6)
    jerk[2] = factor * peak
    limited = JointLimits(limits.velocity * 10, limits.acceleration * 10, jerk=jerk)
    check = check_trajectory(plant, _sine(amplitude, omega, 2, 2.0), limited)
    assert Margin.JERK in check.margins
    assert check.passed() is passes
    assert check.margins[Margin.JERK].index == 2
    assert check.margins[Margin.JERK].value == pytest.approx(
        1.0 - 1.0 / factor, abs=2e-3
    )
    assert "rad/s^3" in check.summary()


def test_topp_ra_acceleration_jumps_break_a_jerk_limit(plant, limits):
    path = np.array([HOME, HOME + [0.8, -0.2, 0.3, 0.0, 0.2, 0.5]])
    result = retime(plant, path, limits)
    free = check_trajectory(plant, result.trajectory, limits)
    assert Margin.JERK not in free.margins and free.passed()
    jerk = dataclass_jerk(limits, 50.0)
    check = check_trajectory(plant, result.trajectory, jerk)
    # A jump of the acceleration of size a in one 1 ms step reads a / 1e-3.
    assert check.margins[Margin.JERK].value < -1.0
    assert not check.passed()


def dataclass_jerk(limits: JointLimits, per_second: float) -> JointLimits:
    """``limits`` with jerk limits of ``per_second`` times the accelerations."""
    return JointLimits(
        limits.velocity,
        limits.acceleration,
        limits.torque,
        per_second * limits.acceleration,
    )


def test_jerk_limits_are_checked_like_the_others(limits):
    from rt_drake.retiming import RetimeInputError

    with pytest.raises(RetimeInputError, match="jerk limits must be > 0"):
        JointLimits(limits.velocity, limits.acceleration, jerk=np.zeros(6))
    with pytest.raises(RetimeInputError, match="jerk 5"):
        JointLimits(limits.velocity, limits.acceleration, jerk=np.ones(5))
