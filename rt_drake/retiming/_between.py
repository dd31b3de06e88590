"""What a retimed profile does between two grid points, and how to hold it.

Within segment i (from ``s_i`` to ``s_{i+1}``, inside one cubic piece of the
path, see :mod:`.grid`) the motion has the constant path acceleration ``u_i``
and ``x(s) = x_i + 2 u_i (s - s_i)``. At the point ``s = s_i + theta ds_i``
the constraints read, in the stage's own variables (u_i, x_i),

- joint velocity ``q'_j(s)^2 (x_i + 2 theta ds_i u_i) <= v_j^2``,
- joint acceleration ``|(q'_j(s) + 2 theta ds_i q''_j(s)) u_i + q''_j(s) x_i|
  <= a_j``,
- joint torque ``|a_j(s) u_i + b_j(s) x(s) + c_j(s)| <= tau_j``,
- grasp ``F_k (a(s) u_i + b(s) x(s) + c(s)) <= g_k``,

all linear in (u_i, x_i). TOPP-RA enforces them at the grid points only;
between, they can be exceeded (by several percent at 100 grid points). So:

- :func:`interior_rows` adds, from the start, the joint velocities and
  accelerations at theta = 1/4, 1/2, 3/4 of every segment (exact, from the
  spline), and
  :func:`grasp_midpoint_rows` the grasp rows in force at the midpoints;
- after solving, :func:`joint_cuts` evaluates the joint limits exactly at
  the sub-points; where one still exceeds its limit by more than the
  tolerance, its row at the worst sub-point becomes a cut (solve again, no
  new grid point); if the cuts do not converge, :func:`joint_split_points`
  splits those segments in two;
- :func:`refinement_points` evaluates torques and grasp at the sub-points;
  a segment exceeding a limit by ``e`` is split into ``ceil(sqrt(e /
  tolerance))`` equal parts (an overshoot shrinks with the square of the
  step), up to :data:`MAX_SPLIT`: the retimer evaluates Drake at the new grid
  points and solves again.

Torque and wrench coefficients at the sub-points come from Lagrange
interpolation through up to four grid points of the same cubic piece
(smooth there: the error, fourth order in the step, is far below the
overshoot looked for, and it costs no Drake call). Grasp rows are looked at
between grid points if they come within :data:`ROW_SCREEN` of their bound at
a grid point (further away, a row cannot reach its bound inside a segment:
overshoots measured at 100 grid points stay below 3 %).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from rt_drake.dynamics.wrench import PathCoefficients
from rt_drake.retiming import _between_kernels as K
from rt_drake.retiming._joint_path import JointPath
from rt_drake.retiming._samples import PathSamples
from rt_drake.retiming.limits import JointLimits
from rt_drake.retiming.passes import VAR_BOUND, StageRows
from rt_drake.retiming.seidel import kernel_array

#: Interior points per segment: theta = 1/8, 2/8, ..., 7/8.
SUBPOINTS = 7
#: Grasp rows with ``max_i F_k w_i / g_k`` above ``1 - ROW_SCREEN`` at the grid
#: points are evaluated between them.
ROW_SCREEN = 0.1
#: Parts a segment is split into, at most, per refinement.
MAX_SPLIT = 8

_THETA = np.arange(1, SUBPOINTS + 1) / (SUBPOINTS + 1)
#: The sub-points of the interior joint rows (theta = 1/4, 1/2, 3/4) and the
#: midpoint.
_INTERIOR_POINTS = np.array([1, 3, 5], dtype=np.int64)
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
            self.dq = np.empty((count, len(_THETA), n))
            self.ddq = np.empty((count, len(_THETA), n))
            K.sub_derivatives(
                kernel_array(samples.dq),
                kernel_array(samples.ddq),
                self.ds,
                _THETA,
                self.dq,
                self.ddq,
            )
        else:
            points = self.s[:-1, None] + _THETA * self.ds[:, None]
            self.dq = kernel_array(path(points, 1))
            self.ddq = kernel_array(path(points, 2))
        self.step = 2.0 * _THETA * self.ds[:, None]  # x(s) = x_i + step u_i
        self._index, self._weights = _lagrange(self.s, knots)

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
            self._weights,
            self._index,
            MIDDLE,
            out,
        )
        return out

    def interpolate(self, values: np.ndarray, point: int | None = None) -> np.ndarray:
        """(G, m) values at the grid points -> (N, K, m) at the sub-points.

        With ``point``, only at that sub-point: (N, m).
        """
        if point is None:
            return np.matmul(self._weights, values[self._index])
        return np.einsum("nj,njm->nm", self._weights[:, point], values[self._index])


def interior_rows(segments: Segments, limits: JointLimits) -> StageRows:
    """The joint limits inside every segment, as rows of its stage's LP.

    Exact (from the spline), in the stage's variables (u_i, x_i), at
    theta = 1/4, 1/2, 3/4: the velocity cap ``x_i + 2 theta ds_i u_i <=
    min_j v_j^2 / q'_j(s)^2`` (inactive where every q'_j is 0) and the
    accelerations of every joint, each sign.
    """
    count, n = len(segments.ds), segments.dq.shape[2]
    width = len(_INTERIOR_POINTS) * (1 + 2 * n)
    A, B, C = (np.empty((count, width)) for _ in range(3))
    K.interior_rows(
        segments.dq,
        segments.ddq,
        segments.step,
        _INTERIOR_POINTS,
        kernel_array(limits.velocity),
        kernel_array(limits.acceleration),
        VAR_BOUND,
        A,
        B,
        C,
    )
    return StageRows(A, B, C)


def grasp_midpoint_rows(
    segments: Segments, wrench: PathCoefficients, F: np.ndarray, g: np.ndarray
) -> StageRows:
    """Grasp rows at every segment's midpoint, as rows of its stage's LP.

    ``F_k (a(m) u_i + b(m) (x_i + ds_i u_i) + c(m)) <= g_k`` at
    ``m = s_i + ds_i / 2``, the coefficients interpolated: this quarters the
    overshoot between grid points before :func:`refinement_points` looks
    for it, so that few paths need a refinement.

    Args:
        segments: The grid's segments.
        wrench: Wrench coefficients at the grid points.
        F: (R, 6) the rows in force.
        g: (R,) their bounds.
    """
    shape = (len(segments.ds), len(g))
    A, B, C = np.empty(shape), np.empty(shape), np.empty(shape)
    K.midpoint_rows(
        *(kernel_array(v) for v in wrench),
        kernel_array(F),
        kernel_array(g),
        segments.s,
        segments._weights,
        segments._index,
        MIDDLE,
        A,
        B,
        C,
    )
    return StageRows(A, B, C)


def joint_cuts(
    segments: Segments,
    x: np.ndarray,
    u: np.ndarray,
    limits: JointLimits,
    tolerance: float,
) -> StageRows | None:
    """Cuts where each joint limit is exceeded most in a segment (see joint_excess).

    Args:
        segments: The grid's segments.
        x: (G,) ``s'^2`` at the grid points.
        u: (G-1,) ``s''`` per segment.
        limits: Joint limits.
        tolerance: Relative excess allowed.

    Returns:
        The cut rows (one per exceeded joint, kind and segment; inactive
        rows elsewhere), or None if no joint limit is exceeded.
    """
    dq, step = segments.dq, segments.step
    count, n = len(u), dq.shape[2]
    worst, excess, vertex = _joint_excess(segments, x, u, limits)
    exceeded = excess > tolerance  # (3, N, n)
    if not exceeded.any():
        return None
    rows = np.arange(count)[:, None]
    joints = np.arange(n)
    columns = []
    # Velocity: (2 theta ds) u + x - v^2 / q'^2 <= 0 at the worst theta.
    q1 = dq[rows, worst[0], joints]
    with np.errstate(divide="ignore"):
        cap = limits.velocity**2 / q1**2
    columns.append((step[rows, worst[0]], np.ones_like(q1), -cap, exceeded[0]))
    # Acceleration, each sign: sign ((q' + 2 theta ds q'') u + q'' x) - a <= 0,
    # at the worst sub-point or at the parabola's vertex between them.
    for kind, sign in ((1, 1.0), (2, -1.0)):
        q1, q2, to_x = _at_worst(segments, worst[kind], vertex[kind])
        columns.append(
            (
                sign * (q1 + to_x * q2),
                sign * q2,
                -np.broadcast_to(limits.acceleration, q1.shape),
                exceeded[kind],
            )
        )
    A, B, C, active = (np.hstack(parts) for parts in zip(*columns, strict=True))
    used = active.any(axis=0)
    A, B, C, active = A[:, used], B[:, used], C[:, used], active[:, used]
    return StageRows(
        np.where(active, A, 0.0), np.where(active, B, 0.0), np.where(active, C, -1.0)
    )


def joint_split_points(
    segments: Segments,
    x: np.ndarray,
    u: np.ndarray,
    limits: JointLimits,
    tolerance: float,
) -> np.ndarray:
    """Midpoints (sorted s) of the segments where a joint limit is exceeded.

    For when cuts (:func:`joint_cuts`) have not converged: a segment split
    in two has its sub-points at half the step, and an excess between grid
    points shrinks with the square of the step.

    Args:
        segments: The grid's segments.
        x: (G,) ``s'^2`` at the grid points.
        u: (G-1,) ``s''`` per segment.
        limits: Joint limits.
        tolerance: Relative excess allowed.
    """
    excess = _joint_excess(segments, x, u, limits)[1]
    split = np.flatnonzero((excess > tolerance).any(axis=(0, 2)))
    return segments.s[split] + 0.5 * segments.ds[split]


def joint_excess_max(
    segments: Segments, x: np.ndarray, u: np.ndarray, limits: JointLimits
) -> tuple[float, float]:
    """(largest relative excess of a joint limit between grid points, its s).

    The excess is ``|value| / limit - 1`` over the joints' velocities and
    accelerations at the sub-points and the acceleration's vertex
    (:func:`._between_kernels.joint_excess`); s is the start of its segment.
    """
    excess = _joint_excess(segments, x, u, limits)[1]
    _, segment, _ = np.unravel_index(int(np.argmax(excess)), excess.shape)
    return float(excess.max()), float(segments.s[segment])


def _joint_excess(
    segments: Segments, x: np.ndarray, u: np.ndarray, limits: JointLimits
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(worst, excess, vertex), each (3, N, n): :func:`._between_kernels.joint_excess`.

    For velocity, acceleration up and down (axis 0), per segment and joint:
    the worst sub-point (-1: the acceleration parabola's vertex between
    them), its relative excess over the limit, and the vertex's theta.
    """
    count, n = len(u), segments.dq.shape[2]
    worst = np.empty((3, count, n), dtype=np.int64)
    excess = np.empty((3, count, n))
    vertex = np.zeros((3, count, n))
    K.joint_excess(
        segments.dq,
        segments.ddq,
        segments.step,
        kernel_array(x),
        kernel_array(u),
        kernel_array(limits.velocity),
        kernel_array(limits.acceleration),
        worst,
        excess,
        vertex,
    )
    return worst, excess, vertex


def _at_worst(
    segments: Segments, worst: np.ndarray, vertex: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """q', q'' and ``2 theta ds`` (each (N, n)) where :func:`joint_cuts` cuts.

    At sub-point ``worst``; where ``worst`` is -1, at theta = ``vertex``:
    q' through sub-points 0, 3, 6 (theta = 1/8, 1/2, 7/8) by its quadratic,
    q'' through 0 and 6 by its line (exact inside a cubic piece).
    """
    dq, ddq = segments.dq, segments.ddq
    rows = np.arange(dq.shape[0])[:, None]
    joints = np.arange(dq.shape[2])
    index = np.maximum(worst, 0)
    q1, q2 = dq[rows, index, joints], ddq[rows, index, joints]
    theta = _THETA[index]
    between = worst < 0
    if between.any():
        r = (vertex - 0.5) / (_THETA[3] - _THETA[0])
        weights = (0.5 * r * (r - 1.0), 1.0 - r * r, 0.5 * r * (r + 1.0))
        nodes = [dq[:, j, :] for j in (0, 3, 6)]
        quadratic = sum(w * v for w, v in zip(weights, nodes, strict=True))
        line = ddq[:, 0, :] + (vertex - _THETA[0]) / (_THETA[6] - _THETA[0]) * (
            ddq[:, 6, :] - ddq[:, 0, :]
        )
        q1 = np.where(between, quadratic, q1)
        q2 = np.where(between, line, q2)
        theta = np.where(between, vertex, theta)
    return q1, q2, 2.0 * theta * segments.ds[:, None]


def subpoint_x(segments: Segments, x: np.ndarray, u: np.ndarray) -> np.ndarray:
    """(N, K) ``x = s'^2`` at the sub-points: ``x_i + 2 theta ds_i u_i`` (>= 0)."""
    return np.maximum(x[:-1, None] + segments.step * u[:, None], 0.0)


def refinement_points(
    segments: Segments,
    samples: PathSamples,
    x: np.ndarray,
    u: np.ndarray,
    limits: JointLimits,
    normals: np.ndarray | None,
    row_max: np.ndarray | None,
    tolerance: float,
    grasp_ratio: np.ndarray | None = None,
) -> np.ndarray:
    """Grid points to add where torque or grasp is exceeded in a segment.

    Args:
        segments: The grid's segments.
        samples: The path at the grid points.
        x: (G,) ``s'^2`` at the grid points.
        u: (G-1,) ``s''`` per segment.
        limits: Joint limits.
        normals: (6, R) grasp rows ``F / g`` (transposed), or None.
        row_max: (R,) each grasp row's largest ``F_k w / g_k`` over the
            wrenches the stage LPs enforced (from the exactness check; exact
            where above ``1 - ROW_SCREEN``), or None.
        tolerance: Relative excess allowed.
        grasp_ratio: For a set of objects, (N, K) its worst object's largest
            ``F_k w / g_k`` and torque ratio at the sub-points (from
            :meth:`._robust_grasp.SetRows.between`; the samples' torques are
            then the arm's alone and not checked here), or None.

    Returns:
        Sorted new s values (empty: nothing exceeded).
    """
    checks: list[tuple[PathCoefficients, np.ndarray, bool]] = []
    if (
        samples.torque is not None
        and limits.torque is not None
        and samples.torque_set is None  # a set's torques come with its grasp
    ):
        checks.append((samples.torque, np.diag(1.0 / limits.torque), True))
    if samples.wrench is not None and normals is not None and row_max is not None:
        rows = np.flatnonzero(row_max > 1.0 - ROW_SCREEN)
        if rows.size:
            checks.append((samples.wrench, normals[:, rows], False))
    if not checks and grasp_ratio is None:
        return np.zeros(0)
    excess = np.full(len(u), -np.inf)
    if grasp_ratio is not None:
        excess = grasp_ratio.max(axis=1) - 1.0
    part = np.empty(len(u))
    x, u = kernel_array(x), kernel_array(u)
    for (a, b, c), rows_map, absolute in checks:
        K.affine_excess(
            segments._weights,
            segments._index,
            kernel_array(a),
            kernel_array(b),
            kernel_array(c),
            segments.step,
            x,
            u,
            kernel_array(rows_map),
            absolute,
            part,
        )
        np.maximum(excess, part, out=excess)
    split = np.flatnonzero(excess > tolerance)
    if not split.size:
        return np.zeros(0)
    parts = np.clip(np.ceil(np.sqrt(excess[split] / tolerance)), 2, MAX_SPLIT)
    s, ds = segments.s, segments.ds
    points = [
        s[i] + ds[i] * np.arange(1, k) / k
        for i, k in zip(split, parts.astype(int), strict=True)
    ]
    return np.sort(np.concatenate(points))


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
    weights = np.empty((count, len(_THETA), 4))
    _lagrange_kernel(
        kernel_array(s),
        bounds[piece].astype(np.int64),
        bounds[piece + 1].astype(np.int64),
        _THETA,
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


__all__ = [
    "MAX_SPLIT",
    "MIDDLE",
    "ROW_SCREEN",
    "SUBPOINTS",
    "Segments",
    "grasp_midpoint_rows",
    "interior_rows",
    "joint_cuts",
    "refinement_points",
    "subpoint_x",
]
