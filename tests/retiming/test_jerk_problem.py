"""The jerk LPs' equality rows (:func:`continuity`) against their equations."""

import numpy as np
import pytest

from rt_drake.retiming._jerk_problem import continuity
from rt_drake.retiming._jerk_timed_path import Piece


def _written_out(s: np.ndarray, kinds: np.ndarray) -> np.ndarray:
    """Dense rows of ``x_{i+1} - x_i - ds_i (u_i + u_{i+1}) = 0`` (and rest pieces')."""
    size = len(s)
    rows = np.zeros((len(kinds), 2 * size))
    for i, (kind, ds) in enumerate(zip(kinds, np.diff(s), strict=True)):
        if kind == Piece.START:  # x_1 = 1.5 ds u_1
            rows[i, i + 1], rows[i, size + i + 1] = 1.0, -1.5 * ds
        elif kind == Piece.STOP:  # x_{N-1} = -1.5 ds u_{N-1}
            rows[i, i], rows[i, size + i] = 1.0, 1.5 * ds
        else:
            rows[i, [i + 1, i, size + i, size + i + 1]] = 1.0, -1.0, -ds, -ds
    return rows


@pytest.mark.parametrize(
    "kinds",
    [[1, 0, 0, 0, 2], [0, 0, 0], [1, 0, 2], [0, 0, 0, 0, 2], [1, 0, 0]],
)
def test_continuity_rows_are_the_equations_in_sorted_csr(kinds):
    rng = np.random.default_rng(len(kinds))
    kinds = np.array(kinds)
    s = np.cumsum(rng.uniform(0.01, 0.2, len(kinds) + 1))
    A, b = continuity(s, kinds)
    assert A.shape == (len(kinds), 2 * len(s)) and not b.any()
    assert np.array_equal(A.toarray(), _written_out(s, kinds))
    # Four entries a row (a rest piece's zeros kept), columns ascending:
    # the compiled solver reads the CSR arrays as they are.
    assert np.array_equal(A.indptr, 4 * np.arange(len(kinds) + 1))
    assert all(
        np.all(np.diff(A.indices[4 * i : 4 * i + 4]) > 0) for i in range(len(kinds))
    )
    # As scipy builds it from (row, column) pairs (its canonical form).
    coo = A.tocoo()
    again = type(A)((coo.data, (coo.row, coo.col)), shape=A.shape)
    assert np.array_equal(again.indices, A.indices)
    assert np.array_equal(again.data, A.data)


def test_middle_rows_is_scipys_transpose_to_the_bit():
    """``middle_rows`` against ``maps.X[middle].T.tocsr()`` (what it replaces)."""
    from rt_drake.retiming._jerk_problem import middle_rows
    from rt_drake.retiming._jerk_rows import Band

    rng = np.random.default_rng(3)
    kinds = np.array([1, 0, 0, 0, 0, 0, 2])
    s = np.cumsum(rng.uniform(0.01, 0.2, len(kinds) + 1))
    segment = np.repeat(np.arange(len(kinds)), 5)
    band = Band.of(s, kinds, segment, np.tile(np.linspace(0.0, 1.0, 5), len(kinds)))
    middle = np.flatnonzero(np.arange(len(segment)) % 5 == 2)
    reference = band.maps(len(s)).X.tocsr()[middle].T.tocsr()
    got = middle_rows(band, middle, len(s))
    assert got.shape == reference.shape
    assert np.array_equal(got.toarray(), reference.toarray())
    for _ in range(5):
        w = rng.normal(size=len(middle)) * 10.0 ** rng.uniform(-6, 6, len(middle))
        assert np.array_equal(got @ w, reference @ w)
