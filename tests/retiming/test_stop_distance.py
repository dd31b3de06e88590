"""rt_drake.retiming._stop_distance: the 1-D jerk-limited stop against Ruckig.

Ruckig (velocity interface, target v = a = 0, one axis) computes the
time-optimal jerk-limited stop on its own; its position at the end is the
stop's distance.
"""

from __future__ import annotations

import numpy as np
import pytest
from ruckig import ControlInterface, InputParameter, Result, Ruckig, Trajectory

from rt_drake.retiming import JointLimits
from rt_drake.retiming._samples import PathSamples
from rt_drake.retiming._stop_distance import axis_stop_distance, braking_distance


def _ruckig_distance(v: float, a0: float, a: float, j: float) -> float:
    otg, inp, out = Ruckig(1), InputParameter(1), Trajectory(1)
    inp.control_interface = ControlInterface.Velocity
    inp.current_position, inp.current_velocity = [0.0], [v]
    inp.current_acceleration = [a0]
    inp.target_velocity, inp.target_acceleration = [0.0], [0.0]
    inp.max_velocity, inp.max_acceleration, inp.max_jerk = [1e3], [a], [j]
    assert otg.calculate(inp, out) == Result.Working
    position, _, _ = out.at_time(out.duration)
    return float(position[0])


@pytest.mark.parametrize("seed", range(3))
def test_the_axis_stop_distance_is_ruckigs(seed):
    rng = np.random.default_rng(seed)
    for _ in range(40):
        a, j = rng.uniform(2.0, 20.0), rng.uniform(20.0, 400.0)
        v, a0 = rng.uniform(0.05, 3.0), rng.uniform(-1.0, 1.0) * a
        if a0 < 0.0 and v < a0 * a0 / (2.0 * j):
            continue  # no stop without reversing: outside the model
        expected = _ruckig_distance(v, a0, a, j)
        assert axis_stop_distance(v, a0, a, j) == pytest.approx(expected, rel=1e-6)


def test_at_rest_the_distance_is_zero():
    assert axis_stop_distance(0.0, 0.0, 5.0, 50.0) == 0.0


def test_the_simulated_braking_on_a_straight_line_is_the_closed_form():
    """q(s) = q0 + s d: q'' = q''' = 0, so the path's acceleration and jerk
    bounds are the tightest joint's, ``min_j limit_j / |d_j|``, and the
    simulation (steps of 2 ms) lands on the closed-form distance."""
    d = np.array([0.6, -0.3, 0.4, 0.2, -0.5, 0.7])
    acceleration = np.array([3.0, 3.0, 4.0, 5.0, 5.0, 6.0])
    limits = JointLimits(np.full(6, 3.0), acceleration, jerk=20.0 * acceleration)
    s = np.linspace(0.0, 1.0, 101)
    samples = PathSamples(
        s=s,
        q=s[:, None] * d,
        dq=np.tile(d, (len(s), 1)),
        ddq=np.zeros((len(s), 6)),
        x_cap=np.full(len(s), np.inf),
        torque=None,
        wrench=None,
    )
    a = float(np.min(acceleration / np.abs(d)))
    j = float(np.min(limits.jerk / np.abs(d)))
    for v, a0 in ((1.0, 0.0), (2.0, 0.5 * a), (1.5, -0.5 * a)):
        expected = axis_stop_distance(v, a0, a, j)
        got = braking_distance(
            samples, np.zeros((len(s), 6)), limits, None, None, v, a0
        )
        assert got == pytest.approx(expected, rel=0.02)
