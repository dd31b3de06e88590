"""The arm's command as a real controller receives it: samples every period.

With ``robot.command_period_s`` = T (e.g. 8 ms, Denso b-CAP slave mode), the
controller gets the motion's position q(kT) at each tick t_k = kT and, over
the next period, moves linearly from the previous sample to the newest one
(position streaming: it can only interpolate toward a sample it has
received, so the command lags one period). For t in [t_k, t_k + T) with
``alpha = (t - t_k) / T``:

    q_cmd = q_{k-1} + alpha (q_k - q_{k-1})
    v_cmd = (q_k - q_{k-1}) / T
    a_cmd = (q_k - 2 q_{k-1} + q_{k-2}) / T^2   (the feedforward: the mean
            acceleration over the last two periods, held)

with ``q_j = q(clamp(jT, 0, t_end))``; before the motion and after its end
the samples are its end points, so the command's velocity is zero from one
period after the motion's end and its acceleration from two. Linear
interpolation is what a position-streaming interface does between
set-points; its velocity steps every period are far above the bellows' and
arm's modes (125 Hz against 5-10 Hz).
"""

from __future__ import annotations

import math

import numpy as np
from pydrake.trajectories import Trajectory


def sampled_command(
    trajectory: Trajectory, t: float, period: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Return (q, v, a) commanded at motion time ``t`` (s) (module docstring)."""
    k = math.floor(t / period + 1e-9)
    end = trajectory.end_time()

    def sample(j: int) -> np.ndarray:
        return trajectory.value(min(max(j * period, 0.0), end)).ravel()

    q_k, q_1, q_2 = sample(k), sample(k - 1), sample(k - 2)
    alpha = (t - k * period) / period
    q = q_1 + alpha * (q_k - q_1)
    v = (q_k - q_1) / period
    a = (q_k - 2.0 * q_1 + q_2) / period**2
    return q, v, a


__all__ = ["sampled_command"]
