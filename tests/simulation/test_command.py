"""The arm's command sampled at the controller's period (``_command``)."""

from __future__ import annotations

import numpy as np
import pytest
from pydrake.trajectories import PiecewisePolynomial

from rt_drake.simulation._command import sampled_command

PERIOD = 0.008


def _quadratic() -> PiecewisePolynomial:
    """q(t) = (t^2, -3 t^2) on [0, 0.1]: constant acceleration (2, -6)."""
    times = np.linspace(0.0, 0.1, 6)
    q = np.vstack([times**2, -3 * times**2])
    # A clamped cubic spline reproduces a quadratic exactly.
    return PiecewisePolynomial.CubicWithContinuousSecondDerivatives(
        times, q, np.zeros((2, 1)), np.array([[0.2], [-0.6]])
    )


def test_command_interpolates_the_last_two_samples_one_period_late():
    trajectory = _quadratic()
    t = 0.05  # in [6T, 7T): samples q(5T) and q(6T)
    q, v, a = sampled_command(trajectory, t, PERIOD)
    q5, q6 = trajectory.value(5 * PERIOD).ravel(), trajectory.value(6 * PERIOD).ravel()
    alpha = (t - 6 * PERIOD) / PERIOD
    np.testing.assert_allclose(q, q5 + alpha * (q6 - q5), atol=1e-12)
    np.testing.assert_allclose(v, (q6 - q5) / PERIOD, atol=1e-9)
    # The second difference of samples of a quadratic is its acceleration.
    np.testing.assert_allclose(a, [2.0, -6.0], rtol=1e-6)


def test_command_is_continuous_and_comes_to_rest_after_the_end():
    trajectory = _quadratic()
    end = trajectory.end_time()
    before = sampled_command(trajectory, 7 * PERIOD - 1e-9, PERIOD)[0]
    after = sampled_command(trajectory, 7 * PERIOD, PERIOD)[0]
    np.testing.assert_allclose(before, after, atol=1e-6)
    q, v, a = sampled_command(trajectory, end + 3 * PERIOD, PERIOD)
    np.testing.assert_allclose(q, trajectory.value(end).ravel(), atol=1e-6)
    assert np.all(v == 0.0) and np.all(a == 0.0)


@pytest.mark.parametrize("t", [-0.02, 0.0])
def test_command_before_the_motion_holds_its_start(t):
    trajectory = _quadratic()
    q, v, _ = sampled_command(trajectory, t, PERIOD)
    np.testing.assert_allclose(q, trajectory.value(0.0).ravel(), atol=1e-12)
    assert np.all(v == 0.0)
