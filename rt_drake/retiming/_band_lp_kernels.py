"""Compiled (numba) steps of :class:`._band_lp.BandLP` around its dual simplex.

:func:`band_solve` (one LP: its start, the solver, the check of its
answer), :func:`crash` (the first active set of an LP near a guess),
:func:`matched` (the last active set's rows found by key in the
next LP) and :func:`holds`. Arrays are C-contiguous; indices int64
(scipy's int32 accepted).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from rt_drake.retiming import _dual_simplex as simplex


@njit(cache=True)
def crash(guess, indptr, indices, data, b, position, q, lo, hi):  # noqa: D417
    """A first active set near ``guess`` (ids of :mod:`._dual_simplex`).

    The equality rows, the fixed variables' bounds and, for each first
    column (in the solver's order, ``position``), the inequality row (A z
    <= b in CSR form, the caller's columns) with the least slack ``(b - a
    guess) / |a|`` there, the tightest of them first, as many as the
    variables left free (then upper bounds if too few). ``guess``, ``lo``,
    ``hi``: in the solver's order. The caller falls back to bounds alone if
    this set is singular.
    """
    m, n = len(b), len(guess)
    best = np.full(n, -1, dtype=np.int64)
    least = np.full(n, np.inf)
    for r in range(m):
        if indptr[r] == indptr[r + 1]:
            continue
        slack, first, total = b[r], n, 0.0
        for t in range(indptr[r], indptr[r + 1]):
            column = position[indices[t]]
            slack -= data[t] * guess[column]
            first = min(first, column)
            total += data[t] * data[t]
        slack /= np.sqrt(total) if total > 0.0 else 1.0
        if slack < least[first]:
            least[first], best[first] = slack, r
    fixed = np.flatnonzero(lo == hi)
    need = n - q - len(fixed)
    chosen = best[best >= 0]
    chosen = chosen[np.argsort(least[best >= 0], kind="mergesort")][: max(need, 0)]
    out = np.empty(n, dtype=np.int64)
    out[: len(chosen)] = chosen
    at = len(chosen)
    for k in range(q):
        out[at] = m + k
        at += 1
    is_fixed = lo == hi
    for j in range(n):
        if is_fixed[j]:
            out[at] = m + q + j
            at += 1
    for j in range(n):
        if at >= n:
            break
        if not is_fixed[j]:
            out[at] = m + q + j
            at += 1
    return out[:at]


@njit(cache=True)
def matched(previous, keys):  # noqa: D417
    """Indices in ``keys`` of the keys ``previous`` (sorted); -1 where absent."""
    found = np.full(len(previous), -1, dtype=np.int64)
    for i in range(len(keys)):
        at = np.searchsorted(previous, keys[i])
        if at < len(previous) and previous[at] == keys[i]:
            found[at] = i
    return found


@njit(cache=True)
def band_solve(  # noqa: D417, PLR0913
    ub, eq, keys, bounds, c, columns, previous, guess, settings
):  # fmt: skip
    """One LP of :class:`._band_lp.BandLP` (its module docstring), compiled whole.

    ``ub``, ``eq``: (indptr, indices, data, b) of ``A_ub z <= b_ub`` and
    ``A_eq z = b_eq``; ``keys``: (R_ub,) the rows' names; ``bounds``: (n,
    2); ``columns``: the solver's column order; ``previous``: the last
    optimum's active set (its rows' keys sorted, its equality rows, its
    bounds: j upper, n + j lower), each empty and ``previous[3][0] = 0``
    for none; ``guess``: (n,) or empty, the crash's centre when there is no
    last active set (or one of its rows is gone); ``settings``: (width, feasible,
    dual, box, radius, widen, iterations per column). Returns the status,
    z (the caller's column order), the next ``previous``, the iterations
    and 1 if the LP started from bounds alone.
    """
    width, feasible, dual = int(settings[0]), settings[1], settings[2]
    box, radius_scale, widen = settings[3], settings[4], settings[5]
    n, m, q = len(c), len(ub[3]), len(eq[3])
    position = np.empty(n, dtype=np.int64)
    position[columns] = np.arange(n)
    lower, upper = bounds[columns, 0].copy(), bounds[columns, 1].copy()
    artificial = np.concatenate((~np.isfinite(upper), ~np.isfinite(lower)))
    scale = 1e-300
    for j in range(n):
        scale = max(scale, abs(c[j]))
    cost = c[columns] / scale
    start = np.zeros(0, dtype=np.int64)
    have = False
    if previous[3][0] == 1 and np.all(previous[1] < q) and np.all(previous[2] < 2 * n):
        rows = matched(previous[0], keys)
        have = bool(np.all(rows >= 0))  # else: a crash near the guess
        start = np.concatenate((rows, m + previous[1], m + q + previous[2]))
    centre, radius = np.zeros(n), np.ones(n)
    if have or len(guess) != n:  # the box: BOX times the largest finite bound
        largest = 1.0
        for j in range(n):
            for v in (lower[j], upper[j]):
                if np.isfinite(v):
                    largest = max(largest, abs(v))
        radius[:] = box * largest
    else:
        centre = guess[columns]
        for parity in range(2):  # x's and u's: every other column
            largest = 1.0
            for j in range(parity, n, 2):
                largest = max(largest, abs(centre[j]))
            radius[parity::2] = radius_scale * largest
        start = crash(centre, ub[0], ub[1], ub[2], ub[3], position, q, lower, upper)
        have = True
    cold = 0
    status, z, active, iterations = simplex.SINGULAR, np.zeros(n), start, 0
    for attempt in range(4):
        if not have:
            start = m + q + np.arange(n)  # every upper bound
            cold, have = 1, True
        lo = np.where(np.isfinite(lower), lower, centre - radius)
        hi = np.where(np.isfinite(upper), upper, centre + radius)
        status, z, active, steps = simplex.dual_simplex(
            ub[0], ub[1], ub[2], ub[3], eq[0], eq[1], eq[2], eq[3], position, lo, hi,
            artificial, cost, width, start, int(settings[6]) * n, feasible, dual,
        )  # fmt: skip
        iterations += steps
        if status == simplex.SINGULAR and attempt == 0 and cold == 0:
            have = False  # no basis: once more from the bounds
        elif status == simplex.ARTIFICIAL:
            radius *= widen  # the box may be what binds: wider, warm
            start = active
        else:
            break
    out = np.zeros(n)
    state = (np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64))
    nothing = (state[0], state[0], state[1], np.zeros(1, dtype=np.int64))
    if status != simplex.OPTIMAL:
        return status, out, nothing, iterations, cold
    out = z[position]
    if not holds(out, ub, eq, bounds, 10.0 * feasible):
        return NOT_HELD, out, nothing, iterations, cold
    rows = active[active < m]
    row_keys = np.sort(keys[rows])
    eq_rows = active[(active >= m) & (active < m + q)] - m
    bound_ids = active[active >= m + q] - (m + q)
    return (
        status,
        out,
        (row_keys, eq_rows, bound_ids, np.ones(1, dtype=np.int64)),
        iterations,
        cold,
    )


#: :func:`band_solve`'s status for an optimum that breaks a row (never seen).
NOT_HELD = 9


@njit(cache=True)
def holds(z, ub, eq, bounds, tolerance):  # noqa: D417
    """Every row (``ub``, ``eq``: indptr, indices, data, b) and bound of z held.

    Within ``tolerance max(1, |b|)``; the sums in the rows' order.
    """
    if not _rows_held(z, ub[0], ub[1], ub[2], ub[3], False, tolerance):
        return False
    if not _rows_held(z, eq[0], eq[1], eq[2], eq[3], True, tolerance):
        return False
    for j in range(len(z)):
        low, high = bounds[j, 0], bounds[j, 1]
        if np.isfinite(low) and not low - z[j] <= tolerance * max(1.0, abs(low)):
            return False
        if np.isfinite(high) and not z[j] - high <= tolerance * max(1.0, abs(high)):
            return False
    return True


@njit(cache=True)
def _rows_held(z, indptr, indices, data, b, equal, tolerance):
    """``a z <= b`` (``|a z - b|`` if ``equal``) within ``tolerance max(1, |b|)``."""
    for r in range(len(b)):
        total = -b[r]
        for t in range(indptr[r], indptr[r + 1]):
            total += data[t] * z[indices[t]]
        if equal:
            total = abs(total)
        if not total <= tolerance * max(1.0, abs(b[r])):
            return False
    return True


__all__ = ["band_solve", "crash", "holds", "matched"]
