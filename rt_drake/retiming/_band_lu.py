"""Compiled (numba) LU factorisation of a banded matrix, with partial pivoting.

LAPACK's ``dgbtf2`` / ``dgbtrs`` (unblocked), for the square matrices of
:mod:`._dual_simplex`: A (n, n) with ``A[i, j] = 0`` unless ``-kl <= j - i
<= ku``, stored by columns in ``ab`` of shape ``(n, 2 kl + ku + 1)`` with
``A[i, j]`` at ``ab[j, kl + ku + i - j]`` (each column's band contiguous,
its first kl entries the fill of the row exchanges). :func:`factor`
overwrites ``ab`` with ``P A = L U`` (unit lower L with kl multipliers per
column, upper U of bandwidth kl + ku, its diagonal stored as its
reciprocals) and the pivots; :func:`solve` and :func:`solve_transposed`
then solve ``A x = b`` and ``A^T y = c`` in O(n (2 kl + ku)). Arrays are C-contiguous
float64, pivots int64.
"""

from __future__ import annotations

from numba import njit


@njit(cache=True)
def factor(ab, kl, ku, pivots, tiny):  # noqa: D417
    """``P A = L U`` in place (module docstring); False if a pivot is below ``tiny``.

    ``pivots``: (n,) filled with the row exchanged with row j at step j.
    A pivot ``|u_jj| <= tiny`` (the matrix singular, or nearly) stops the
    factorisation.
    """
    n = ab.shape[0]
    kv = kl + ku
    for j in range(ku + 1, min(kv, n)):  # the fill rows start at zero
        for i in range(kv - j, kl):
            ab[j, i] = 0.0
    ju = 0
    for j in range(n):
        if j + kv < n:
            for i in range(kl):
                ab[j + kv, i] = 0.0
        km = min(kl, n - 1 - j)
        best, jp = abs(ab[j, kv]), 0
        for t in range(1, km + 1):
            if abs(ab[j, kv + t]) > best:
                best, jp = abs(ab[j, kv + t]), t
        pivots[j] = j + jp
        if best <= tiny:
            return False
        ju = max(ju, min(j + ku + jp, n - 1))
        if jp != 0:
            for c in range(j, ju + 1):
                a, b = kv + j - c, kv + j + jp - c
                ab[c, a], ab[c, b] = ab[c, b], ab[c, a]
        inverse = 1.0 / ab[j, kv]
        ab[j, kv] = inverse  # the solves multiply by it
        for t in range(1, km + 1):
            ab[j, kv + t] *= inverse
        for c in range(j + 1, ju + 1):
            f = ab[c, kv + j - c]
            if f != 0.0:
                for t in range(1, km + 1):
                    ab[c, kv + j + t - c] -= ab[j, kv + t] * f
    return True


@njit(cache=True)
def solve(ab, kl, ku, pivots, b):  # noqa: D417
    """``x`` with ``A x = b`` from :func:`factor`'s ``ab`` and pivots; b kept."""
    n = ab.shape[0]
    kv = kl + ku
    x = b.copy()
    for j in range(n - 1):  # L, with the exchanges
        p = pivots[j]
        if p != j:
            x[j], x[p] = x[p], x[j]
        km = min(kl, n - 1 - j)
        for t in range(1, km + 1):
            x[j + t] -= ab[j, kv + t] * x[j]
    for j in range(n - 1, -1, -1):  # U
        xj = x[j] * ab[j, kv]
        x[j] = xj
        for i in range(max(0, j - kv), j):
            x[i] -= ab[j, kv + i - j] * xj
    return x


@njit(cache=True)
def solve_transposed(ab, kl, ku, pivots, c):  # noqa: D417
    """``y`` with ``A^T y = c`` from :func:`factor`'s ``ab`` and pivots; c kept."""
    n = ab.shape[0]
    kv = kl + ku
    y = c.copy()
    for j in range(n):  # U^T
        total = y[j]
        for i in range(max(0, j - kv), j):
            total -= ab[j, kv + i - j] * y[i]
        y[j] = total * ab[j, kv]
    for j in range(n - 2, -1, -1):  # L^T, then the exchanges backwards
        km = min(kl, n - 1 - j)
        total = y[j]
        for t in range(1, km + 1):
            total -= ab[j, kv + t] * y[j + t]
        y[j] = total
        p = pivots[j]
        if p != j:
            y[j], y[p] = y[p], y[j]
    return y


__all__ = ["factor", "solve", "solve_transposed"]
