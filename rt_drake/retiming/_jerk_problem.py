"""The jerk-limited retimer's LP, one step of its sequence (:mod:`._jerk`).

The variables are ``z = [x_0..x_N, u_0..u_N]`` (``x = s'^2``, ``u = s''``
at the grid points; 1/s^2). :class:`Problem` holds what is fixed for one
retime (the points, the equalities ``x_{i+1} - x_i - ds_i (u_i + u_{i+1})
= 0``, the Bernstein rows ``x_i + ds_i u_i >= 0`` and the bounds of z);
:class:`Selection` which points and rows the next LP takes (it grows
between rounds). :func:`solve_lp` makes the LP at the previous profile
``xbar``: maximise the first-order decrease of the duration ``T = sum ds /
sqrt(x)`` (Simpson's rule on each segment) under the rows of
:mod:`._jerk_rows` (the jerk rows linearised at ``xbar``), and solves it
with :class:`._jerk_lp.WarmLP`.
"""

from __future__ import annotations

import dataclasses
import enum
import functools

import numpy as np
from scipy import sparse

from rt_drake.retiming._jerk_lp import WarmLP
from rt_drake.retiming._jerk_points import (
    DENSE,
    JERK_DENSE,
    DensePoints,
    JerkPoints,
    Keep,
)
from rt_drake.retiming._jerk_rows import (
    KIND_SHIFT,
    Band,
    Block,
    Rows,
    affine_rows,
    block,
    jerk_rows,
    joined,
    key,
    stacked,
)
from rt_drake.retiming._jerk_set import SetPairs
from rt_drake.retiming._jerk_timed_path import Piece
from rt_drake.retiming._retime_errors import PathNotControllableError
from rt_drake.retiming.limits import JointLimits


class Kind(enum.IntEnum):
    """The kinds of LP rows, for their keys (a sign's rows: kind and kind + 1)."""

    VELOCITY = 0
    POSITIVE = 1
    ACCELERATION = 2
    TORQUE = 4
    GRASP = 6
    JERK = 7
    JERK_POINT_ACCELERATION = 9
    JERK_POINT_VELOCITY = 11
    MIDDLE = 12
    BERNSTEIN = 13


@dataclasses.dataclass(frozen=True, eq=False)
class Problem:
    """What the LPs are built from (fixed for one retime)."""

    s: np.ndarray
    kinds: np.ndarray
    dense: DensePoints
    jerk: JerkPoints
    limits: JointLimits
    bounds: dict[int, tuple[int, float]]
    middle: np.ndarray
    #: x at the middle points as rows of z, transposed: (2(N+1), N)
    #: (:func:`middle_rows`).
    X_middle_T: sparse.csc_matrix
    bernstein: Rows
    equalities: tuple[sparse.csr_matrix, np.ndarray]
    variable_bounds: np.ndarray

    @functools.cached_property
    def simpson(self) -> tuple[np.ndarray, np.ndarray]:
        """Simpson's weights of x^-1/2: (N+1,) at the grid points, (N,) in the middles.

        ``(ds_{i-1} + ds_i) / 6`` at grid point i (``ds_{-1} = ds_N = 0``)
        and ``4 ds_i / 6`` at the middle of segment i (s).
        """
        ds = np.diff(self.s)
        width = (np.concatenate([ds, [0.0]]) + np.concatenate([[0.0], ds])) / 6.0
        return width, 4.0 / 6.0 * ds

    @functools.cached_property
    def tail(self) -> Block:
        """The last LP rows, the same in every LP of the retime.

        ``-x <= 0`` at the middle point of each segment, then the
        Bernstein rows (``x >= 0`` all along each segment).
        """
        middle = self.middle
        zeros = np.zeros((len(middle), 1))
        band = self.dense.band.take(middle)
        return joined(
            [
                affine_rows(band, middle, Kind.MIDDLE, zeros, zeros - 1.0, zeros),
                block([self.bernstein]),
            ]
        )


@dataclasses.dataclass
class Selection:
    """Which points and rows the next LP takes (grows between rounds)."""

    active: np.ndarray
    rows: np.ndarray | None
    keep: Keep
    jerk_active: np.ndarray
    jerk_keep: np.ndarray | None = None
    jerk_acceleration: np.ndarray | None = None
    pairs: SetPairs | None = None
    #: With a set of objects and torque limits: its torque triples.
    torque_pairs: SetPairs | None = None
    #: The LP rows other than the jerk's (:func:`_fixed_rows`: before and
    #: after them) and which of them every sub-LP takes, while the selection
    #: is unchanged; None: to be made.
    fixed: tuple[Block, Block, np.ndarray, np.ndarray] | None = None


def solve_lp(
    problem: Problem,
    chosen: Selection,
    solver: WarmLP,
    x_bar: np.ndarray,
    x_dense: np.ndarray,
    x_jerk: np.ndarray,
) -> np.ndarray:
    """One LP (module docstring, step 2): z = [x, u].

    ``x_bar``, ``x_dense``, ``x_jerk``: the previous profile at the grid,
    dense and jerk points. Only the jerk rows and the objective change from
    one LP of a round to the next: the other rows (:func:`_fixed_rows`) are
    kept in ``chosen.fixed`` until the selection changes.
    """
    limits, points = problem.limits, problem.jerk
    assert limits.jerk is not None
    size = len(problem.s)
    if chosen.fixed is None:  # made once per selection, kept compressed
        before, after = (joined(rows) for rows in _fixed_rows(problem, chosen))
        chosen.fixed = before, after, _always(before), _always(after)
    before, after, always_before, always_after = chosen.fixed
    index = np.flatnonzero(chosen.jerk_active & points.inner)
    x_index = np.maximum(x_jerk[index], 1e-6 * max(float(np.max(x_jerk)), 1e-12))
    jerk_keep = np.ones((len(index), len(limits.jerk)), dtype=bool)
    if chosen.jerk_keep is not None:  # rows near the limit (where exceeded too)
        jerk_keep = chosen.jerk_keep[index]
    jerk = jerk_rows(
        points.band, index, Kind.JERK, (points.dq, points.ddq, points.dddq),
        x_index, limits.jerk, jerk_keep,
    )  # fmt: skip
    # Simpson's rule on each segment: T = sum ds / sqrt(x) at its ends and
    # middle, linearised at the previous profile (d/dx x^-1/2 = -x^-1.5 / 2).
    width, middle_width = problem.simpson
    scale = max(float(np.max(x_bar)), 1e-12)
    x_middle = np.maximum(x_dense[problem.middle], 1e-3 * scale)
    weight = -(problem.X_middle_T @ (middle_width / (2.0 * x_middle**1.5)))
    weight[:size] -= width / (2.0 * np.maximum(x_bar, 1e-3 * scale) ** 1.5)
    A_ub, b_ub, keys = stacked([before, jerk, after], 2 * size)
    # Every sub-LP takes the velocity rows between grid points and the
    # Bernstein rows (at the grid points the velocity is a bound of z): with
    # the continuity rows they bound it. The rows x >= 0 inside a segment
    # are implied by the Bernstein rows (rest pieces: by u's bounds): they
    # join only if broken.
    always = np.concatenate(
        [always_before, np.zeros(len(jerk.keys), dtype=bool), always_after]
    )
    z, status = solver.solve(
        weight / np.max(np.abs(weight)), A_ub, b_ub, keys, *problem.equalities,
        problem.variable_bounds, always,
    )  # fmt: skip
    if z is None:
        raise PathNotControllableError(
            f"jerk-limited retiming: no admissible profile ({status})", s=0.0
        )
    return z


def _always(rows: Block) -> np.ndarray:
    """The rows every sub-LP takes: velocity and Bernstein rows (by their keys)."""
    kind = rows.keys >> KIND_SHIFT
    return (kind == int(Kind.VELOCITY)) | (kind == int(Kind.BERNSTEIN))


def _fixed_rows(problem: Problem, chosen: Selection) -> tuple[list[Block], list[Block]]:
    """The LP rows other than the jerk's: those before them, those after.

    They depend on the selection alone, not on the previous profile. The
    rows at the dense points are taken once per point: at the end of a
    segment only where it is not the next one's start (or where a limit was
    exceeded). After the jerk rows: the velocity and acceleration rows at
    jerk points where a limit was exceeded, ``x >= 0`` in the middle of
    each segment and all along it.
    """
    limits, dense, points = problem.limits, problem.dense, problem.jerk
    last = len(DENSE) - 1
    repeated = (dense.k == last) & (np.arange(len(dense.s)) < len(dense.s) - 1)
    once = np.flatnonzero(chosen.active & (~repeated | chosen.keep.full))
    band = dense.band.take(once)
    smp = dense.samples
    dq, ddq = smp.dq[once], smp.ddq[once]
    # At the start of an interior segment x is x_i: its cap is a bound of z.
    grid = (dense.k[once] == 0) & _capped(problem.kinds)[once // len(DENSE)]
    inside = (dense.k[once] > 0) & (dense.k[once] < last)
    rows: dict[int, _Coefficients] = {
        Kind.VELOCITY: (0.0, 1.0, np.where(grid, np.inf, smp.x_cap[once])),
        Kind.POSITIVE: (0.0, -1.0, np.where(inside, 0.0, np.inf)),  # x >= 0
    }
    keep = chosen.keep
    acceleration = np.where(keep.acceleration[once], limits.acceleration, np.inf)
    for sign, offset in ((1.0, 0), (-1.0, 1)):
        rows[Kind.ACCELERATION + offset] = (sign * dq, sign * ddq, acceleration)
        if dense.one_torque and limits.torque is not None:
            assert smp.torque is not None and keep.torque is not None
            a, b, c = (v[once] for v in smp.torque)
            bound = np.where(keep.torque[once], limits.torque - sign * c, np.inf)
            rows[Kind.TORQUE + offset] = (sign * a, sign * b, bound)
    blocks = [_affine_blocks(band, once, rows, dq.shape[1])]
    if chosen.rows is not None and dense.grasp is not None and smp.wrench is not None:
        blocks.append(block([_grasp_rows_at(dense, once, chosen.rows[once])]))
    if chosen.pairs is not None and len(chosen.pairs):
        blocks.append(block([chosen.pairs.rows(dense.band, once, Kind.GRASP)]))
    torque_pairs = chosen.torque_pairs
    if torque_pairs is not None and len(torque_pairs):  # a set's (one key kind)
        blocks.append(block([torque_pairs.rows(dense.band, once, Kind.TORQUE)]))
    after: list[Block] = []
    added = np.flatnonzero(chosen.jerk_active)
    near = chosen.jerk_acceleration
    if near is None:
        near = np.zeros(points.dq.shape, dtype=bool)
    k = points.k[added]
    added = added[(k != 0) & (k != len(JERK_DENSE) - 1)]
    if added.size:  # where a limit was exceeded: acceleration, velocity too
        acceleration = np.where(near[added], limits.acceleration, np.inf)
        dq, ddq = points.dq[added], points.ddq[added]
        rows = {
            Kind.JERK_POINT_ACCELERATION: (dq, ddq, acceleration),
            Kind.JERK_POINT_ACCELERATION + 1: (-1.0 * dq, -1.0 * ddq, acceleration),
            Kind.JERK_POINT_VELOCITY: (0.0, 1.0, points.x_cap[added]),
        }
        after.append(_affine_blocks(points.band.take(added), added, rows, dq.shape[1]))
    after.append(problem.tail)  # x >= 0 in the middle of and all along each segment
    return blocks, after


#: A kind of affine rows at P points: ``alpha``, ``beta`` and ``bound`` of
#: :func:`._jerk_rows.affine_rows`, (P, n) per joint, or (P,) for a row in
#: x alone (its column 0; alpha and beta scalars).
_Coefficients = tuple[np.ndarray | float, np.ndarray | float, np.ndarray]


def _affine_blocks(
    band: Band, points: np.ndarray, rows: dict[int, _Coefficients], n: int
) -> Block:
    """The rows of each kind (in the dict's order), one compiled pass.

    Stacked into (kinds, P, n) coefficients and bounds for
    :func:`._jerk_rows.affine_rows` (inf: no row).
    """
    shape = (len(rows), len(points), n)
    alpha, beta, bound = np.zeros(shape), np.zeros(shape), np.full(shape, np.inf)
    for at, (a, b, limit) in enumerate(rows.values()):
        m = slice(None) if np.ndim(limit) == 2 else 0
        alpha[at, :, m], beta[at, :, m], bound[at, :, m] = a, b, limit
    return affine_rows(band, points, list(rows), alpha, beta, bound)


def _grasp_rows_at(dense: DensePoints, once: np.ndarray, mask: np.ndarray) -> Rows:
    """Grasp rows ``F_r (a u + b x) <= g_r - F_r c`` of the (point, row) pairs ``mask``.

    ``once``: (P,) dense points; ``mask``: (P, R). Only the pairs asked for
    are made (an LP takes a few percent of them); in the order of
    :func:`._jerk_rows.affine_rows` (point-major).
    """
    assert dense.grasp is not None and dense.samples.wrench is not None
    # (np.nonzero's order, row-major; a 1-D search is faster than a 2-D one)
    p, r = np.divmod(np.flatnonzero(mask), mask.shape[1])
    at = once[p]
    a, b, c = (v[at] for v in dense.samples.wrench)
    F = dense.grasp.F[r]
    alpha = np.einsum("ij,ij->i", a, F)[:, None]
    beta = np.einsum("ij,ij->i", b, F)[:, None]
    band = dense.band
    return Rows(
        band.cols[at],
        alpha * band.U[at] + beta * band.X[at],
        dense.grasp.g[r] - np.einsum("ij,ij->i", c, F),
        key(Kind.GRASP, at, r),
    )


def _capped(kinds: np.ndarray) -> np.ndarray:
    """(N,) segments whose start's velocity cap is a bound of ``x_i``.

    The interior segments but the first (``x_0`` is given: its row stays).
    """
    capped = kinds == int(Piece.INTERIOR)
    capped[0] = False
    return capped


def grid_caps(dense: DensePoints, kinds: np.ndarray) -> np.ndarray:
    """The velocity caps of ``x_i`` that are bounds of z, (N+1,) (inf elsewhere).

    ``min_j v_j^2 / q'_j^2`` at the dense point ``k = 0`` of each segment of
    :func:`_capped`; there :func:`_fixed_rows` makes no velocity row.
    """
    caps = np.full(len(kinds) + 1, np.inf)
    capped = np.flatnonzero(_capped(kinds))
    caps[capped] = dense.samples.x_cap[capped * len(DENSE)]
    return caps


def middle_rows(band: Band, middle: np.ndarray, size: int) -> sparse.csc_matrix:
    """``X[middle].T``, (2 ``size``, M): x at the points ``middle`` as columns.

    The CSR arrays of the rows ``X[middle]`` (three entries each, zeros
    kept) read as CSC: its product with a vector sums each row of the
    transpose in the order of the points, as the CSR transpose does.
    """
    return sparse.csc_matrix(
        (
            band.X[middle].ravel(),
            band.cols[middle].ravel(),
            3 * np.arange(len(middle) + 1),
        ),
        shape=(2 * size, len(middle)),
    )


def bernstein_rows(s: np.ndarray, kinds: np.ndarray) -> Rows:
    """Rows ``-(x_i + ds_i u_i) <= 0`` of the interior segments.

    ``x(sigma)`` on segment i is the quadratic with Bernstein coefficients
    ``x_i``, ``x_i + ds_i u_i``, ``x_{i+1}``: the middle one >= 0 (and the
    ends >= 0, > 0 in the interior of the path) keeps x > 0 all along it,
    so the motion never stops inside a segment.
    """
    size = len(s)
    inner = np.flatnonzero(kinds == Piece.INTERIOR)
    values = np.zeros((len(inner), 3))
    values[:, 0], values[:, 1] = -1.0, -np.diff(s)[inner]
    return Rows(
        np.column_stack([inner, size + inner, size + inner + 1]),
        values,
        np.zeros(len(inner)),
        key(Kind.BERNSTEIN, inner, np.zeros(len(inner), dtype=int)),
    )


def variable_bounds(
    s: np.ndarray,
    kinds: np.ndarray,
    x_cap: np.ndarray,
    rest: dict[int, tuple[int, float]],
    sd_start: float,
    sd_end: float,
    sdd_start: float | None = None,
) -> np.ndarray:
    """Bounds of z: ``0 <= x <= x_cap``, the ends' x, ``u_0`` if given, rest pieces' u.

    ``x_cap``: (N+1,) the velocity bound ``min_j v_j^2 / q'_j^2`` of ``x_i``
    where it is a bound of z instead of a row of the LPs (inf elsewhere,
    :func:`grid_caps`).
    """
    size = len(s)
    lower = np.full(2 * size, -np.inf)
    upper = np.full(2 * size, np.inf)
    lower[:size] = 0.0
    upper[:size] = x_cap
    lower[0] = upper[0] = float(sd_start) ** 2
    lower[size - 1] = upper[size - 1] = float(sd_end) ** 2
    if sdd_start is not None:  # u_0 given (sd_start > 0: no START piece)
        lower[size] = upper[size] = float(sdd_start)
    for segment, (variable, most) in rest.items():
        if kinds[segment] == Piece.START:  # u_0 = 0, 0 <= u_1 <= most
            lower[size] = upper[size] = 0.0
            lower[variable], upper[variable] = 0.0, most
        else:  # u_N = 0, -most <= u_{N-1} <= 0
            lower[2 * size - 1] = upper[2 * size - 1] = 0.0
            lower[variable], upper[variable] = -most, 0.0
    return np.column_stack([lower, upper])


def continuity(
    s: np.ndarray, kinds: np.ndarray
) -> tuple[sparse.csr_matrix, np.ndarray]:
    """``x_{i+1} - x_i - ds_i (u_i + u_{i+1}) = 0`` (and the rest pieces' relations)."""
    size = len(s)
    ds = np.diff(s)
    i = np.arange(len(kinds))
    # Interior: x_{i+1}, x_i, u_i, u_{i+1}; the rest pieces use two of them.
    c = np.column_stack([i + 1, i, size + i, size + i + 1])
    v = np.column_stack([np.ones_like(ds), -np.ones_like(ds), -ds, -ds])
    start, stop = kinds == Piece.START, kinds == Piece.STOP
    v[start] = np.column_stack(
        [np.ones(start.sum()), 0 * ds[start], 0 * ds[start], -1.5 * ds[start]]
    )  # x_1 = 1.5 ds u_1
    v[stop] = np.column_stack(
        [0 * ds[stop], np.ones(stop.sum()), 1.5 * ds[stop], 0 * ds[stop]]
    )  # x_{N-1} = -1.5 ds u_{N-1}
    # CSR straight away, each row's columns sorted (x_i, x_{i+1}, u_i, u_{i+1}).
    c, v = c[:, [1, 0, 2, 3]].ravel(), v[:, [1, 0, 2, 3]].ravel()
    indptr = 4 * np.arange(len(kinds) + 1)
    A = sparse.csr_matrix((v, c, indptr), shape=(len(kinds), 2 * size))
    return A, np.zeros(len(kinds))


__all__ = [
    "Kind",
    "Problem",
    "Selection",
    "bernstein_rows",
    "continuity",
    "grid_caps",
    "middle_rows",
    "solve_lp",
    "variable_bounds",
]
