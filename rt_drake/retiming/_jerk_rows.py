"""The rows of the jerk-limited retimer's LPs, at points inside the segments.

The LP variables are ``z = [x_0..x_N, u_0..u_N]``: ``x = s'^2`` and the path
acceleration ``u = s''`` at the grid points (1/s^2). At a point ``sigma`` of
segment i, ``x``, ``u`` and ``k = du/ds`` are linear in z
(:mod:`._jerk_timed_path`): :func:`point_maps` gives the sparse rows
``X z``, ``U z``, ``K z``. Every limit but the jerk is then linear in z, and
exact at the point:

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

from typing import NamedTuple

import numpy as np
from scipy import sparse

from rt_drake.retiming._jerk_timed_path import Piece


class PointMaps(NamedTuple):
    """``x``, ``u``, ``k`` at P points as sparse (P, 2(N+1)) rows of z."""

    X: sparse.csr_matrix
    U: sparse.csr_matrix
    K: sparse.csr_matrix


def point_maps(
    s: np.ndarray, kinds: np.ndarray, segment: np.ndarray, sigma: np.ndarray
) -> PointMaps:
    """The rows of x, u and k = du/ds at ``sigma`` of ``segment`` (module docstring).

    ``k`` is 0 on START and STOP pieces (their jerk is :func:`rest_bound`'s).
    """
    n_var = 2 * len(s)
    ds = np.diff(s)[segment]
    i = segment
    x_i, u_i, u_next = i, len(s) + i, len(s) + i + 1
    kind = kinds[segment]
    start, stop = kind == Piece.START, kind == Piece.STOP
    inner = ~(start | stop)
    sig = sigma
    rest = np.where(start, sig, 1.0 - sig)
    rows = np.arange(len(i))
    cols_x, vals_x, rows_x = [], [], []
    cols_u, vals_u, rows_u = [], [], []
    # Interior: x = x_i + ds ((2 sig - sig^2) u_i + sig^2 u_{i+1}).
    rows_x += [rows[inner]] * 3
    cols_x += [x_i[inner], u_i[inner], u_next[inner]]
    vals_x += [
        np.ones(inner.sum()),
        (ds * (2.0 * sig - sig**2))[inner],
        (ds * sig**2)[inner],
    ]
    rows_u += [rows[inner]] * 2
    cols_u += [u_i[inner], u_next[inner]]
    vals_u += [(1.0 - sig)[inner], sig[inner]]
    # Start: x = 1.5 ds u_1 sig^(4/3), u = u_1 sig^(1/3); stop mirrored.
    edge = start | stop
    which = np.where(start, u_next, u_i)[edge]
    sign = np.where(start, 1.0, -1.0)[edge]
    rows_x.append(rows[edge])
    cols_x.append(which)
    vals_x.append(sign * 1.5 * ds[edge] * rest[edge] ** (4.0 / 3.0))
    rows_u.append(rows[edge])
    cols_u.append(which)
    vals_u.append(rest[edge] ** (1.0 / 3.0))
    shape = (len(i), n_var)

    def matrix(r: list, c: list, v: list) -> sparse.csr_matrix:
        return sparse.csr_matrix(
            (np.concatenate(v), (np.concatenate(r), np.concatenate(c))), shape=shape
        )

    K = matrix(
        [rows[inner]] * 2,
        [u_i[inner], u_next[inner]],
        [-1.0 / ds[inner], 1.0 / ds[inner]],
    )
    return PointMaps(matrix(rows_x, cols_x, vals_x), matrix(rows_u, cols_u, vals_u), K)


def affine_rows(
    maps: PointMaps, alpha: np.ndarray, beta: np.ndarray, bound: np.ndarray
) -> tuple[sparse.csr_matrix, np.ndarray]:
    """Rows ``alpha[p, m] u_p + beta[p, m] x_p <= bound[p, m]`` (finite bounds).

    ``alpha``, ``beta``, ``bound``: (P, M). Returns (A, b).
    """
    keep = np.isfinite(bound)
    p, _ = np.nonzero(keep)
    A = sparse.diags(alpha[keep]) @ maps.U[p] + sparse.diags(beta[keep]) @ maps.X[p]
    return sparse.csr_matrix(A), bound[keep]


def jerk_rows(
    maps: PointMaps,
    inner: np.ndarray,
    dq: np.ndarray,
    ddq: np.ndarray,
    dddq: np.ndarray,
    x_bar: np.ndarray,
    jerk: np.ndarray,
    keep: np.ndarray | None = None,
) -> tuple[sparse.csr_matrix, np.ndarray]:
    """``+-B_j + J_j x / (2 xbar^1.5) <= 1.5 J_j / sqrt(xbar)`` at interior points.

    ``inner``: (P,) which points lie on interior pieces; ``dq``, ``ddq``,
    ``dddq``: (P, n) the path's derivatives there (the third on the piece's
    own side of a knot); ``x_bar``: (P,) > 0 the previous iterate; ``keep``:
    (P, n) which joints' rows to make (None: all).
    """
    index = np.flatnonzero(inner)
    X, U, K = (m[index] for m in maps)
    slope = 0.5 * jerk[None, :] / x_bar[index, None] ** 1.5
    bound = 1.5 * jerk[None, :] / np.sqrt(x_bar[index, None])
    chosen = np.ones(bound.shape, dtype=bool) if keep is None else keep[index]
    blocks, rhs = [], []
    p, _ = np.nonzero(chosen)
    for sign in (1.0, -1.0):
        a_k = sign * dq[index][chosen]
        a_u = sign * 3.0 * ddq[index][chosen]
        a_x = (sign * dddq[index] + slope)[chosen]
        blocks.append(
            sparse.diags(a_k) @ K[p]
            + sparse.diags(a_u) @ U[p]
            + sparse.diags(a_x) @ X[p]
        )
        rhs.append(bound[chosen])
    return sparse.csr_matrix(sparse.vstack(blocks)), np.concatenate(rhs)


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


__all__ = [
    "PointMaps",
    "affine_rows",
    "jerk_rows",
    "jerk_values",
    "point_maps",
    "rest_bound",
]
