"""When a retimed motion passes a point of its path, and its grid's times."""

from __future__ import annotations

import numpy as np

from rt_drake.retiming import JerkTimedPath, RetimeResult, TimedPath


def grid_times(trajectory: object) -> np.ndarray | None:
    """Times (s) at which a retimed motion passes its grid points.

    There its acceleration may jump (TOPP-RA's piecewise-constant s''); None
    for a motion without a grid.
    """
    if isinstance(trajectory, TimedPath | JerkTimedPath):
        return trajectory.times
    return None


def time_at(result: RetimeResult, s: float) -> float:
    """Time (s) at which the retimed motion reaches path parameter ``s``.

    On grid segment i (``s_i <= s <= s_{i+1}``) the path acceleration u_i is
    constant, so with ``d = s - s_i``: ``tau = 2 d / (s'_i + sqrt(s'_i^2 +
    2 u_i d))``, after ``t_i = sum_{k<i} 2 ds_k / (s'_k + s'_{k+1})``.
    Jerk-limited (u continuous, not constant): at a grid point (a path knot,
    such as the pick's approach pose) the time the motion passes it, else
    :meth:`~rt_drake.retiming.JerkTimedPath.time_at` (bisection: 10 ms).
    """
    if isinstance(result.trajectory, JerkTimedPath):
        grid = result.gridpoints
        i = int(np.argmin(np.abs(grid - s)))
        if abs(grid[i] - s) <= 1e-12:
            return float(result.trajectory.times[i])
        return result.trajectory.time_at(s)
    grid, sd, sdd = result.gridpoints, result.sd, result.sdd
    i = int(np.clip(np.searchsorted(grid, s, side="right") - 1, 0, len(grid) - 2))
    dt = 2.0 * np.diff(grid) / (sd[:-1] + sd[1:])
    d = s - grid[i]
    root = np.sqrt(max(sd[i] ** 2 + 2.0 * sdd[i] * d, 0.0))
    tau = 2.0 * d / (sd[i] + root) if sd[i] + root > 0.0 else 0.0
    return float(result.trajectory.start_time() + dt[:i].sum() + tau)


__all__ = ["grid_times", "time_at"]
