"""Compiled (numba) loops of the jerk-limited retimer: one pass, no temporaries.

:func:`grasp_screen`: at every dense point p the object wrench ``w_p = a_p
u_p + b_p x_p + c_p`` (N, N m, in the cup frame of :mod:`._samples`) and
each grasp row's ratio ``F_r w_p / g_r`` (``scaled = F / g``), reduced as it
is made to the largest ratio per point and the (point, row) pairs at or
above a threshold. The (P, R) ratios are never stored: with numpy they
were three (P, R) temporaries per call. :func:`jerk_ratios`: the joint
jerk at every jerk point. The LPs' rows, made straight into the compressed
blocks the LP stacks: :func:`jerk_block` (the jerk's tangent rows) and
:func:`affine_block` (velocity, acceleration, torque, ``x >= 0``); their
sparse products and row selections :func:`csr_product`, :func:`csr_rows`
(scipy's sums and rows, bit for bit). :func:`interior_duration`: the
duration by quadrature, its sums in numpy's pairwise order. Arrays are
C-contiguous float64 (int64 indices, scipy's int32 for the CSR arrays).
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def grasp_screen(a, b, c, x, u, scaled_t, threshold, over, largest):  # noqa: D417
    """``over[p, r] = F_r w_p / g_r >= threshold``; ``largest[p]`` the max over r.

    ``a``, ``b``, ``c``: (P, 6); ``x``, ``u``: (P,); ``scaled_t``: (6, R),
    ``(F / g)`` transposed (the loop over rows innermost, vectorised);
    ``over``: (P, R) bool and ``largest``: (P,), written in place.
    """
    rows = scaled_t.shape[1]
    ratio = np.empty(rows)
    for p in range(a.shape[0]):
        ratio[:] = 0.0
        for k in range(a.shape[1]):
            w = a[p, k] * u[p] + b[p, k] * x[p] + c[p, k]
            for r in range(rows):
                ratio[r] += w * scaled_t[k, r]
        most = -np.inf
        for r in range(rows):
            over[p, r] = ratio[r] >= threshold
            most = max(most, ratio[r])
        largest[p] = most


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
def jerk_block(  # noqa: D417
    cols, X, U, K, index, keep, dq, ddq, dddq, x_root, x_power, jerk, kind, shift
):
    """The jerk rows of :func:`._jerk_rows.jerk_rows` (its docstring), compressed.

    At each point ``p = index[i]`` and joint j with ``keep[i, j]``: ``B =
    q'_j K + 3 q''_j U + q'''_j X`` (the band's three entries at p) and the
    tangent ``J_j X / (2 xbar^1.5)``; the rows ``+-B + tangent <= 1.5 J_j /
    sqrt(xbar)``, those of the sign +1 first (pairs in row-major order),
    then those of -1, zero entries dropped (:func:`._jerk_rows.block`).
    ``cols``, ``X``, ``U``, ``K``: (P, 3) the band of every point; ``dq``,
    ``ddq``, ``dddq``: (P, n); ``index``: (I,); ``keep``: (I, n) bool;
    ``x_root``, ``x_power``: (I,) ``sqrt(xbar)`` and ``xbar^1.5`` there
    (> 0); ``jerk``: (n,); keys ``kind << shift + p << 24 + j`` (``kind +
    1`` for the sign -1). Returns the block's ``values``, ``cols``,
    ``counts``, ``bound`` and ``keys``.
    """
    pairs = 0
    for i in range(keep.shape[0]):
        for j in range(keep.shape[1]):
            if keep[i, j]:
                pairs += 1
    rows = np.empty((2 * pairs, 3))
    bound = np.empty(2 * pairs)
    keys = np.empty(2 * pairs, dtype=np.int64)
    at = np.empty(pairs, dtype=np.int64)
    row = 0
    for i in range(keep.shape[0]):
        p = index[i]
        for j in range(keep.shape[1]):
            if not keep[i, j]:
                continue
            slope = 0.5 * jerk[j] / x_power[i]
            bound[row] = 1.5 * jerk[j] / x_root[i]
            bound[pairs + row] = bound[row]
            three = 3.0 * ddq[p, j]
            for e in range(3):
                B = dq[p, j] * K[p, e] + three * U[p, e] + dddq[p, j] * X[p, e]
                tangent = slope * X[p, e]
                rows[row, e] = B + tangent
                rows[pairs + row, e] = tangent - B
            point = np.int64(p) << 24
            keys[row] = (np.int64(kind) << shift) + point + j
            keys[pairs + row] = (np.int64(kind + 1) << shift) + point + j
            at[row] = p
            row += 1
    values = np.empty(6 * pairs)
    columns = np.empty(6 * pairs, dtype=cols.dtype)
    counts = np.empty(2 * pairs, dtype=np.int64)
    entries = 0
    for r in range(2 * pairs):
        p = at[r % pairs] if pairs else 0
        count = 0
        for e in range(3):
            if rows[r, e] != 0.0:
                values[entries] = rows[r, e]
                columns[entries] = cols[p, e]
                entries += 1
                count += 1
        counts[r] = count
    return values[:entries], columns[:entries], counts, bound, keys


@njit(cache=True)
def affine_block(cols, X, U, points, alpha, beta, bound, kind, shift):  # noqa: D417
    """The rows of :func:`._jerk_rows.affine_rows` (its docstring), compressed.

    At each point i (``cols``, ``X``, ``U``: (I, 3), its band) and column m
    with ``bound[i, m]`` finite: the row ``alpha[i, m] U + beta[i, m] X <=
    bound[i, m]`` (pairs in row-major order, zero entries dropped, as
    :func:`._jerk_rows.block`), key ``kind << shift + points[i] << 24 + m``.
    ``alpha``, ``beta``, ``bound``: (I, M). Returns the block's ``values``,
    ``cols``, ``counts``, ``bound`` and ``keys``.
    """
    rows = 0
    for i in range(bound.shape[0]):
        for m in range(bound.shape[1]):
            if np.isfinite(bound[i, m]):
                rows += 1
    values = np.empty(3 * rows)
    columns = np.empty(3 * rows, dtype=cols.dtype)
    counts = np.empty(rows, dtype=np.int64)
    bounds = np.empty(rows)
    keys = np.empty(rows, dtype=np.int64)
    row = entries = 0
    for i in range(bound.shape[0]):
        for m in range(bound.shape[1]):
            if not np.isfinite(bound[i, m]):
                continue
            count = 0
            for e in range(3):
                value = alpha[i, m] * U[i, e] + beta[i, m] * X[i, e]
                if value != 0.0:
                    values[entries] = value
                    columns[entries] = cols[i, e]
                    entries += 1
                    count += 1
            counts[row] = count
            bounds[row] = bound[i, m]
            keys[row] = (np.int64(kind) << shift) + (np.int64(points[i]) << 24) + m
            row += 1
    return values[:entries], columns[:entries], counts, bounds, keys


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


@njit(cache=True)
def csr_product(indptr, indices, data, z):  # noqa: D417
    """``A z`` of a CSR matrix A (``indptr``, ``indices``, ``data``), (R,).

    Each row's sum from 0.0 in the order of its entries: scipy's
    ``csr_matvec`` bit for bit.
    """
    out = np.empty(len(indptr) - 1)
    for r in range(len(indptr) - 1):
        total = 0.0
        for e in range(indptr[r], indptr[r + 1]):
            total += data[e] * z[indices[e]]
        out[r] = total
    return out


@njit(cache=True)
def csr_rows(indptr, indices, data, rows):  # noqa: D417
    """The rows ``rows`` of a CSR matrix: their starts (int32), columns (int32), values.

    Entries in their order within each row (as ``A[rows]``); starts
    ``(len(rows) + 1,)``.
    """
    start = np.empty(len(rows) + 1, dtype=np.int32)
    start[0] = 0
    for i in range(len(rows)):
        start[i + 1] = start[i] + indptr[rows[i] + 1] - indptr[rows[i]]
    index = np.empty(start[-1], dtype=np.int32)
    value = np.empty(start[-1])
    for i in range(len(rows)):
        at = start[i]
        for e in range(indptr[rows[i]], indptr[rows[i] + 1]):
            index[at] = indices[e]
            value[at] = data[e]
            at += 1
    return start, index, value


__all__ = [
    "affine_block",
    "csr_product",
    "csr_rows",
    "grasp_screen",
    "interior_duration",
    "jerk_block",
    "jerk_ratios",
]
