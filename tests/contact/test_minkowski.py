"""Exact Minkowski-sum enumeration against pycddlib and an LP vertex test."""

from __future__ import annotations

import itertools

import cdd
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import linprog

from rt_drake.contact._minkowski import minkowski_sum


def _random_summands(seed: int, count: int, n: int = 6):
    """Random polytopes of dimension 0-3 embedded in R^n, and an offset."""
    rng = np.random.default_rng(seed)
    summands = []
    for _ in range(count):
        dim = int(rng.integers(0, 4))
        points = rng.normal(size=(int(rng.integers(dim + 1, dim + 4)), dim))
        summands.append(points @ rng.normal(size=(dim, n)) + rng.normal(size=n))
    return summands, rng.normal(size=n)


def _cdd_facets(points: np.ndarray) -> tuple[np.ndarray, np.ndarray, int]:
    """Facets (unit rows, offsets) and the number of equalities, by cdd."""
    matrix = cdd.matrix_from_array(
        np.hstack([np.ones((len(points), 1)), points]), rep_type=cdd.RepType.GENERATOR
    )
    inequalities = cdd.copy_inequalities(cdd.polyhedron_from_matrix(matrix))
    rows = np.array(inequalities.array)
    keep = [i for i in range(len(rows)) if i not in inequalities.lin_set]
    keep = [i for i in keep if np.linalg.norm(rows[i, 1:]) > 1e-12]  # not 0 <= 1
    F, g = -rows[keep, 1:].reshape(-1, points.shape[1]), rows[keep, 0]
    norms = np.linalg.norm(F, axis=1)
    return F / norms[:, None], g / norms, len(inequalities.lin_set)


def _lp_support(direction: np.ndarray, F: np.ndarray, g: np.ndarray) -> float:
    """max direction . w subject to F w <= g, by HiGHS."""
    result = linprog(-direction, A_ub=F, b_ub=g, bounds=(None, None), method="highs")
    assert result.status == 0, result.message
    return -result.fun


@given(seed=st.integers(0, 2**32 - 1), count=st.integers(1, 3))
@settings(max_examples=40, deadline=None)
def test_random_sums_have_exactly_the_true_facets_and_vertices(seed, count):
    summands, offset = _random_summands(seed, count)
    exact = minkowski_sum(summands, offset)
    F, g, e = exact.F, exact.g, exact.equalities
    sums = np.array([offset + sum(c) for c in itertools.product(*summands)])
    d = 6 - e
    np.testing.assert_allclose(np.linalg.norm(F, axis=1), 1.0)
    # Every Minkowski point satisfies every row.
    assert np.all(sums @ F.T <= g + 1e-9)
    # Every inequality row is a facet: tight at d affinely independent points.
    for row, offset_ in zip(F[2 * e :], g[2 * e :], strict=True):
        on = sums[np.abs(sums @ row - offset_) <= 1e-9]
        assert len(on) >= 1
        if d >= 2:
            assert np.linalg.svd(on - on[0], compute_uv=False)[d - 2] > 1e-6
    # No facet missing: in cdd's facet directions (which may be wrong: cdd runs
    # in floating point) and random ones, the H-rep's support value is the
    # true one, sum_s max_j u . v_sj + u . offset.
    F_cdd, _, equalities = _cdd_facets(sums)
    assert equalities == e
    known = {tuple(u) for u in F.round(6)}
    rng = np.random.default_rng(seed)
    directions = [u for u in F_cdd if tuple(u.round(6)) not in known]
    for u in [*directions, *rng.normal(size=(10, 6))]:
        true = u @ offset + sum(np.max(v @ u) for v in summands)
        assert _lp_support(u, F, g) == pytest.approx(true, abs=1e-7)
    # Vertices: the points whose tight rows have rank 6.
    tight = np.abs(sums @ F.T - g) <= 1e-9
    rank = [np.linalg.matrix_rank(F[t], tol=1e-7) for t in tight]
    expected = {tuple(x) for x in sums[np.array(rank) == 6].round(9)}
    assert {tuple(v) for v in exact.vertices.round(9)} == expected
    assert len(exact.vertices) == len(expected)


def test_symmetry_must_map_each_summand_onto_the_next():
    summands, offset = _random_summands(1, 3)
    with pytest.raises(ValueError, match="symmetry"):
        minkowski_sum(summands, np.zeros(6), symmetry=np.eye(6))
    with pytest.raises(ValueError, match="offset"):
        minkowski_sum(summands, offset, symmetry=-np.eye(6))


def test_summand_of_dimension_four_is_rejected():
    simplex = np.vstack([np.zeros(6), np.eye(6)[:4]])
    with pytest.raises(ValueError, match="dimension 4"):
        minkowski_sum([simplex], np.zeros(6))
