"""The rows of the jerk-limited retimer's LPs, at points inside the segments.

The LP variables are ``z = [x_0..x_N, u_0..u_N]``: ``x = s'^2`` and the path
acceleration ``u = s''`` at the grid points (1/s^2). At a point ``sigma`` of
segment i, ``x``, ``u`` and ``k = du/ds`` are linear in z
(:mod:`._jerk_timed_path`): :meth:`Band.maps` gives the sparse rows
``X z``, ``U z`` (k's three entries stay in :class:`Band`). Every limit
but the jerk is then linear in z, and exact at the point:

- velocity ``x <= min_j v_j^2 / q'_j^2`` and ``x >= 0``;
- acceleration ``|q'_j u + q''_j x| <= a_j``;
- torque ``|a_j u + b_j x + c_j| <= tau_j``;
- grasp ``F_r (a u + b x + c) <= g_r`` (the rows asked for).

The jerk ``q'''_j = s' B_j``, ``B_j = q'_j k + 3 q''_j u + q'''_j x``, with
``s' = sqrt(x)``: ``|B_j| <= J_j / sqrt(x)``. The right side is convex in x,
so its tangent at the previous iterate ``xbar`` lies below it:
``|B_j| <= J_j (1.5 / sqrt(xbar) - x / (2 xbar^1.5))`` is an inner (safe)
linear row, exact at ``x = xbar`` (:func:`jerk_rows`). On a start from rest
the jerk is ``u_1^1.5 K_j(sigma)`` in closed form, a bound on u_1
(:func:`rest_bound`), and likewise before a stop.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
from scipy import sparse

from rt_drake.retiming._jerk_row_kernels import affine_block, csr_product, jerk_block
from rt_drake.retiming._jerk_timed_path import Piece


class RowMatrix(NamedTuple):
    """A (R, ``shape[1]``) matrix in scipy's CSR arrays, without scipy's object.

    ``indptr`` (R + 1,), ``indices`` int32 and ``data`` float64 as
    :class:`scipy.sparse.csr_matrix` holds them: :class:`._jerk_lp.WarmLP`
    reads only these (and ``shape``), so its LPs skip scipy's constructor.
    """

    indptr: np.ndarray
    indices: np.ndarray
    data: np.ndarray
    shape: tuple[int, int]

    def tocsr(self) -> sparse.csr_matrix:
        """The same matrix as scipy's (for scipy's solvers and tests)."""
        return sparse.csr_matrix((self.data, self.indices, self.indptr), self.shape)


class PointMaps(NamedTuple):
    """``x`` and ``u`` at P points as sparse (P, 2(N+1)) rows of z.

    In scipy's CSR arrays (:class:`RowMatrix`; ``tocsr()`` for scipy's).
    """

    X: RowMatrix
    U: RowMatrix

    def x(self, z: np.ndarray) -> np.ndarray:
        """``X z``, (P,): scipy's product bit for bit, without its dispatch."""
        return _times(self.X, z)

    def u(self, z: np.ndarray) -> np.ndarray:
        """``U z``, (P,), likewise."""
        return _times(self.U, z)


def _times(A: RowMatrix, z: np.ndarray) -> np.ndarray:
    """``A @ z`` by :func:`._jerk_row_kernels.csr_product` (the same sums)."""
    return csr_product(A.indptr, A.indices, A.data, np.asarray(z, dtype=float))


class Band(NamedTuple):
    """``x``, ``u``, ``k`` at P points as three entries each.

    Each point's x, u and k are linear in the three variables ``cols[p] =
    (x_i, u_i, u_{i+1})`` of its segment i: ``x_p = X[p] . z[cols[p]]``, and
    likewise U and K; all (P, 3).
    """

    cols: np.ndarray
    X: np.ndarray
    U: np.ndarray
    K: np.ndarray

    @staticmethod
    def of(
        s: np.ndarray, kinds: np.ndarray, segment: np.ndarray, sigma: np.ndarray
    ) -> Band:
        """x, u and k = du/ds at ``sigma`` of ``segment`` (module docstring).

        Interior piece i: ``x = x_i + ds ((2 sig - sig^2) u_i + sig^2
        u_{i+1})``, ``u = (1 - sig) u_i + sig u_{i+1}``, ``k = (u_{i+1} -
        u_i) / ds``. Start: ``x = 1.5 ds u_1 sig^(4/3)``, ``u = u_1
        sig^(1/3)``, ``k`` 0 (its jerk is :func:`rest_bound`'s); a stop
        mirrored (``sig -> 1 - sig``, on ``u_{N-1}``, x with the sign flipped).
        """
        size = len(s)
        ds = np.diff(s)[segment]
        kind = kinds[segment]
        start, stop = kind == Piece.START, kind == Piece.STOP
        inner = ~(start | stop)
        sig = sigma
        X, U, K = (np.zeros((len(segment), 3)) for _ in range(3))
        X[inner, 0] = 1.0
        X[inner, 1] = (ds * (2.0 * sig - sig**2))[inner]
        X[inner, 2] = (ds * sig**2)[inner]
        U[inner, 1], U[inner, 2] = (1.0 - sig)[inner], sig[inner]
        K[inner, 1], K[inner, 2] = -1.0 / ds[inner], 1.0 / ds[inner]
        for edge, rest, column, sign in (
            (start, sig, 2, 1.0),
            (stop, 1.0 - sig, 1, -1.0),
        ):
            X[edge, column] = sign * 1.5 * ds[edge] * rest[edge] ** (4.0 / 3.0)
            U[edge, column] = rest[edge] ** (1.0 / 3.0)
        cols = np.column_stack([segment, size + segment, size + segment + 1])
        return Band(cols, X, U, K)

    def maps(self, size: int) -> PointMaps:
        """The band as sparse (P, 2 ``size``) rows of z (zeros kept)."""
        P = len(self.cols)
        indptr = 3 * np.arange(P + 1, dtype=np.int32)
        indices = self.cols.ravel().astype(np.int32)

        def matrix(values: np.ndarray) -> RowMatrix:
            return RowMatrix(indptr, indices, values.ravel(), (P, 2 * size))

        return PointMaps(matrix(self.X), matrix(self.U))

    def take(self, index: np.ndarray) -> Band:
        """The band at the points ``index``."""
        return Band(self.cols[index], self.X[index], self.U[index], self.K[index])


class Rows(NamedTuple):
    """LP rows ``values . z[cols] <= bound``, each named by a key.

    ``cols``, ``values``: (R, 3); ``bound``, ``keys``: (R,). A key names one
    row across the LPs of a retime (kind of row, point, joint or grasp row:
    :func:`key`), so that one LP's basis can start the next.
    """

    cols: np.ndarray
    values: np.ndarray
    bound: np.ndarray
    keys: np.ndarray


def key(kind: int, point: np.ndarray, column: np.ndarray) -> np.ndarray:
    """``kind * 2^52 + point * 2^24 + column`` (point < 2^28, column < 2^24)."""
    return (
        (int(kind) << KIND_SHIFT)
        + (point.astype(np.int64) << 24)
        + column.astype(np.int64)
    )


class Block(NamedTuple):
    """Rows in compressed form: their nonzero entries row by row.

    ``values``, ``cols``: the nonzero entries and their columns; ``counts``:
    (R,) entries per row; ``bound``, ``keys``: (R,) as in :class:`Rows`.
    """

    values: np.ndarray
    cols: np.ndarray
    counts: np.ndarray
    bound: np.ndarray
    keys: np.ndarray


def affine_rows(
    band: Band,
    points: np.ndarray,
    kind: int | Sequence[int],
    alpha: np.ndarray,
    beta: np.ndarray,
    bound: np.ndarray,
) -> Block:
    """Rows ``alpha[p, m] u_p + beta[p, m] x_p <= bound[p, m]`` (finite bounds).

    ``band``: the P points; ``points``: (P,) their indices among all points
    (for the keys); ``alpha``, ``beta``: broadcast to ``bound``'s (P, M).
    Pairs (p, m) in row-major order, compressed
    (:func:`._jerk_row_kernels.affine_block`). With B kinds (a sequence),
    ``bound`` is (B, P, M): B blocks one after the other, block b's keys
    of ``kind[b]``.
    """
    kinds = np.atleast_1d(np.asarray(kind, dtype=np.int64))
    bound = np.asarray(bound, dtype=float)
    if bound.ndim == 2:
        bound = bound[None]
    # Copies: writable and contiguous, so that one compiled form serves.
    alpha, beta = (
        np.array(np.broadcast_to(v, bound.shape), dtype=float) for v in (alpha, beta)
    )
    return Block(
        *affine_block(
            np.ascontiguousarray(band.cols), np.ascontiguousarray(band.X),
            np.ascontiguousarray(band.U), np.asarray(points, dtype=np.int64), alpha,
            beta, np.ascontiguousarray(bound), kinds, KIND_SHIFT,
        )
    )  # fmt: skip


def jerk_rows(
    band: Band,
    index: np.ndarray,
    kind: int,
    derivatives: tuple[np.ndarray, np.ndarray, np.ndarray],
    x_bar: np.ndarray,
    jerk: np.ndarray,
    keep: np.ndarray,
) -> Block:
    """``+-B_j + J_j x / (2 xbar^1.5) <= 1.5 J_j / sqrt(xbar)`` at interior points.

    ``band``: x, u, k of every point; ``index``: (I,) the points (on
    interior pieces); ``derivatives``: the path's first, second and third
    derivatives (P, n) at every point (the third on the piece's own side of
    a knot); ``x_bar``: (I,) > 0 the previous iterate there; ``keep``: (I,
    n) which joints' rows to make. ``B_j = q'_j k + 3 q''_j u + q'''_j x``.
    Rows of the sign +1 (keys of ``kind``) first, then those of -1 (``kind
    + 1``); compressed (:func:`._jerk_kernels.jerk_block`).
    """
    dq, ddq, dddq = derivatives
    return Block(
        *jerk_block(
            band.cols, band.X, band.U, band.K, np.asarray(index, dtype=np.int64),
            np.ascontiguousarray(keep), dq, ddq, dddq, np.sqrt(x_bar),
            x_bar**1.5, np.array(jerk, dtype=float), int(kind), KIND_SHIFT,
        )
    )  # fmt: skip


def block(rows: list[Rows]) -> Block:
    """The rows, one after the other, with their zero entries dropped."""
    cols = np.concatenate([r.cols for r in rows])
    values = np.concatenate([r.values for r in rows])
    nonzero = values != 0.0
    return Block(
        values[nonzero],
        cols[nonzero],
        nonzero.sum(axis=1),
        np.concatenate([r.bound for r in rows]),
        np.concatenate([r.keys for r in rows]),
    )


def joined(blocks: list[Block]) -> Block:
    """The blocks, one after the other."""
    return Block(*(np.concatenate(parts) for parts in zip(*blocks, strict=True)))


def stacked(blocks: list[Block], size: int) -> tuple[RowMatrix, np.ndarray, np.ndarray]:
    """The blocks as one (R, size) :class:`RowMatrix`, their bounds and keys."""
    counts = np.concatenate([b.counts for b in blocks])
    indptr = np.zeros(len(counts) + 1, dtype=np.int32)
    np.cumsum(counts, out=indptr[1:])
    A = RowMatrix(
        indptr,
        np.concatenate([b.cols for b in blocks]).astype(np.int32),
        np.concatenate([b.values for b in blocks]).astype(float),
        (len(counts), size),
    )
    return (
        A,
        np.concatenate([b.bound for b in blocks]),
        np.concatenate([b.keys for b in blocks]),
    )


def jerk_values(
    x: np.ndarray,
    u: np.ndarray,
    k: np.ndarray,
    dq: np.ndarray,
    ddq: np.ndarray,
    dddq: np.ndarray,
) -> np.ndarray:
    """The joint jerk ``sqrt(x) (q' k + 3 q'' u + q''' x)`` at points, (P, n)."""
    x = np.maximum(x, 0.0)[:, None]
    return np.sqrt(x) * (dq * k[:, None] + 3.0 * ddq * u[:, None] + dddq * x)


def rest_bound(
    ds: float,
    dq: np.ndarray,
    ddq: np.ndarray,
    dddq: np.ndarray,
    rest: np.ndarray,
    jerk: np.ndarray,
) -> float:
    """Largest ``|u|`` at the far end of a start from rest (or a stop), by the jerk.

    With ``r`` the fraction of the piece from the rest end and the path's
    derivatives taken pointing away from rest, the joint jerk is
    ``|u|^1.5 K(r)``, ``K = q'/sqrt(6 ds) + 3 q'' sqrt(1.5 ds) r + q''' (1.5
    ds)^1.5 r^2`` (:mod:`._jerk_timed_path`); the bound is ``min (J / |K|)^(2/3)``
    over the points given ((P,) ``rest``, (P, n) derivatives).
    """
    K = (
        dq / np.sqrt(6.0 * ds)
        + 3.0 * ddq * np.sqrt(1.5 * ds) * rest[:, None]
        + dddq * (1.5 * ds) ** 1.5 * rest[:, None] ** 2
    )
    with np.errstate(divide="ignore"):
        return float(np.min((jerk[None, :] / np.abs(K)) ** (2.0 / 3.0)))


#: The key bits below a row's kind (:func:`key`).
KIND_SHIFT = 52

__all__ = [
    "KIND_SHIFT",
    "Band",
    "Block",
    "PointMaps",
    "RowMatrix",
    "Rows",
    "affine_rows",
    "block",
    "joined",
    "key",
    "stacked",
    "jerk_rows",
    "jerk_values",
    "rest_bound",
]
