"""Compiled (numba) loops of the jerk-limited retimer's LP rows.

The rows are made straight into the compressed blocks the LP stacks
(:class:`._jerk_rows.Block`: nonzero entries row by row, zeros dropped):
:func:`jerk_block` (the jerk's tangent rows) and :func:`affine_block`
(velocity, acceleration, torque, ``x >= 0``). The LP wrapper's sparse
products and row selections are :func:`csr_product` and :func:`csr_rows`
(scipy's sums and rows, bit for bit). Arrays are C-contiguous float64,
int64 indices (scipy's int32 for the CSR arrays).
"""

from __future__ import annotations

import numpy as np
from numba import njit


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
def affine_block(cols, X, U, points, alpha, beta, bound, kinds, shift):  # noqa: D417
    """The rows of :func:`._jerk_rows.affine_rows` (its docstring), compressed.

    B blocks of rows, one after the other: in block ``b``, at each point i
    (``cols``, ``X``, ``U``: (I, 3), its band) and column m with ``bound[b,
    i, m]`` finite, the row ``alpha[b, i, m] U + beta[b, i, m] X <= bound[b,
    i, m]`` (pairs in row-major order, zero entries dropped, as
    :func:`._jerk_rows.block`), key ``kinds[b] << shift + points[i] << 24 +
    m``. ``alpha``, ``beta``, ``bound``: (B, I, M). Returns the blocks'
    ``values``, ``cols``, ``counts``, ``bound`` and ``keys``.
    """
    rows = 0
    for b in range(bound.shape[0]):
        for i in range(bound.shape[1]):
            for m in range(bound.shape[2]):
                if np.isfinite(bound[b, i, m]):
                    rows += 1
    values = np.empty(3 * rows)
    columns = np.empty(3 * rows, dtype=cols.dtype)
    counts = np.empty(rows, dtype=np.int64)
    bounds = np.empty(rows)
    keys = np.empty(rows, dtype=np.int64)
    row = entries = 0
    for b in range(bound.shape[0]):
        kind = np.int64(kinds[b]) << shift
        for i in range(bound.shape[1]):
            point = np.int64(points[i]) << 24
            for m in range(bound.shape[2]):
                if not np.isfinite(bound[b, i, m]):
                    continue
                count = 0
                for e in range(3):
                    value = alpha[b, i, m] * U[i, e] + beta[b, i, m] * X[i, e]
                    if value != 0.0:
                        values[entries] = value
                        columns[entries] = cols[i, e]
                        entries += 1
                        count += 1
                counts[row] = count
                bounds[row] = bound[b, i, m]
                keys[row] = kind + point + m
                row += 1
    return values[:entries], columns[:entries], counts, bounds, keys


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


__all__ = ["affine_block", "csr_product", "csr_rows", "jerk_block"]
