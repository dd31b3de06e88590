"""A piece ``[start, end]`` of a path, reparametrised to [0, 1], and its stop grid.

``sigma = (s - start) / L`` with ``L = end - start``: the sub-path is
``q(start + sigma L)``, its k-th derivative in sigma ``L^k d^k q / ds^k``;
a profile on it maps back by ``x_s = L^2 x_sigma`` (``x = s'^2``, 1/s^2)
and ``u_s = L u_sigma`` (``u = s''``).
"""

from __future__ import annotations

import numpy as np

from rt_drake.retiming._joint_path import JointPath
from rt_drake.retiming.grid import MIN_STEP

#: Uniform points, at least, of the grid of the sub-path a stop is retimed on
#: (with the retime's own grid points in it).
STOP_GRIDPOINTS = 30


def sub_path(spline: JointPath, start: float, end: float) -> JointPath:
    """``q(start + sigma (end - start))``, sigma in [0, 1], as a JointPath.

    Its derivatives in sigma are ``L^k d^k q / ds^k`` (``L = end - start``);
    its breaks are those of ``spline`` inside, mapped.
    """
    length = end - start
    inside = spline.breaks[(spline.breaks > start) & (spline.breaks < end)]
    breaks = np.concatenate([[0.0], (inside - start) / length, [1.0]])

    def evaluate(sigma: np.ndarray, order: int) -> np.ndarray:
        s = np.minimum(start + sigma * length, end)
        return spline(s, order) * length**order

    return JointPath(evaluate, breaks, spline.cubic, spline.num_joints)


def stop_grid(own: np.ndarray, start: float, length: float) -> np.ndarray:
    """Grid in sigma of a stop from ``start`` over ``length``.

    :data:`STOP_GRIDPOINTS` uniform points and the motion's own grid points
    ``own`` (in s) inside, none closer than ``MIN_STEP``; it ends at 1.
    """
    own = np.asarray(own, dtype=float)
    own = (own[(own > start) & (own < start + length)] - start) / length
    grid = np.unique(np.concatenate([np.linspace(0, 1, STOP_GRIDPOINTS), own]))
    grid = grid[np.concatenate([[True], np.diff(grid) > MIN_STEP])]
    grid[-1] = 1.0
    return grid


__all__ = ["STOP_GRIDPOINTS", "stop_grid", "sub_path"]
