"""The grid's segments at their sub-points, where limits are looked at.

Segment i runs from ``s_i`` to ``s_{i+1}`` (inside one cubic piece of the
path, :mod:`.grid`); its sub-points are ``s_i + theta ds_i`` at theta = 1/8,
2/8, ..., 7/8 (:data:`SUBPOINTS`), where ``x(s) = x_i + 2 theta ds_i u_i``
(``x = s'^2``, u the segment's constant ``s''``). :class:`Segments` holds
q'(s), q''(s) there and the Lagrange stencils that interpolate torque and
wrench coefficients from up to four grid points of the same cubic piece
(smooth there: the error, fourth order in the step, is far below the
overshoot looked for, and it costs no Drake call).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from rt_drake.dynamics.wrench import PathCoefficients
from rt_drake.retiming import _between_kernels as K
from rt_drake.retiming._joint_path import JointPath
from rt_drake.retiming._samples import PathSamples
from rt_drake.retiming.seidel import kernel_array

#: Interior points per segment: theta = 1/8, 2/8, ..., 7/8.
SUBPOINTS = 7
#: theta of each sub-point.
THETA = np.arange(1, SUBPOINTS + 1) / (SUBPOINTS + 1)
#: The sub-point at the segment's midpoint (theta = 1/2).
MIDDLE = 3


class Segments:
    """The grid's segments at their sub-points: path derivatives, stencils.

    Built once per grid (it does not depend on the profile). For a cubic
    path q' and q'' at the sub-points follow from their grid values; for
    another path they are evaluated.

    Attributes:
        s: (G,) grid; ds: (N,) steps.
        dq, ddq: (N, K, n) q'(s), q''(s) at the sub-points.
    """

    def __init__(
        self, samples: PathSamples, knots: np.ndarray, path: JointPath
    ) -> None:
        self.s = samples.s
        self.ds = np.diff(self.s)
        count, n = len(self.ds), samples.dq.shape[1]
        if path.cubic:  # exact from the grid values (q'' linear per segment)
            self.dq = np.empty((count, len(THETA), n))
            self.ddq = np.empty((count, len(THETA), n))
            K.sub_derivatives(
                kernel_array(samples.dq),
                kernel_array(samples.ddq),
                self.ds,
                THETA,
                self.dq,
                self.ddq,
            )
        else:
            points = self.s[:-1, None] + THETA * self.ds[:, None]
            self.dq = kernel_array(path(points, 1))
            self.ddq = kernel_array(path(points, 2))
        self.step = 2.0 * THETA * self.ds[:, None]  # x(s) = x_i + step u_i
        self.index, self.weights = _lagrange(self.s, knots)

    def enforced_wrenches(
        self, wrench: PathCoefficients, x: np.ndarray, u: np.ndarray
    ) -> np.ndarray:
        """The (3N + 1, 6) wrenches the stage LPs enforce.

        At every grid point, both ends of every segment and its midpoint
        (interpolated), see :func:`._between_kernels.enforced_wrenches`; the
        exactness check evaluates every grasp row at them.
        """
        count = len(self.ds)
        out = np.empty((3 * count + 1, 6))
        K.enforced_wrenches(
            *(kernel_array(v) for v in wrench),
            kernel_array(x),
            kernel_array(u),
            self.s,
            self.weights,
            self.index,
            MIDDLE,
            out,
        )
        return out

    def interpolate(self, values: np.ndarray, point: int | None = None) -> np.ndarray:
        """(G, m) values at the grid points -> (N, K, m) at the sub-points.

        With ``point``, only at that sub-point: (N, m).
        """
        if point is None:
            return np.matmul(self.weights, values[self.index])
        return np.einsum("nj,njm->nm", self.weights[:, point], values[self.index])


def subpoint_x(segments: Segments, x: np.ndarray, u: np.ndarray) -> np.ndarray:
    """(N, K) ``x = s'^2`` at the sub-points: ``x_i + 2 theta ds_i u_i`` (>= 0)."""
    return np.maximum(x[:-1, None] + segments.step * u[:, None], 0.0)


def _lagrange(s: np.ndarray, knots: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Interpolation at the sub-points from grid points of one cubic piece.

    Segment i uses up to four consecutive grid points around it, all within
    the piece that holds it (its bounding knots, if they are grid points;
    else the whole path).

    Returns:
        index: (N, 4) grid points used; weights: (N, K, 4) Lagrange weights
        (0 for the slots a short piece leaves unused).
    """
    count = len(s) - 1
    on_grid = np.searchsorted(s, knots).clip(0, len(s) - 1)
    on_grid = on_grid[np.abs(s[on_grid] - knots) <= 1e-12]
    bounds = np.unique(np.concatenate([[0, count], on_grid]))
    piece = np.searchsorted(bounds, np.arange(count), side="right") - 1
    index = np.empty((count, 4), dtype=np.int64)
    weights = np.empty((count, len(THETA), 4))
    _lagrange_kernel(
        kernel_array(s),
        bounds[piece].astype(np.int64),
        bounds[piece + 1].astype(np.int64),
        THETA,
        index,
        weights,
    )
    return index, weights


@njit(cache=True)
def _lagrange_kernel(s, low, high, theta, index, weights):  # noqa: D417
    """Fill ``index`` (N, 4) and ``weights`` (N, K, 4) (see :func:`_lagrange`).

    ``w_k(t) = prod_{m != k} (t - t_m) / (t_k - t_m)`` over the nodes of the
    piece; unused slots (a piece with fewer than four points) get weight 0.
    """
    for i in range(index.shape[0]):
        size = min(4, high[i] - low[i] + 1)
        start = min(max(i - 1, low[i]), high[i] - size + 1)
        for k in range(4):
            index[i, k] = min(start + k, high[i])
        for j in range(theta.shape[0]):
            t = s[i] + theta[j] * (s[i + 1] - s[i])
            for k in range(4):
                if k >= size:
                    weights[i, j, k] = 0.0
                    continue
                w = 1.0
                for m in range(size):
                    if m != k:
                        t_k, t_m = s[index[i, k]], s[index[i, m]]
                        w *= (t - t_m) / (t_k - t_m)
                weights[i, j, k] = w


__all__ = ["MIDDLE", "SUBPOINTS", "THETA", "Segments", "subpoint_x"]
