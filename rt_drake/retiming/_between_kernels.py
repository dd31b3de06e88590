"""Compiled (numba) loops of :mod:`._between`: one pass each, no temporaries.

All work on segment i of the grid (``s_i`` to ``s_{i+1}``, inside one cubic
piece of the path) at the sub-points ``s_i + theta_j ds_i``, where

    q'(theta)  = q'_i + theta ds_i (q''_i + theta J_i / 2)
    q''(theta) = q''_i + theta J_i,      J_i = q''_{i+1} - q''_i

(q'' is linear inside a cubic piece), and ``x(theta) = x_i + 2 theta ds_i
u_i``. Arrays are C-contiguous float64 (``seidel.kernel_array``).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit


@njit(cache=True)
def sub_derivatives(dq, ddq, ds, theta, out_dq, out_ddq):  # noqa: D417
    """Q' and q'' at the sub-points: (N, K, n) each, written in place."""
    for i in range(ds.shape[0]):
        for j in range(theta.shape[0]):
            t = theta[j]
            for k in range(dq.shape[1]):
                jump = ddq[i + 1, k] - ddq[i, k]
                out_dq[i, j, k] = dq[i, k] + t * ds[i] * (ddq[i, k] + 0.5 * t * jump)
                out_ddq[i, j, k] = ddq[i, k] + t * jump


@njit(cache=True)
def interior_rows(sub_dq, sub_ddq, step, points, velocity, acceleration, big, A, B, C):  # noqa: D417
    """Joint rows at the sub-points ``points`` of every segment, in place.

    Columns, per sub-point p of ``points``: the velocity cap row ``step u +
    x - min_k v_k^2 / q'_k^2 <= 0`` (inactive: 0, 0, -1, where every q'_k is
    0), then for every joint k both signs of ``(q'_k + step q''_k) u + q''_k
    x - a_k <= 0``.
    """
    n = sub_dq.shape[2]
    width = 1 + 2 * n
    for i in range(sub_dq.shape[0]):
        for p in range(points.shape[0]):
            j = points[p]
            column = p * width
            cap = big
            for k in range(n):
                square = sub_dq[i, j, k] * sub_dq[i, j, k]
                if square > 0.0:
                    cap = min(cap, velocity[k] * velocity[k] / square)
            if cap < big:
                A[i, column], B[i, column], C[i, column] = step[i, j], 1.0, -cap
            else:
                A[i, column], B[i, column], C[i, column] = 0.0, 0.0, -1.0
            for k in range(n):
                a_row = sub_dq[i, j, k] + step[i, j] * sub_ddq[i, j, k]
                b_row = sub_ddq[i, j, k]
                plus, minus = column + 1 + k, column + 1 + n + k
                A[i, plus], B[i, plus], C[i, plus] = a_row, b_row, -acceleration[k]
                A[i, minus], B[i, minus] = -a_row, -b_row
                C[i, minus] = -acceleration[k]


@njit(cache=True)
def joint_excess(  # noqa: D417
    sub_dq, sub_ddq, step, x, u, velocity, acceleration, worst, excess, vertex
):
    """Worst point and ratio of each joint limit in each segment.

    ``worst``, ``excess``: (3, N, n) for velocity, +acceleration and
    -acceleration: the sub-point index and ``ratio - 1`` there. Inside one
    cubic piece the acceleration ``q' u + q'' x`` is a quadratic in theta
    (q' quadratic, q'' and x linear), so its extreme can fall between
    sub-points (a segment that starts from rest climbs from 0 to the limit
    and back); where the parabola through theta = 1/8, 1/2, 7/8 peaks higher
    than every sub-point, ``worst`` is -1 and ``vertex`` (3, N, n) holds its
    theta.
    """
    h = 3.0 / 8.0  # the parabola's nodes: sub-points 0, 3, 6
    nodes = np.empty(3)
    for i in range(sub_dq.shape[0]):
        for k in range(sub_dq.shape[2]):
            for kind in range(3):
                excess[kind, i, k] = -math.inf
            for j in range(sub_dq.shape[1]):
                x_j = max(x[i] + step[i, j] * u[i], 0.0)
                value = abs(sub_dq[i, j, k]) * math.sqrt(x_j) / velocity[k] - 1.0
                if value > excess[0, i, k]:
                    excess[0, i, k], worst[0, i, k] = value, j
                a_j = sub_dq[i, j, k] * u[i] + sub_ddq[i, j, k] * x_j
                a_j /= acceleration[k]
                if j % 3 == 0:
                    nodes[j // 3] = a_j
                if a_j - 1.0 > excess[1, i, k]:
                    excess[1, i, k], worst[1, i, k] = a_j - 1.0, j
                if -a_j - 1.0 > excess[2, i, k]:
                    excess[2, i, k], worst[2, i, k] = -a_j - 1.0, j
            curvature = nodes[0] - 2.0 * nodes[1] + nodes[2]
            if curvature == 0.0:
                continue
            slope = (nodes[2] - nodes[0]) / (2.0 * h)
            offset = -slope * h * h / curvature  # theta - 1/2 at the vertex
            if not -0.5 < offset < 0.5:
                continue
            peak = nodes[1] + 0.5 * slope * offset
            kind = 1 if curvature < 0.0 else 2
            sign = 1.0 if curvature < 0.0 else -1.0
            if sign * peak - 1.0 > excess[kind, i, k]:
                excess[kind, i, k] = sign * peak - 1.0
                worst[kind, i, k] = -1
                vertex[kind, i, k] = 0.5 + offset


@njit(cache=True)
def affine_excess(weights, index, a, b, c, step, x, u, rows, absolute, out):  # noqa: D417
    """Largest ratio - 1 in each segment of ``rows . (a u + b x + c)``.

    The coefficients at each sub-point are interpolated (``weights``,
    ``index``: the Lagrange stencil); ``rows`` (m, R) maps a value to
    ratios (``F / g`` transposed for the grasp, ``diag(1 / tau_max)`` for
    torques); ``absolute``: take the absolute value (torques). The ratios
    are summed a coordinate at a time over all rows (the same sums, in the
    same order, as row by row; the loop over rows vectorises).
    """
    m, count = rows.shape
    value = np.empty(m)
    ratio = np.empty(count)
    for i in range(weights.shape[0]):
        best = -math.inf
        for j in range(weights.shape[1]):
            x_j = max(x[i] + step[i, j] * u[i], 0.0)
            for d in range(m):
                total = 0.0
                for slot in range(4):
                    w = weights[i, j, slot]
                    if w != 0.0:
                        g = index[i, slot]
                        total += w * (a[g, d] * u[i] + b[g, d] * x_j + c[g, d])
                value[d] = total
            ratio[:] = 0.0
            for d in range(m):
                v = value[d]
                for r in range(count):
                    ratio[r] += rows[d, r] * v
            largest = -math.inf  # of the ratios, or of their absolute values
            for r in range(count):
                item = abs(ratio[r]) if absolute else ratio[r]
                largest = item if item > largest else largest
            best = max(best, largest - 1.0)
        out[i] = best


@njit(cache=True)
def enforced_wrenches(a, b, c, x, u, s, weights, index, middle, out):  # noqa: D417
    """The wrenches ``a u + b x + c`` the stage LPs enforce, (3N + 1, 6).

    Rows 0..N-1: stage i at ``s_i`` with ``(u_i, x_i)``; row N: the end
    point with ``(u_{N-1}, x_N)``; rows N+1..2N: stage i at ``s_{i+1}``
    with ``(u_i, x_i + 2 ds_i u_i)``; rows 2N+1..3N: stage i at its
    midpoint with ``(u_i, x_i + ds_i u_i)``, the coefficients interpolated
    (sub-point ``middle`` of the stencil ``weights``, ``index``).
    """
    count = u.shape[0]
    for i in range(count + 1):
        u_i = u[min(i, count - 1)]
        for d in range(6):
            out[i, d] = a[i, d] * u_i + b[i, d] * x[i] + c[i, d]
    for i in range(count):
        ds = s[i + 1] - s[i]
        x_next = x[i] + 2.0 * ds * u[i]
        x_middle = x[i] + ds * u[i]
        for d in range(6):
            out[count + 1 + i, d] = (
                a[i + 1, d] * u[i] + b[i + 1, d] * x_next + c[i + 1, d]
            )
            total = 0.0
            for slot in range(4):
                w = weights[i, middle, slot]
                if w != 0.0:
                    g = index[i, slot]
                    total += w * (a[g, d] * u[i] + b[g, d] * x_middle + c[g, d])
            out[2 * count + 1 + i, d] = total


@njit(cache=True)
def midpoint_rows(a, b, c, F, g, s, weights, index, middle, A, B, C):  # noqa: D417
    """Rows ``F (a(m) u + b(m) (x + ds u) + c(m)) - g <= 0`` at every midpoint.

    ``m = s_i + ds_i / 2``, the coefficients interpolated (sub-point
    ``middle`` of the stencil ``weights``, ``index``); A, B, C (N, k) are
    written in place: ``A = F a(m) + ds_i F b(m)``, ``B = F b(m)``,
    ``C = F c(m) - g``.
    """
    k, m = F.shape
    here = np.empty((3, m))
    for i in range(A.shape[0]):
        for d in range(m):
            sum_a = sum_b = sum_c = 0.0
            for slot in range(4):
                w = weights[i, middle, slot]
                g_i = index[i, slot]
                sum_a += w * a[g_i, d]
                sum_b += w * b[g_i, d]
                sum_c += w * c[g_i, d]
            here[0, d], here[1, d], here[2, d] = sum_a, sum_b, sum_c
        ds = s[i + 1] - s[i]
        for r in range(k):
            f_a = f_b = f_c = 0.0
            for d in range(m):
                f_a += here[0, d] * F[r, d]
                f_b += here[1, d] * F[r, d]
                f_c += here[2, d] * F[r, d]
            A[i, r] = f_a + ds * f_b
            B[i, r] = f_b
            C[i, r] = f_c - g[r]


@njit(cache=True)
def position_excess(s, q, dq, ddq, lower, upper, tolerance):  # noqa: D417
    """The first grid point or segment extreme outside the position limits.

    ``dq/dtheta = c0 + c1 theta + c2 theta^2`` inside segment i (theta in
    [0, 1]); its roots in (0, 1) are where joint k can peak. Returns
    ``(found, k, value, s)``.
    """
    for i in range(s.shape[0]):
        for k in range(q.shape[1]):
            if q[i, k] < lower[k] - tolerance or q[i, k] > upper[k] + tolerance:
                return True, k, q[i, k], s[i]
    roots = np.empty(2)
    for i in range(s.shape[0] - 1):
        ds = s[i + 1] - s[i]
        for k in range(q.shape[1]):
            c0 = dq[i, k] * ds
            c1 = ddq[i, k] * ds * ds
            c2 = 0.5 * (ddq[i + 1, k] - ddq[i, k]) * ds * ds
            count = 0
            if abs(c2) <= 1e-12 * (abs(c1) + 1e-300):
                if c1 != 0.0:
                    roots[0] = -c0 / c1
                    count = 1
            else:
                disc = c1 * c1 - 4.0 * c2 * c0
                if disc >= 0.0:
                    root = math.sqrt(disc)
                    roots[0] = (-c1 + root) / (2.0 * c2)
                    roots[1] = (-c1 - root) / (2.0 * c2)
                    count = 2
            for r in range(count):
                t = roots[r]
                if not 0.0 < t < 1.0:
                    continue
                value = q[i, k] + t * (c0 + t * (c1 / 2.0 + t * c2 / 3.0))
                if value < lower[k] - tolerance or value > upper[k] + tolerance:
                    return True, k, value, s[i] + t * ds
    return False, -1, 0.0, 0.0


__all__ = [
    "affine_excess",
    "enforced_wrenches",
    "interior_rows",
    "joint_excess",
    "midpoint_rows",
    "position_excess",
    "sub_derivatives",
]
