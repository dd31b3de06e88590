"""The joint limits between grid points: rows from the start, cuts after.

In segment i at ``s = s_i + theta ds_i`` (``x = s'^2``, u the segment's
``s''``): velocity ``q'_j(s)^2 (x_i + 2 theta ds_i u_i) <= v_j^2`` and
acceleration ``|(q'_j(s) + 2 theta ds_i q''_j(s)) u_i + q''_j(s) x_i| <=
a_j``, linear in the stage's variables (u_i, x_i). :func:`interior_rows`
holds them at theta = 1/4, 1/2, 3/4 from the start; after a solve
:func:`joint_cuts` cuts where they are still exceeded, and
:func:`joint_split_points` splits the segments where cuts do not converge
(see :mod:`._between`).
"""

from __future__ import annotations

import numpy as np

from rt_drake.retiming import _between_kernels as K
from rt_drake.retiming._segments import THETA, Segments
from rt_drake.retiming.limits import JointLimits
from rt_drake.retiming.passes import VAR_BOUND, StageRows
from rt_drake.retiming.seidel import kernel_array

#: The sub-points of the interior joint rows (theta = 1/4, 1/2, 3/4).
INTERIOR_POINTS = np.array([1, 3, 5], dtype=np.int64)


def interior_rows(segments: Segments, limits: JointLimits) -> StageRows:
    """The joint limits inside every segment, as rows of its stage's LP.

    Exact (from the spline), in the stage's variables (u_i, x_i), at
    theta = 1/4, 1/2, 3/4: the velocity cap ``x_i + 2 theta ds_i u_i <=
    min_j v_j^2 / q'_j(s)^2`` (inactive where every q'_j is 0) and the
    accelerations of every joint, each sign.
    """
    count, n = len(segments.ds), segments.dq.shape[2]
    width = len(INTERIOR_POINTS) * (1 + 2 * n)
    A, B, C = (np.empty((count, width)) for _ in range(3))
    K.interior_rows(
        segments.dq,
        segments.ddq,
        segments.step,
        INTERIOR_POINTS,
        kernel_array(limits.velocity),
        kernel_array(limits.acceleration),
        VAR_BOUND,
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
    theta = THETA[index]
    between = worst < 0
    if between.any():
        r = (vertex - 0.5) / (THETA[3] - THETA[0])
        weights = (0.5 * r * (r - 1.0), 1.0 - r * r, 0.5 * r * (r + 1.0))
        nodes = [dq[:, j, :] for j in (0, 3, 6)]
        quadratic = sum(w * v for w, v in zip(weights, nodes, strict=True))
        line = ddq[:, 0, :] + (vertex - THETA[0]) / (THETA[6] - THETA[0]) * (
            ddq[:, 6, :] - ddq[:, 0, :]
        )
        q1 = np.where(between, quadratic, q1)
        q2 = np.where(between, line, q2)
        theta = np.where(between, vertex, theta)
    return q1, q2, 2.0 * theta * segments.ds[:, None]


__all__ = [
    "INTERIOR_POINTS",
    "interior_rows",
    "joint_cuts",
    "joint_excess_max",
    "joint_split_points",
]
