"""Compiled (numba) loops of the jerk-limited retimer: one pass, no temporaries.

:func:`grasp_screen`: at every dense point p the object wrench ``w_p = a_p
u_p + b_p x_p + c_p`` (N, N m, in the cup frame of :mod:`._samples`) and
each grasp row's ratio ``F_r w_p / g_r`` (``scaled = F / g``), reduced as it
is made to the largest ratio per point and the (point, row) pairs at or
above a threshold. The (P, R) ratios are never stored: with numpy they
were three (P, R) temporaries per call. :func:`jerk_ratios`: the joint
jerk at every jerk point. :func:`interior_duration`: the duration by
quadrature, its sums in numpy's pairwise order. The LPs' rows are
:mod:`._jerk_row_kernels`'. Arrays are C-contiguous float64.
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def grasp_screen(a, b, c, x, u, scaled_t, threshold, at, over, largest):  # noqa: D417
    """``over[p, r] = F_r w_p / g_r >= threshold``; ``largest[p]`` the max over r.

    At the points ``p`` in ``at`` (the others are not written). ``a``,
    ``b``, ``c``: (P, 6); ``x``, ``u``: (P,); ``scaled_t``: (6, R), ``(F /
    g)`` transposed (each ratio summed from 0 over the wrench's six
    components in order; the loop over rows innermost, vectorised); ``at``:
    (A,) int64; ``over``: (P, R) bool, False on entry at ``at`` (a row is
    written only where its largest ratio reaches ``threshold``) and
    ``largest``: (P,), written in place.
    """
    rows = scaled_t.shape[1]
    ratio = np.empty(rows)
    w = np.empty(6)
    s0, s1, s2 = scaled_t[0], scaled_t[1], scaled_t[2]
    s3, s4, s5 = scaled_t[3], scaled_t[4], scaled_t[5]
    for i in range(len(at)):
        p = at[i]
        for k in range(6):
            w[k] = a[p, k] * u[p] + b[p, k] * x[p] + c[p, k]
        w0, w1, w2, w3, w4, w5 = w[0], w[1], w[2], w[3], w[4], w[5]
        for r in range(rows):  # summed from 0 in the order of w (vectorised over r)
            ratio[r] = (
                ((((0.0 + w0 * s0[r]) + w1 * s1[r]) + w2 * s2[r]) + w3 * s3[r])
                + w4 * s4[r]
            ) + w5 * s5[r]
        # The largest in four interleaved runs (max is exact: the same value).
        m0 = m1 = m2 = m3 = -np.inf
        quad = rows - rows % 4
        for r in range(0, quad, 4):
            m0, m1 = max(m0, ratio[r]), max(m1, ratio[r + 1])
            m2, m3 = max(m2, ratio[r + 2]), max(m3, ratio[r + 3])
        for r in range(quad, rows):
            m0 = max(m0, ratio[r])
        most = max(max(m0, m1), max(m2, m3))
        largest[p] = most
        if most >= threshold:
            for r in range(rows):
                over[p, r] = ratio[r] >= threshold


@njit(cache=True)
def jerk_ratios(cols, X, U, K, z, dq, ddq, dddq, jerk, inner, out):  # noqa: D417
    """``|q'''_j| / J_j`` at every point, 0 off the interior pieces, in place.

    At point p, ``x``, ``u``, ``k`` are ``band . z[cols[p]]`` (``cols``, ``X``,
    ``U``, ``K``: (P, 3), :class:`._jerk_rows.Band`, summed in the order of
    the sparse maps' rows), ``x`` clipped at 0, and the joint jerk ``sqrt(x)
    (q'_j k + 3 q''_j u + q'''_j x)`` (1/s^3 times rad). ``dq``, ``ddq``,
    ``dddq``, ``out``: (P, n); ``jerk``: (n,); ``inner``: (P,) bool.
    """
    for p in range(cols.shape[0]):
        if not inner[p]:
            for j in range(out.shape[1]):
                out[p, j] = 0.0
            continue
        x, u, k = 0.0, 0.0, 0.0
        for e in range(3):
            value = z[cols[p, e]]
            x += X[p, e] * value
            u += U[p, e] * value
            k += K[p, e] * value
        x = max(x, 0.0)
        root = np.sqrt(x)
        for j in range(out.shape[1]):
            bracket = dq[p, j] * k + 3.0 * ddq[p, j] * u + dddq[p, j] * x
            out[p, j] = abs(root * bracket / jerk[j])


@njit(cache=True)
def _x_u(cols, X, U, z, p):  # noqa: D417
    """The x (clipped at 0) and u at point p: the band times z, in the maps' order."""
    x, u = 0.0, 0.0
    for e in range(3):
        x += X[p, e] * z[cols[p, e]]
        u += U[p, e] * z[cols[p, e]]
    return max(x, 0.0), u


@njit(cache=True, error_model="numpy")  # x / 0 is inf (a cap of 0: a stop)
def joint_ratios(cols, X, U, z, dq, ddq, x_cap, acceleration, out):  # noqa: D417
    """The largest velocity or acceleration ratio at every point, in place.

    At point p, x (clipped at 0) and u from the band (as :func:`jerk_ratios`),
    the velocity ratio ``sqrt(x / x_cap)`` (0 where x is 0) and the
    acceleration ratios ``|q'_j u + q''_j x| / a_j``; ``out[p]`` the largest
    (numpy's ``np.maximum(velocity, max_j ...)``). ``dq``, ``ddq``: (P, n);
    ``x_cap``, ``out``: (P,); ``acceleration``: (n,) 1/s^2 times rad.
    """
    for p in range(cols.shape[0]):
        x, u = _x_u(cols, X, U, z, p)
        most = -np.inf
        for j in range(dq.shape[1]):
            most = max(most, abs(dq[p, j] * u + ddq[p, j] * x) / acceleration[j])
        velocity = np.sqrt(x / x_cap[p]) if x > 0.0 else 0.0
        out[p] = max(velocity, most)


@njit(cache=True)
def acceleration_ratios(cols, X, U, z, dq, ddq, acceleration, at, out):  # noqa: D417
    """``|q'_j u + q''_j x| / a_j`` at the points ``at``, in place; ``out`` (A, n).

    x (clipped at 0) and u from the band as :func:`joint_ratios`.
    """
    for i in range(len(at)):
        p = at[i]
        x, u = _x_u(cols, X, U, z, p)
        for j in range(dq.shape[1]):
            out[i, j] = abs(dq[p, j] * u + ddq[p, j] * x) / acceleration[j]


@njit(cache=True)
def row_max(a, out):  # noqa: D417
    """``np.max(a, axis=1)`` of a (P, n) array without NaN, in place."""
    for p in range(a.shape[0]):
        most = a[p, 0]
        for j in range(1, a.shape[1]):
            most = max(most, a[p, j])
        out[p] = most


@njit(cache=True)
def _block_sum(a, start, n):  # noqa: D417
    """The pairwise sum (numpy's) of ``a[start : start + n]``, ``n <= 128``."""
    if n < 8:
        total = 0.0
        for i in range(n):
            total += a[start + i]
        return total
    r0, r1, r2, r3 = a[start], a[start + 1], a[start + 2], a[start + 3]
    r4, r5, r6, r7 = a[start + 4], a[start + 5], a[start + 6], a[start + 7]
    i = 8
    while i < n - n % 8:
        at = start + i
        r0, r1, r2, r3 = r0 + a[at], r1 + a[at + 1], r2 + a[at + 2], r3 + a[at + 3]
        r4, r5, r6, r7 = r4 + a[at + 4], r5 + a[at + 5], r6 + a[at + 6], r7 + a[at + 7]
        i += 8
    total = ((r0 + r1) + (r2 + r3)) + ((r4 + r5) + (r6 + r7))
    while i < n:
        total += a[start + i]
        i += 1
    return total


@njit(cache=True)
def _pairwise(a):  # noqa: D417
    """``np.sum(a)`` of a 1-D array, bit for bit: numpy's pairwise order.

    Blocks of at most 128 by :func:`_block_sum`; a longer range is split at
    half its length rounded down to a multiple of 8 and the two sums added
    (numpy's recursion, here on an explicit stack: numba's cache cannot
    hold a recursive function).
    """
    if len(a) <= 128:
        return _block_sum(a, 0, len(a))
    starts = np.empty(128, dtype=np.int64)
    lengths = np.empty(128, dtype=np.int64)
    values = np.empty(128)
    tasks, results = 1, 0
    starts[0], lengths[0] = 0, len(a)
    while tasks:
        tasks -= 1
        start, n = starts[tasks], lengths[tasks]
        if n < 0:  # both halves summed: add them
            results -= 1
            values[results - 1] += values[results]
        elif n <= 128:
            values[results] = _block_sum(a, start, n)
            results += 1
        else:
            half = n // 2
            half -= half % 8
            # Popped in the order: left half, right half, then their sum.
            starts[tasks], lengths[tasks] = 0, -1
            starts[tasks + 1], lengths[tasks + 1] = start + half, n - half
            starts[tasks + 2], lengths[tasks + 2] = start, half
            tasks += 3
    return values[0]


@njit(cache=True)
def interior_duration(ds, x, u, u_next, rise, square, weights):  # noqa: D417
    """``sum ds / sqrt(x(sigma))`` over interior segments (Gauss-Legendre), or inf.

    On segment i, ``x(sigma) = x_i + ds_i (rise(sigma) u_i + square(sigma)
    u_{i+1})`` (``rise = 2 sigma - sigma^2``, ``square = sigma^2`` at the
    nodes, (G,)); ``weights``: (G,) the nodes' weights on [-1, 1]. Inf where
    the lowest x of a segment (at an end or at the vertex of the quadratic)
    is <= 0. The sums are numpy's pairwise ones, so the result is
    :func:`._jerk_timed_path.quadrature_duration`'s numpy form bit for bit.
    ``ds``, ``x``, ``u``, ``u_next``: (N,) per segment, s and 1/s^2.
    """
    count = len(ds)
    for i in range(count):
        a, b = ds[i] * u[i], ds[i] * u_next[i]
        curvature = b - a
        lowest = min(x[i], x[i] + a + b)
        if curvature > 0.0:
            vertex = -a / curvature
            if 0.0 < vertex < 1.0:
                square_v = vertex * vertex
                lowest = min(
                    lowest, x[i] + (2.0 * vertex - square_v) * a + square_v * b
                )
        if lowest <= 0.0:
            return np.inf
    terms = np.empty(len(weights))
    parts = np.empty(count)
    for i in range(count):
        for k in range(len(weights)):
            at = x[i] + ds[i] * (rise[k] * u[i] + square[k] * u_next[i])
            terms[k] = weights[k] / np.sqrt(at)
        parts[i] = 0.5 * ds[i] * _pairwise(terms)
    return _pairwise(parts)


__all__ = [
    "acceleration_ratios",
    "grasp_screen",
    "interior_duration",
    "jerk_ratios",
    "joint_ratios",
    "row_max",
]
