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
  new grid point);
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

from rt_drake.dynamics import PathCoefficients
from rt_drake.retiming.limits import JointLimits
from rt_drake.retiming.passes import VAR_BOUND, StageRows
from rt_drake.retiming.samples import PathSamples

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
INTERIOR_POINTS = np.array([1, 3, 5])
MIDDLE = 3


class Segments:
    """The grid's segments at their sub-points: path derivatives, stencils.

    Built once per grid (it does not depend on the profile).

    Attributes:
        s: (G,) grid; ds: (N,) steps.
        dq, ddq: (N, K, n) q'(s), q''(s) at the sub-points.
    """

    def __init__(self, samples: PathSamples, knots: np.ndarray) -> None:
        self.s = samples.s
        self.ds = np.diff(self.s)
        # Inside one cubic piece q'' is linear, so with J = q''_{i+1} - q''_i,
        # q'(s_i + theta ds) = q'_i + theta ds (q''_i + theta J / 2) and
        # q''(s_i + theta ds) = q''_i + theta J.
        ddq = samples.ddq
        jump = (ddq[1:] - ddq[:-1])[:, None]  # (N, 1, n)
        theta = _THETA[None, :, None]
        ds = self.ds[:, None, None]
        self.dq = samples.dq[:-1, None] + theta * ds * (
            ddq[:-1, None] + 0.5 * theta * jump
        )
        self.ddq = ddq[:-1, None] + theta * jump
        self.step = 2.0 * _THETA * self.ds[:, None]  # x(s) = x_i + step u_i
        self._index, self._weights = _lagrange(self.s, knots)

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
    points = INTERIOR_POINTS
    with np.errstate(divide="ignore"):
        cap = np.min(limits.velocity**2 / segments.dq[:, points] ** 2, axis=2)
    bounded = cap < VAR_BOUND  # (N, 3)
    velocity = (
        np.where(bounded, segments.step[:, points], 0.0),
        np.where(bounded, 1.0, 0.0),
        np.where(bounded, -np.minimum(cap, VAR_BOUND), -1.0),
    )
    dq = segments.dq[:, points]  # (N, 3, n)
    ddq = segments.ddq[:, points]
    step = segments.step[:, points, None]
    count = len(segments.ds)
    A = (dq + step * ddq).reshape(count, -1)
    B = ddq.reshape(count, -1)
    C = -np.broadcast_to(np.tile(limits.acceleration, len(points)), A.shape)
    return StageRows(
        np.hstack([velocity[0], A, -A]),
        np.hstack([velocity[1], B, -B]),
        np.hstack([velocity[2], C, C]),
    )


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
    a, b, c = (segments.interpolate(v, MIDDLE) for v in wrench)  # (N, 6)
    Fa, Fb, Fc = a @ F.T, b @ F.T, c @ F.T
    return StageRows(Fa + segments.ds[:, None] * Fb, Fb, Fc - g)


def joint_cuts(
    segments: Segments,
    x: np.ndarray,
    u: np.ndarray,
    limits: JointLimits,
    tolerance: float,
) -> StageRows | None:
    """Cuts at the worst sub-point of every joint limit exceeded in a segment.

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
    dq, ddq, step = segments.dq, segments.ddq, segments.step
    x_sub = np.maximum(x[:-1, None] + step * u[:, None], 0.0)
    velocity = np.abs(dq) * np.sqrt(x_sub)[..., None] / limits.velocity
    acceleration = (dq * u[:, None, None] + ddq * x_sub[..., None]) / (
        limits.acceleration
    )
    rows = np.arange(len(u))[:, None]
    joints = np.arange(dq.shape[2])
    columns = []
    # Velocity: (2 theta ds) u + x - v^2 / q'^2 <= 0 at the worst theta.
    worst = np.argmax(velocity, axis=1)  # (N, n)
    exceeded = velocity[rows, worst, joints] > 1.0 + tolerance
    if exceeded.any():
        q1 = dq[rows, worst, joints]
        with np.errstate(divide="ignore"):
            cap = limits.velocity**2 / q1**2
        columns.append((step[rows, worst], np.ones_like(q1), -cap, exceeded))
    # Acceleration, each sign: sign ((q' + 2 theta ds q'') u + q'' x) - a <= 0.
    for sign in (1.0, -1.0):
        value = sign * acceleration
        worst = np.argmax(value, axis=1)
        exceeded = value[rows, worst, joints] > 1.0 + tolerance
        if not exceeded.any():
            continue
        q1, q2 = dq[rows, worst, joints], ddq[rows, worst, joints]
        columns.append(
            (
                sign * (q1 + step[rows, worst] * q2),
                sign * q2,
                -np.broadcast_to(limits.acceleration, q1.shape),
                exceeded,
            )
        )
    if not columns:
        return None
    A, B, C, active = (np.hstack(parts) for parts in zip(*columns, strict=True))
    used = active.any(axis=0)
    A, B, C, active = A[:, used], B[:, used], C[:, used], active[:, used]
    return StageRows(
        np.where(active, A, 0.0), np.where(active, B, 0.0), np.where(active, C, -1.0)
    )


def subpoint_x(segments: Segments, x: np.ndarray, u: np.ndarray) -> np.ndarray:
    """(N, K) ``x = s'^2`` at the sub-points: ``x_i + 2 theta ds_i u_i`` (>= 0)."""
    return np.maximum(x[:-1, None] + segments.step * u[:, None], 0.0)


def refinement_points(
    segments: Segments,
    samples: PathSamples,
    x: np.ndarray,
    u: np.ndarray,
    limits: JointLimits,
    grasp_ratio: np.ndarray | None,
    tolerance: float,
) -> np.ndarray:
    """Grid points to add where torque or grasp is exceeded in a segment.

    Args:
        segments: The grid's segments.
        samples: The path at the grid points.
        x: (G,) ``s'^2`` at the grid points.
        u: (G-1,) ``s''`` per segment.
        limits: Joint limits.
        grasp_ratio: (N, K) the grasp's largest ``F_k w / g_k`` at the
            sub-points (and, for a set of objects, its torque ratio), from
            the grasp rows' ``between``; None: nothing to look at.
        tolerance: Relative excess allowed.

    Returns:
        Sorted new s values (empty: nothing exceeded).
    """
    torque = (
        samples.torque is not None
        and limits.torque is not None
        and samples.torque_set is None  # a set's torques come with its grasp
    )
    if not torque and grasp_ratio is None:
        return np.zeros(0)
    x_sub = subpoint_x(segments, x, u)
    ratio = np.zeros_like(x_sub)
    if torque:
        assert samples.torque is not None and limits.torque is not None
        a, b, c = (segments.interpolate(v) for v in samples.torque)
        value = a * u[:, None, None] + b * x_sub[..., None] + c
        ratio = np.maximum(ratio, np.max(np.abs(value) / limits.torque, axis=2))
    if grasp_ratio is not None:
        ratio = np.maximum(ratio, grasp_ratio)
    excess = ratio.max(axis=1) - 1.0
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
    low, high = bounds[piece], bounds[piece + 1]
    size = np.minimum(4, high - low + 1)  # points available in the piece
    start = np.clip(np.arange(count) - 1, low, high - size + 1)
    offsets = np.arange(4)
    index = np.minimum(start[:, None] + offsets, high[:, None])  # (N, 4)
    nodes = s[index]
    valid = offsets < size[:, None]  # (N, 4)
    t = s[:-1, None] + _THETA * np.diff(s)[:, None]  # (N, K)
    # w_k(t) = prod_{m != k} (t - t_m) / (t_k - t_m) over the valid nodes m
    # (t is never a node: the sub-points lie strictly inside the segments).
    factors = np.where(valid[:, None, :], t[..., None] - nodes[:, None, :], 1.0)
    numerators = np.prod(factors, axis=2, keepdims=True) / factors  # (N, K, 4)
    gaps = nodes[:, :, None] - nodes[:, None, :]  # (N, k, m)
    gaps[:, offsets, offsets] = 1.0
    gaps = np.where(valid[:, None, :], gaps, 1.0)
    weights = numerators / np.prod(gaps, axis=2)[:, None, :]
    return index, np.where(valid[:, None, :], weights, 0.0)


__all__ = [
    "INTERIOR_POINTS",
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
