"""The jerk LPs' warm-started HiGHS (``_jerk_lp.WarmLP``) against scipy's HiGHS.

A random bounded LP ``min c z`` s.t. ``A z <= b``, ``E z = e``, box bounds,
solved by :class:`WarmLP` (cutting planes, warm starts) and by
``scipy.optimize.linprog``: the same optimal value. Its rows are dense, so
the compiled solver (``_band_lp``, tested there) leaves them to HiGHS. A
warm start that gives
no answer (HiGHS's model status "Not Set", seen once on a Table I MOVE) is
solved again from scratch rather than reported as no profile.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy import sparse
from scipy.optimize import linprog

from rt_drake.retiming._jerk_lp import WarmLP


def _problem(seed: int):
    rng = np.random.default_rng(seed)
    n, m = 12, 40
    A = rng.normal(size=(m, n))
    b = rng.uniform(1.0, 2.0, m)  # z = 0 feasible
    E = rng.normal(size=(2, n))
    e = E @ rng.uniform(-0.05, 0.05, n)
    c = rng.normal(size=n)
    bounds = np.tile([-1.0, 1.0], (n, 1))
    return c, sparse.csr_matrix(A), b, sparse.csr_matrix(E), e, bounds


def _reference(c, A, b, E, e, bounds) -> float:
    result = linprog(
        c, A_ub=A.toarray(), b_ub=b, A_eq=E.toarray(), b_eq=e, bounds=bounds,
        method="highs",
    )  # fmt: skip
    assert result.status == 0
    return float(result.fun)


def _solve(lp: WarmLP, c, A, b, E, e, bounds, every_row=False) -> np.ndarray:
    keys = np.arange(A.shape[0])
    always = np.full(A.shape[0], every_row)
    z, status = lp.solve(c, A, b, keys, E, e, bounds, always)
    assert z is not None, status
    return z


@pytest.mark.parametrize("seed", range(4))
def test_warm_lps_reach_scipys_optimum(seed):
    lp = WarmLP()
    c, A, b, E, e, bounds = _problem(seed)
    for step in range(3):  # the same rows, a changed cost: warm starts
        cost = c + 0.3 * step * np.roll(c, step)
        z = _solve(lp, cost, A, b, E, e, bounds)
        assert np.all(A @ z <= b + 1e-7)
        assert np.allclose(E @ z, e, atol=1e-7)
        assert cost @ z == pytest.approx(_reference(cost, A, b, E, e, bounds), abs=1e-7)


class _SkipsFirstRun:
    """HiGHS whose first ``run`` does nothing: the model status stays Not Set."""

    def __init__(self, highs):
        self._highs, self.skipped = highs, False

    def run(self):
        if not self.skipped:
            self.skipped = True
            return None
        return self._highs.run()

    def __getattr__(self, name):
        return getattr(self._highs, name)


def test_a_warm_start_without_an_answer_is_solved_from_scratch():
    lp = WarmLP(compiled=False)
    fake = _SkipsFirstRun(lp._highs)
    lp._highs = fake
    c, A, b, E, e, bounds = _problem(7)
    # Every row in the first sub-LP: no cutting-plane round to fall back on.
    z = _solve(lp, c, A, b, E, e, bounds, every_row=True)
    assert fake.skipped
    assert c @ z == pytest.approx(_reference(c, A, b, E, e, bounds), abs=1e-7)


class _RecordsBasis:
    """HiGHS that records each basis it is given (and whether it is alien)."""

    def __init__(self, highs):
        self._highs, self.given = highs, []

    def setBasis(self, basis):  # noqa: N802 (HiGHS's name)
        self.given.append(basis.alien)
        return self._highs.setBasis(basis)

    def __getattr__(self, name):
        return getattr(self._highs, name)


@pytest.mark.parametrize("seed", range(3))
def test_the_carried_basis_is_highs_own_and_needs_no_repair(seed):
    lp = WarmLP(compiled=False)
    recorder = _RecordsBasis(lp._highs)
    lp._highs = recorder
    c, A, b, E, e, bounds = _problem(seed)
    _solve(lp, c, A, b, E, e, bounds)
    # HiGHS's own statuses at the optimum (the enum, not the carried codes):
    # the same basic set, and each nonbasic column at the same bound.
    basis = lp._highs.getBasis()
    highs_cols = np.array([int(v) for v in basis.col_status])
    assert np.array_equal(highs_cols, lp._cols)
    assert (
        np.count_nonzero(highs_cols == 1)
        + np.count_nonzero(np.array([int(v) for v in basis.row_status]) == 1)
        == lp._highs.getNumRow()
    )
    # The same LP again from the carried basis: taken as it is (not alien)
    # and already optimal (no simplex iteration).
    before = lp.iterations
    z = _solve(lp, c, A, b, E, e, bounds)
    assert recorder.given[-1] is False
    assert lp.iterations == before
    assert c @ z == pytest.approx(_reference(c, A, b, E, e, bounds), abs=1e-7)


def test_member_is_numpys_isin():
    """``_member(keys, of)`` against ``np.isin`` on random int64 keys (and none)."""
    from rt_drake.retiming._jerk_lp import _member

    rng = np.random.default_rng(2)
    keys = rng.integers(0, 1 << 60, size=300)
    of = np.concatenate([rng.choice(keys, 40), rng.integers(0, 1 << 60, size=20)])
    np.testing.assert_array_equal(_member(keys, of), np.isin(keys, of))
    assert not _member(keys, of[:0]).any()


class _CutsAhead(WarmLP):
    """WarmLP whose cuts bring, with each broken row, the rows near their bound."""

    ahead = 0  # rows added before they broke

    def _cuts(self, working, value, b_ub, slack, keys):
        broken = super()._cuts(working, value, b_ub, slack, keys)
        if broken.size:
            more = np.flatnonzero(~working & (value > b_ub - 0.5 * slack))
            self.ahead += len(more) - len(broken)
            broken = more
        return broken


@pytest.mark.parametrize("seed", range(4))
def test_cuts_other_than_the_broken_rows_reach_the_same_optimum(seed):
    # The cut hook (benchmarks/bench_jerk_replay.py's variants): more rows
    # per cut change the path of the sub-LPs, not the LP's optimum.
    c, A, b, E, e, bounds = _problem(seed)
    lp = _CutsAhead(compiled=False)
    for step in range(2):
        cost = c + 0.3 * step * np.roll(c, step)
        z = _solve(lp, cost, A, b, E, e, bounds)
        assert np.all(A @ z <= b + 1e-7)
        assert cost @ z == pytest.approx(_reference(cost, A, b, E, e, bounds), abs=1e-7)
    assert lp.ahead > 0  # the LPs took the subclass's cuts
