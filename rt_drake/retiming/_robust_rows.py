"""The worst object of a set, row by row: compiled support functions.

A set of objects is a union of parameter boxes
(:mod:`rt_drake.uncertainty.inertial_set`)
``{m (c1 + G1 sigma) + cz + Gz tau}``. At one motion point (u, x) every
parameter vector maps linearly to a wrench (or to joint torques): the
vectors ``W[j] = a_j u + b_j x + c_j`` of the columns ``c1, G1_*, cz,
Gz_*``. For a row ``n`` (``n w <= 1``)
the largest value over a box is, in closed form (``m > 0``)::

    B   = n.W[c1] + sum_j |n.W[G1_j]|
    max = max(m_lo B, m_hi B) + n.W[cz] + sum_j |n.W[Gz_j]|

attained at the vertex with ``m = m_hi`` iff ``B >= 0``, ``sigma_j =
sign(n.W[G1_j])`` and ``tau_j = sign(n.W[Gz_j])``: its key (:func:`key`)
names it. Over a union, the largest box value wins.

:func:`worst_rows` evaluates every row at every point, screened: with
``w_b`` the wrench of box b's centre (``m_mid c1 + cz``) and ``rho_b`` its
spread per component (``(m_hi - m_mid) |c1| + m_hi sum_j |G1_j| + sum_j
|Gz_j|``, the box hull of the box's wrenches), each row's value is at most
``n.w_b + |n|.rho_b``; exact values are computed first for the row of
largest bound, then only for rows whose bound exceeds the largest exact value
(about three rows per point along a retimed path). Every box has a centre
column (``cz``, possibly zero).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit

from rt_drake.retiming.seidel import kernel_array

#: Bits of a vertex key below the box index.
BOX_SHIFT = 32


class Layout(NamedTuple):
    """Where each box's vectors are among the P columns.

    Attributes:
        columns: (B, 6) per box: unit column, first and end CoM generator
            column, centre column, first and end inertia column (the centre
            column is just before the inertia ones).
        masses: (B, 2) m_lo, m_hi (kg).
    """

    columns: np.ndarray
    masses: np.ndarray


class Worst(NamedTuple):
    """Result of :func:`worst_rows` at M points.

    Attributes:
        ratio: (M,) the largest row value at each point (<= 1: held).
        row: (M,) the row attaining it.
        key: (M,) its worst vertex (:func:`key`).
        bound_max: (R,) an upper bound of each row's largest value over the
            points (the screening bound).
        ranked: The values, rows and keys (each (M,
            ranks)) of the rows of largest worst value at each point, in
            decreasing order (row -1 where there are fewer rows).
    """

    ratio: np.ndarray
    row: np.ndarray
    key: np.ndarray
    bound_max: np.ndarray
    ranked: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None


def key(box: int, heavy: bool, com: np.ndarray, inertia: np.ndarray) -> int:
    """The vertex key: box index, then bit 0 heavy, then one bit per + sign."""
    bits = int(heavy)
    for j, positive in enumerate(np.concatenate([com, inertia])):
        bits |= int(positive) << (j + 1)
    return (box << BOX_SHIFT) | bits


def vertex_weights(layout: Layout, vertices: np.ndarray, columns: int) -> np.ndarray:
    """(V, P) weights of the columns whose sums are the vertices' vectors.

    Vertex ``(box, bits)`` (:func:`key`): ``m (c1 + G1 sigma) + cz + Gz tau``
    with ``m`` from bit 0 and the signs from the next bits.
    """
    vertices = np.asarray(vertices, dtype=np.int64)
    boxes = vertices >> BOX_SHIFT
    bits = vertices & ((1 << BOX_SHIFT) - 1)
    weights = np.zeros((len(vertices), columns))
    for box in np.unique(boxes).tolist():
        (rows,) = np.nonzero(boxes == box)
        unit, c0, c1, center, i0, i1 = layout.columns[box].tolist()
        code = bits[rows]
        m = layout.masses[box, code & 1]
        count = c1 - c0 + i1 - i0
        signs = 2.0 * ((code[:, None] >> np.arange(1, count + 1)) & 1) - 1.0
        weights[rows, unit] = m
        weights[rows, c0:c1] = m[:, None] * signs[:, : c1 - c0]
        weights[rows, center] = 1.0
        weights[rows, i0:i1] = signs[:, c1 - c0 :]
    return weights


def worst_rows(
    table: tuple[np.ndarray, np.ndarray, np.ndarray],
    index: np.ndarray,
    u: np.ndarray,
    x: np.ndarray,
    normals: np.ndarray,
    layout: Layout,
    ranks: int = 1,
) -> Worst:
    """The largest row value over the set at M points (module docstring).

    The column vectors at point q are ``a[i] u_q + b[i] x_q + c[i]`` with
    ``i = index[q]``.

    Args:
        table: a, b, c (T, P, D): the columns' coefficients at T places.
        index: (M,) the place of each point.
        u: (M,) s'' at each point.
        x: (M,) s'^2 at each point.
        normals: (D, R) rows ``n_k`` (the constraint is ``n_k v <= 1``).
        layout: The boxes.
        ranks: How many rows to rank at each point (the worst first).
    """
    count = len(index)
    ratio = np.empty((count, ranks))
    row = np.empty((count, ranks), dtype=np.int64)
    vertex = np.empty((count, ranks), dtype=np.int64)
    bound_max = np.full(normals.shape[1], -np.inf)
    _worst_rows(
        *(kernel_array(v) for v in table),
        np.ascontiguousarray(index, dtype=np.int64),
        kernel_array(u),
        kernel_array(x),
        kernel_array(normals),
        np.ascontiguousarray(layout.columns, dtype=np.int64),
        kernel_array(layout.masses),
        ratio,
        row,
        vertex,
        bound_max,
    )
    ranked = (ratio, row, vertex)
    return Worst(ratio[:, 0], row[:, 0], vertex[:, 0], bound_max, ranked)


@njit(cache=True)
def _exact(n, k, V, columns, masses):
    """Largest value of row k over the boxes at one point, and its key."""
    dims = V.shape[1]
    best, best_key = -np.inf, 0
    for b in range(columns.shape[0]):
        unit, c0, c1 = columns[b, 0], columns[b, 1], columns[b, 2]
        center, i0, i1 = columns[b, 3], columns[b, 4], columns[b, 5]
        B = 0.0
        for d in range(dims):
            B += n[d, k] * V[unit, d]
        bits = 0
        for j in range(c0, c1):
            value = 0.0
            for d in range(dims):
                value += n[d, k] * V[j, d]
            if value >= 0.0:
                bits |= 1 << (j - c0 + 1)
            B += abs(value)
        if B >= 0.0:
            total = masses[b, 1] * B
            bits |= 1
        else:
            total = masses[b, 0] * B
        offset = c1 - c0 + 1
        for j in range(center, i1):
            value = 0.0
            for d in range(dims):
                value += n[d, k] * V[j, d]
            if j == center:
                total += value
                continue
            if value >= 0.0:
                bits |= 1 << (j - i0 + offset)
            total += abs(value)
        if total > best:
            best, best_key = total, (b << BOX_SHIFT) | bits
    return best, best_key


@njit(cache=True)
def _bounds(V, n, absn, columns, masses, centre, spread, tmp, bound):
    """``bound[k] >= max_set n_k v``: the box hull of each box, per dimension.

    With ``w_b`` the centre (``m_mid c1 + cz``) and ``rho_b`` the per-dimension
    spread (``(m_hi - m_mid) |c1| + m_hi sum |G1_j| + sum |Gz_j|``), the value
    of row k over box b is at most ``n_k w_b + |n_k| rho_b``.
    """
    dims, rows = n.shape
    for b in range(columns.shape[0]):
        unit, c0, c1 = columns[b, 0], columns[b, 1], columns[b, 2]
        center, i0, i1 = columns[b, 3], columns[b, 4], columns[b, 5]
        m_lo, m_hi = masses[b, 0], masses[b, 1]
        mid = 0.5 * (m_lo + m_hi)
        for d in range(dims):
            centre[d] = mid * V[unit, d] + V[center, d]
            rho = (m_hi - mid) * abs(V[unit, d])
            for j in range(c0, c1):
                rho += m_hi * abs(V[j, d])
            for j in range(i0, i1):
                rho += abs(V[j, d])
            spread[d] = rho
        if dims == 6:  # a wrench: unrolled, vectorised over the rows
            c0, c1, c2, c3, c4, c5 = (
                centre[0],
                centre[1],
                centre[2],
                centre[3],
                centre[4],
                centre[5],
            )
            s0, s1, s2, s3, s4, s5 = (
                spread[0],
                spread[1],
                spread[2],
                spread[3],
                spread[4],
                spread[5],
            )
            for k in range(rows):
                tmp[k] = (
                    n[0, k] * c0
                    + n[1, k] * c1
                    + n[2, k] * c2
                    + n[3, k] * c3
                    + n[4, k] * c4
                    + n[5, k] * c5
                    + absn[0, k] * s0
                    + absn[1, k] * s1
                    + absn[2, k] * s2
                    + absn[3, k] * s3
                    + absn[4, k] * s4
                    + absn[5, k] * s5
                )
        else:
            for k in range(rows):
                tmp[k] = 0.0
            for d in range(dims):
                cd, sd = centre[d], spread[d]
                for k in range(rows):
                    tmp[k] += n[d, k] * cd + absn[d, k] * sd
        if b == 0:
            for k in range(rows):
                bound[k] = tmp[k]
        else:
            for k in range(rows):
                if tmp[k] > bound[k]:
                    bound[k] = tmp[k]


@njit(cache=True)
def _insert(values, rows, keys, value, row, key):
    """Put (value, row, key) into the descending top list if it belongs."""
    slots = values.shape[0]
    if value <= values[slots - 1]:
        return
    j = slots - 1
    while j > 0 and values[j - 1] < value:
        values[j], rows[j], keys[j] = values[j - 1], rows[j - 1], keys[j - 1]
        j -= 1
    values[j], rows[j], keys[j] = value, row, key


@njit(cache=True)
def _worst_rows(
    a, b, c, index, u, x, n, columns, masses, ratio, row, vertex, bound_max
):
    dims, rows = n.shape
    slots = ratio.shape[1]
    absn = np.abs(n)
    centre = np.empty(dims)
    spread = np.empty(dims)
    tmp = np.empty(rows)
    bound = np.empty(rows)
    V = np.empty(a.shape[1:])
    for i in range(index.shape[0]):
        place, u_i, x_i = index[i], u[i], x[i]
        for j in range(V.shape[0]):
            for d in range(dims):
                V[j, d] = a[place, j, d] * u_i + b[place, j, d] * x_i + c[place, j, d]
        _bounds(V, n, absn, columns, masses, centre, spread, tmp, bound)
        values, best_rows, keys = ratio[i], row[i], vertex[i]
        values[:] = -np.inf
        best_rows[:] = -1
        keys[:] = 0
        # The row of largest bound first; then only rows whose bound exceeds
        # the slots-th best exact value so far can enter the ranking.
        top, top_bound = 0, -np.inf
        for k in range(rows):
            value = bound[k]
            if value > bound_max[k]:
                bound_max[k] = value
            if value > top_bound:
                top, top_bound = k, value
        value, key = _exact(n, top, V, columns, masses)
        _insert(values, best_rows, keys, value, top, key)
        for k in range(rows):
            if bound[k] > values[slots - 1] and k != top:
                value, key = _exact(n, k, V, columns, masses)
                _insert(values, best_rows, keys, value, k, key)


__all__ = [
    "BOX_SHIFT",
    "Layout",
    "Worst",
    "key",
    "vertex_weights",
    "worst_rows",
]
