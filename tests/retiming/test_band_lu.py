"""The banded LU (``_band_lu``) against numpy's dense solve.

Random band matrices whose diagonal is small against the band (so that
partial pivoting exchanges rows), in the column storage of LAPACK's
``dgbtrf``: ``A x = b`` and ``A^T y = c`` agree with ``numpy.linalg.solve``;
a singular band matrix is refused.
"""

from __future__ import annotations

import numpy as np
import pytest

from rt_drake.retiming._band_lu import factor, solve, solve_transposed


def _band(A: np.ndarray, kl: int, ku: int) -> np.ndarray:
    """A stored as :mod:`._band_lu` does: ``A[i, j]`` at ``ab[j, kl + ku + i - j]``."""
    n = len(A)
    ab = np.zeros((n, 2 * kl + ku + 1))
    for i in range(n):
        for j in range(max(0, i - kl), min(n, i + ku + 1)):
            ab[j, kl + ku + i - j] = A[i, j]
    return ab


def _random_band(rng: np.random.Generator, n: int, kl: int, ku: int) -> np.ndarray:
    A = np.zeros((n, n))
    for i in range(n):
        for j in range(max(0, i - kl), min(n, i + ku + 1)):
            A[i, j] = rng.normal()
        A[i, i] *= 1e-3  # rows must be exchanged
    return A


@pytest.mark.parametrize(
    ("n", "kl", "ku", "seed"), [(40, 3, 3, 0), (31, 2, 4, 1), (7, 1, 1, 2)]
)
def test_band_solves_match_numpy(n, kl, ku, seed):
    rng = np.random.default_rng(seed)
    A = _random_band(rng, n, kl, ku)
    ab = _band(A, kl, ku)
    pivots = np.empty(n, dtype=np.int64)
    assert factor(ab, kl, ku, pivots, 1e-14)
    assert np.any(pivots != np.arange(n))  # partial pivoting exchanged rows
    b, c = rng.normal(size=n), rng.normal(size=n)
    scale = np.linalg.cond(A)
    x, y = solve(ab, kl, ku, pivots, b), solve_transposed(ab, kl, ku, pivots, c)
    assert np.max(np.abs(x - np.linalg.solve(A, b))) <= 1e-13 * scale * np.max(
        np.abs(x)
    )
    assert np.max(np.abs(y - np.linalg.solve(A.T, c))) <= 1e-13 * scale * np.max(
        np.abs(y)
    )


def test_singular_band_matrix_is_refused():
    rng = np.random.default_rng(3)
    A = _random_band(rng, 12, 2, 2)
    A[5] = 0.0  # a zero row
    pivots = np.empty(12, dtype=np.int64)
    assert not factor(_band(A, 2, 2), 2, 2, pivots, 1e-12)
