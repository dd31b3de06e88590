"""A compiled (numba) dual simplex for LPs whose rows span a few neighbouring columns.

The LP, in the column order the caller chose (every row's nonzero columns
within ``width`` consecutive ones: the jerk LPs' rows each touch ``x_i, u_i,
x_{i+1}, u_{i+1}`` of one segment, i.e. width 4 with x and u interleaved):

    minimise c z  subject to  A z <= b,  E z = e,  lo <= z <= hi,

with ``lo``, ``hi`` finite (the caller puts an artificial box where a bound
is infinite). It is solved in the active-set ("inequality") form: a vertex
is n active constraints W (rows of A or E, or bounds), ``A_W z = b_W``; its
multipliers ``A_W^T lam = -c`` are >= 0 for the inequalities (free for
equalities and fixed variables): the vertex is dual feasible. Each
iteration the row (or bound) the vertex breaks most (distance ``(a z - b) /
|a|``) enters W, and the inequality whose multiplier reaches zero first
along ``lam - t w`` (``A_W^T w = a``) leaves (Harris's two-pass ratio test,
the largest ``w`` among the near-ties). A vertex breaking nothing is
optimal; a broken row with no ``w > 0`` proves the LP infeasible (Farkas),
unless an artificial bound takes part in the proof.

Sorted by their first column, the n active normals of a nonsingular W form
a band matrix with ``width - 1`` diagonals on each side (rows ``0..r`` lie
in columns ``< lo_r + width``, rows ``r..`` in columns ``>= lo_r``), so
each iteration factorises W anew (:mod:`._band_lu`, O(n width^2)): nothing
drifts. A start that is not dual feasible is repaired first: a bound with
a negative multiplier changes to the variable's other bound (the
multiplier changes sign, the others stay), a row with one is replaced by
a bound of a variable its direction ``A_W^{-1} e_r`` moves.

Constraint ids: row i of A is ``i``, row k of E is ``m + k``, the upper
bound of z_j ``m + q + j``, its lower bound ``m + q + n + j`` (a fixed
variable's, ``lo_j = hi_j``, is its upper one: free multiplier).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from rt_drake.retiming._band_lu import factor, solve, solve_transposed

#: Iterations between factorisations (the updates in between: Sherman-Morrison).
REFACTOR = 8
#: Statuses of :func:`dual_simplex`.
OPTIMAL, INFEASIBLE, ITERATION_CAP, SINGULAR, ARTIFICIAL, TOO_WIDE = 0, 1, 2, 3, 4, 5


@njit(cache=True)
def _table(indptr, indices, data, b, eptr, eind, edata, e, position, width):
    """Every constraint's normal, by id, scaled to unit length in the solver's columns.

    Returns ``cols``, ``vals`` (K, width) and ``count`` (K,): its (column,
    value) pairs; ``first`` (K,): its first column (``first[0] = -1`` if a
    row spans more than ``width`` columns); ``rhs`` (K,): its scaled bound
    (the bounds' left 0, for the caller); ``length`` (m + q,): the rows'
    lengths before scaling (1 for a zero row). K = m + q + 2n.
    """
    m, q, n = len(b), len(e), len(position)
    K = m + q + 2 * n
    cols = np.empty((K, width), dtype=np.int64)
    vals = np.empty((K, width))
    count = np.empty(K, dtype=np.int64)
    first = np.empty(K, dtype=np.int64)
    rhs = np.zeros(K)
    length = np.ones(m + q)
    for k in range(m + q):
        if k < m:
            ind, dat, start, stop = indices, data, indptr[k], indptr[k + 1]
        else:
            ind, dat, start, stop = eind, edata, eptr[k - m], eptr[k - m + 1]
        low, high, total = n, -1, 0.0
        for t in range(start, stop):
            column = position[ind[t]]
            low, high = min(low, column), max(high, column)
            total += dat[t] * dat[t]
        if stop - start > width or high - low >= width:
            first[0] = -1
            return cols, vals, count, first, rhs, length
        norm = np.sqrt(total) if total > 0.0 else 1.0
        first[k] = low if high >= 0 else 0
        count[k] = stop - start
        for t in range(start, stop):
            cols[k, t - start] = position[ind[t]]
            vals[k, t - start] = dat[t] / norm
        rhs[k] = (b[k] if k < m else e[k - m]) / norm
        length[k] = norm
    for j in range(n):
        for side, sign in ((0, 1.0), (1, -1.0)):
            k = m + q + side * n + j
            cols[k, 0], vals[k, 0], count[k], first[k] = j, sign, 1, j
    return cols, vals, count, first, rhs, length


@njit(cache=True)
def dual_simplex(  # noqa: C901, D417, PLR0912, PLR0915
    indptr, indices, data, b, eptr, eind, edata, e, position, lo, hi, artificial, c,
    width, start, max_iterations, feasible, dual,
):  # fmt: skip
    """The LP of the module docstring from the active set ``start``, (n,) ids.

    ``indptr``, ``indices``, ``data``, ``b``: A z <= b in CSR form (the
    caller's columns); ``eptr``, ``eind``, ``edata``, ``e``: E z = e
    likewise; ``position``: (n,) each column's index in the solver's order,
    which ``lo``, ``hi``, ``c`` (scaled to ``max |c| = 1``) and the returned
    z follow. Rows are scaled to unit length here. ``artificial``: (2n,)
    upper then lower bounds that are the caller's box, not the LP's (one
    active at the end: :data:`ARTIFICIAL`). A row (a bound) may keep an
    excess of ``feasible max(1, |b|)`` in its own units; ``dual``:
    tolerance of a multiplier. Returns the status, z, the final active set
    (ids) and the iterations (ratio-test pivots and repair steps).
    """
    m, q, n = len(b), len(e), len(c)
    kl = width - 1
    z = np.zeros(n)
    cols, vals, count, first, rhs_of, length = _table(
        indptr, indices, data, b, eptr, eind, edata, e, position, width
    )
    if len(first) and first[0] < 0:
        return TOO_WIDE, z, start.copy(), 0
    tolerance = np.empty(m + q + 2 * n)
    for i in range(m):
        tolerance[i] = feasible * max(1.0, abs(b[i])) / length[i]
    for k in range(q):
        tolerance[m + k] = feasible * max(1.0, abs(e[k])) / length[m + k]
    for j in range(n):
        tolerance[m + q + j] = feasible * max(1.0, abs(hi[j]))
        tolerance[m + q + n + j] = feasible * max(1.0, abs(lo[j]))
        rhs_of[m + q + j], rhs_of[m + q + n + j] = hi[j], -lo[j]
    free = np.zeros(m + q + 2 * n, dtype=np.bool_)
    free[m : m + q] = True
    for j in range(n):
        free[m + q + j] = lo[j] == hi[j]
    active = np.zeros(m + q + 2 * n, dtype=np.bool_)
    W = start[np.argsort(first[start], kind="mergesort")].copy()
    for k in W:
        active[k] = True
    candidates = np.empty(m + q, dtype=np.int64)
    size = -1  # the rows broken at the last full pricing; -1: price them all
    ab = np.empty((n, 3 * kl + 1))
    pivots = np.empty(n, dtype=np.int64)
    rhs = np.empty(n)
    # The updates since the factorisation: A_k = A_{k-1} + e_r v^T, with
    # u = A_{k-1}^{-1} e_r, v (sparse: the new row minus the old) and
    # delta = 1 + v u (Sherman-Morrison).
    etas = 0
    eta_at = np.empty(REFACTOR, dtype=np.int64)
    eta_u = np.empty((REFACTOR, n))
    eta_cols = np.empty((REFACTOR, 2 * width), dtype=np.int64)
    eta_vals = np.empty((REFACTOR, 2 * width))
    eta_count = np.empty(REFACTOR, dtype=np.int64)
    eta_delta = np.empty(REFACTOR)
    lam = np.zeros(n)
    fresh = False  # z and lam from a factorisation of the current W
    iterations = 0
    while True:
        if iterations >= max_iterations:
            return ITERATION_CAP, z, W, iterations
        if not fresh:
            W = W[np.argsort(first[W], kind="mergesort")]
            ab[:] = 0.0
            for r in range(n):
                k = W[r]
                if first[k] > r or first[k] < r - kl:
                    return SINGULAR, z, W, iterations
                for t in range(count[k]):
                    ab[cols[k, t], 2 * kl + r - cols[k, t]] = vals[k, t]
                rhs[r] = rhs_of[k]
            if not factor(ab, kl, kl, pivots, 1e-12):
                return SINGULAR, z, W, iterations
            etas = 0
            z = solve(ab, kl, kl, pivots, rhs)
            lam = solve_transposed(ab, kl, kl, pivots, -c)
            fresh = True
            # Repair: a bound's wrong sign flips it, a row's is replaced.
            worst, at, flipped = -dual, -1, False
            for r in range(n):
                k = W[r]
                if free[k] or lam[r] >= -dual:
                    continue
                if k >= m + q:  # the variable's other bound
                    other = k + n if k < m + q + n else k - n
                    active[k], active[other] = False, True
                    W[r], flipped = other, True
                elif lam[r] < worst:
                    worst, at = lam[r], r
            if at >= 0:
                unit = np.zeros(n)
                unit[at] = 1.0
                d = solve(ab, kl, kl, pivots, unit)
                j = int(np.argmax(np.abs(d)))
                if abs(d[j]) <= 1e-12:
                    return SINGULAR, z, W, iterations
                active[W[at]] = False
                W[at] = m + q + j
                active[m + q + j] = True
            if flipped or at >= 0:
                iterations += 1
                fresh = False
                continue
        # Pricing: the largest excess (a distance: rows are unit length) among
        # the rows the last full pricing found broken; all rows when none is.
        best, enter, sign = 0.0, -1, 1.0
        for full in (size < 0, True):
            kept = 0
            for at in range(m + q if full else size):
                i = at if full else candidates[at]
                if active[i]:
                    continue
                excess = -rhs_of[i]
                for t in range(count[i]):
                    excess += vals[i, t] * z[cols[i, t]]
                sign_i = 1.0
                if i >= m and excess < 0.0:
                    sign_i, excess = -1.0, -excess
                if excess > tolerance[i]:
                    candidates[kept] = i
                    kept += 1
                    if excess > best:
                        best, enter, sign = excess, i, sign_i
            size = kept
            if enter >= 0 or full:
                break
        for j in range(n):
            if active[m + q + j] or active[m + q + n + j]:
                continue
            if z[j] - hi[j] > tolerance[m + q + j] and z[j] - hi[j] > best:
                best, enter, sign = z[j] - hi[j], m + q + j, 1.0
            if lo[j] - z[j] > tolerance[m + q + n + j] and lo[j] - z[j] > best:
                best, enter, sign = lo[j] - z[j], m + q + n + j, 1.0
        if enter < 0:
            if etas:  # confirm at a vertex solved afresh
                fresh = False
                continue
            for k in W:
                if k >= m + q and not free[k] and artificial[k - m - q]:
                    return ARTIFICIAL, z, W, iterations
            return OPTIMAL, z, W, iterations
        a = np.zeros(n)
        for t in range(count[enter]):
            a[cols[enter, t]] = sign * vals[enter, t]
        for e_k in range(
            etas - 1, -1, -1
        ):  # A_k^{-T} = A_{k-1}^{-T} (I - v u^T / delta)
            dot = 0.0
            for i in range(n):
                dot += eta_u[e_k, i] * a[i]
            dot /= eta_delta[e_k]
            for t in range(eta_count[e_k]):
                a[eta_cols[e_k, t]] -= eta_vals[e_k, t] * dot
        w = solve_transposed(ab, kl, kl, pivots, a)
        # Harris: the bound of the step with the tolerance, then the largest w.
        pivot = 1e-9 * max(1.0, np.max(np.abs(w)))
        bound = np.inf
        for r in range(n):
            if not free[W[r]] and w[r] > pivot:
                bound = min(bound, (max(lam[r], 0.0) + dual) / w[r])
        leave, largest = -1, 0.0
        for r in range(n):
            if not free[W[r]] and w[r] > pivot and max(lam[r], 0.0) / w[r] <= bound:
                if w[r] > largest:
                    leave, largest = r, w[r]
        if leave < 0:
            if etas:
                fresh = False
                continue
            # Farkas: a_p = sum w_r a_r with w_r <= 0 on the inequalities;
            # a proof only if no artificial bound takes part.
            for r in range(n):
                k = W[r]
                if k >= m + q and artificial[k - m - q] and w[r] < -pivot:
                    return ARTIFICIAL, z, W, iterations
            return INFEASIBLE, z, W, iterations
        # The direction that frees the leaving constraint: d = A^{-1} e_leave.
        d = np.zeros(n)
        d[leave] = 1.0
        d = solve(ab, kl, kl, pivots, d)
        for e_k in range(etas):  # A_k^{-1} = (I - u v^T / delta) A_{k-1}^{-1}
            dot = 0.0
            for t in range(eta_count[e_k]):
                dot += eta_vals[e_k, t] * d[eta_cols[e_k, t]]
            dot /= eta_delta[e_k]
            for i in range(n):
                d[i] -= eta_u[e_k, i] * dot
        along = 0.0  # a_p d (= sign w_leave)
        excess = -rhs_of[enter]
        for t in range(count[enter]):
            along += vals[enter, t] * d[cols[enter, t]]
            excess += vals[enter, t] * z[cols[enter, t]]
        step = max(lam[leave], 0.0) / w[leave]
        for r in range(n):
            lam[r] -= step * w[r]
        lam[leave] = sign * step
        z -= (excess / along) * d
        old = W[leave]
        active[old] = False
        W[leave] = enter
        active[enter] = True
        iterations += 1
        if etas == REFACTOR:
            fresh = False
            continue
        eta_at[etas], eta_delta[etas] = leave, along
        eta_u[etas] = d
        # v = the new row minus the old one, both as stored.
        t_v = 0
        for t in range(count[enter]):
            eta_cols[etas, t_v], eta_vals[etas, t_v] = cols[enter, t], vals[enter, t]
            t_v += 1
        for t in range(count[old]):
            eta_cols[etas, t_v], eta_vals[etas, t_v] = cols[old, t], -vals[old, t]
            t_v += 1
        eta_count[etas] = t_v
        etas += 1


@njit(cache=True)
def _replaced(W, at, k, first):
    """W with its entry ``at`` replaced by k, kept sorted by first column."""
    out = np.empty_like(W)
    key = first[k]
    put = False
    o = 0
    for r in range(len(W)):
        if r == at:
            continue
        if not put and first[W[r]] > key:
            out[o] = k
            o += 1
            put = True
        out[o] = W[r]
        o += 1
    if not put:
        out[o] = k
    return out


__all__ = [
    "ARTIFICIAL",
    "INFEASIBLE",
    "ITERATION_CAP",
    "OPTIMAL",
    "SINGULAR",
    "TOO_WIDE",
    "dual_simplex",
]
