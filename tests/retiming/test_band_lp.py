"""The compiled dual simplex (``_band_lp.BandLP``) against scipy's HiGHS.

Random LPs with the jerk LPs' sparsity: ``z = [x_0..x_N, u_0..u_N]``, the
continuity rows ``x_{i+1} - x_i - ds (u_i + u_{i+1}) = 0``, inequality rows
on ``(x_i, u_i, u_{i+1})`` of one segment, ``0 <= x <= cap`` (some caps
infinite), u free or boxed. Each is solved by :class:`BandLP` and by
``scipy.optimize.linprog(method="highs")`` with tight tolerances: the same
optimal value (1e-9 relative) and every row and bound held (1e-9
relative), also along a sequence of warm-started LPs whose costs and rows
change and grow (as a retime's), on a degenerate LP (rows repeated and
rows through the optimum) and from a guess. An infeasible LP, an unbounded
one and one whose rows are too wide get no answer, with the reason. The
retimer's ``WarmLP`` answers with it, as HiGHS alone does.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy import sparse
from scipy.optimize import linprog

from rt_drake.retiming._band_lp import BandLP
from rt_drake.retiming._jerk_lp import WarmLP


def _lp(seed: int, segments: int = 30, per_segment: int = 6):
    """A feasible random LP of the jerk LPs' shape: c, A, b, keys, E, e, bounds."""
    rng = np.random.default_rng(seed)
    size = segments + 1
    n = 2 * size
    ds = rng.uniform(0.01, 0.05, segments)
    i = np.arange(segments)
    E = sparse.csr_matrix(
        (
            np.column_stack([np.ones(segments), -np.ones(segments), -ds, -ds]).ravel(),
            (
                np.repeat(i, 4),
                np.column_stack([i + 1, i, size + i, size + i + 1]).ravel(),
            ),
        ),
        shape=(segments, n),
    )
    # A feasible point: a smooth positive x, u from the continuity rows.
    x0 = 1.0 + np.sin(np.linspace(0.0, 3.0, size)) ** 2
    u0 = np.zeros(size)
    for k in range(segments):
        u0[k + 1] = (x0[k + 1] - x0[k]) / ds[k] - u0[k]
    z0 = np.concatenate([x0, u0])
    rows = np.repeat(i, per_segment)
    cols = np.column_stack([rows, size + rows, size + rows + 1])
    values = rng.normal(size=cols.shape)
    A = sparse.csr_matrix(
        (values.ravel(), (np.repeat(np.arange(len(rows)), 3), cols.ravel())),
        shape=(len(rows), n),
    )
    b = A @ z0 + rng.uniform(0.0, 0.5, len(rows))
    bounds = np.column_stack([np.full(n, -np.inf), np.full(n, np.inf)])
    bounds[:size, 0] = 0.0
    bounds[:size, 1] = np.where(
        rng.random(size) < 0.7, x0 + rng.uniform(0.1, 2.0, size), np.inf
    )
    bounds[size:, 0] = np.where(rng.random(size) < 0.5, u0 - 50.0, -np.inf)
    bounds[size:, 1] = np.where(rng.random(size) < 0.5, u0 + 50.0, np.inf)
    bounds[0] = x0[0]  # x_0 given, as a retime's start
    # A cost that bounds the optimum: maximise x, keep u small in sum.
    c = np.concatenate([-rng.uniform(0.5, 1.5, size), np.zeros(size)])
    A = sparse.vstack([A, _u_box(size, n, u0, 200.0)]).tocsr()
    b = np.concatenate([b, np.concatenate([u0 + 200.0, -(u0 - 200.0)])])
    keys = rng.permutation(len(b)).astype(np.int64) * 7 + 3  # distinct names
    return c, A, b, keys, E.tocsr(), np.zeros(segments), bounds, z0


def _u_box(size: int, n: int, u0: np.ndarray, width: float) -> sparse.csr_matrix:
    """Rows ``u_k <= u0_k + width`` and ``-u_k <= -(u0_k - width)`` (bound u)."""
    k = np.arange(size)
    upper = sparse.csr_matrix((np.ones(size), (k, size + k)), shape=(size, n))
    return sparse.vstack([upper, -upper]).tocsr()


def _reference(c, A, b, E, e, bounds):
    result = linprog(
        c, A_ub=A, b_ub=b, A_eq=E, b_eq=e, bounds=list(map(tuple, bounds)),
        method="highs",
        options={
            "primal_feasibility_tolerance": 1e-10,
            "dual_feasibility_tolerance": 1e-10,
        },
    )  # fmt: skip
    return result


def _assert_optimal(z, c, A, b, E, e, bounds):
    assert z is not None
    reference = _reference(c, A, b, E, e, bounds)
    assert reference.status == 0
    assert c @ z == pytest.approx(reference.fun, rel=1e-9, abs=1e-9)
    assert np.all(A @ z - b <= 1e-9 * np.maximum(1.0, np.abs(b)))
    assert np.all(np.abs(E @ z - e) <= 1e-9 * np.maximum(1.0, np.abs(e)))
    low, high = bounds[:, 0], bounds[:, 1]
    assert np.all(z >= low - 1e-9 * np.maximum(1.0, np.abs(low)))
    assert np.all(
        z <= high + 1e-9 * np.maximum(1.0, np.abs(np.where(np.isinf(high), 0.0, high)))
    )


@pytest.mark.parametrize("seed", range(3))
def test_random_banded_lp_reaches_highs_optimum(seed):
    c, A, b, keys, E, e, bounds, _ = _lp(seed)
    z, status = BandLP().solve(c, A, b, keys, E, e, bounds)
    assert status == "Optimal"
    _assert_optimal(z, c, A, b, E, e, bounds)


def test_warm_sequence_with_changed_and_added_rows():
    """As a retime: costs change, some rows' coefficients change, rows join."""
    rng = np.random.default_rng(7)
    c, A, b, keys, E, e, bounds, z0 = _lp(7)
    lp = BandLP()
    lp.guess(np.zeros(len(c)))  # a poor guess: the crash must still work
    cold = lp.cold
    for step in range(4):
        z, status = lp.solve(c, A, b, keys, E, e, bounds)
        _assert_optimal(z, c, A, b, E, e, bounds)
        if step:
            assert lp.cold == cold  # warm: from the last active set
        A = A.tolil()
        changed = rng.choice(A.shape[0] - 62, 20, replace=False)
        for r in changed:  # a row's coefficients scaled, its bound kept
            A[r] = A[r].toarray() * rng.uniform(0.9, 1.1)
        A = A.tocsr()
        b = np.maximum(b, A @ z0 + 0.01)  # z0 feasible still
        extra, extra_b, extra_keys = _more_rows(rng, z, z0, 10, 10**6 + 10 * step)
        A = sparse.vstack([A, extra]).tocsr()
        b, keys = np.concatenate([b, extra_b]), np.concatenate([keys, extra_keys])
        c = c * rng.uniform(0.8, 1.2, len(c))


def _more_rows(rng, z, z0, count, first_key):
    """Rows of random segments through the middle of z and the feasible z0.

    Each row whose value at z exceeds that at z0 cuts z off, and z0 (a
    point of every LP of the sequence) keeps it feasible.
    """
    n = len(z)
    size = n // 2
    seg = rng.integers(0, size - 1, count)
    cols = np.column_stack([seg, size + seg, size + seg + 1])
    values = rng.normal(size=cols.shape)
    A = sparse.csr_matrix(
        (values.ravel(), (np.repeat(np.arange(count), 3), cols.ravel())),
        shape=(count, n),
    )
    return A, A @ (0.5 * (z + z0)), first_key + np.arange(count)


def test_degenerate_lp():
    """Rows repeated, and rows through the optimum: the same optimal value."""
    c, A, b, keys, E, e, bounds, z0 = _lp(11)
    z, _ = BandLP().solve(c, A, b, keys, E, e, bounds)
    assert z is not None
    rng = np.random.default_rng(11)
    tight = _more_rows(rng, z, z0, 40, 0)[0]
    A = sparse.vstack([A, A[:30], tight]).tocsr()
    b = np.concatenate([b, b[:30], tight @ z])
    keys = np.arange(len(b), dtype=np.int64)
    z, status = BandLP().solve(c, A, b, keys, E, e, bounds)
    assert status == "Optimal"
    _assert_optimal(z, c, A, b, E, e, bounds)


def test_infeasible_unbounded_and_too_wide_lps_get_no_answer():
    c, A, b, keys, E, e, bounds, _ = _lp(5)
    n = A.shape[1]
    # x_3 <= -1 against x >= 0: infeasible.
    bad = sparse.csr_matrix(([1.0], ([0], [3])), shape=(1, n))
    A_inf = sparse.vstack([A, bad]).tocsr()
    b_inf, k_inf = np.append(b, -1.0), np.append(keys, 10**6)
    assert _reference(c, A_inf, b_inf, E, e, bounds).status == 2
    z, status = BandLP().solve(c, A_inf, b_inf, k_inf, E, e, bounds)
    assert z is None and status == "Infeasible"
    # No cap, u free, one row (x_1 >= 0 again): x grows without bound.
    free = bounds.copy()
    free[1:, 1], free[n // 2 :, 0] = np.inf, -np.inf
    A_free = sparse.csr_matrix(([-1.0], ([0], [1])), shape=(1, n))
    b_free = np.zeros(1)
    assert _reference(c, A_free, b_free, E, e, free).status == 3
    z, status = BandLP().solve(c, A_free, b_free, keys[:1], E, e, free)
    assert z is None and status == "Unbounded or artificial bound active"
    # A row over five columns: not for this solver.
    wide = sparse.csr_matrix((np.ones(5), ([0] * 5, [0, 1, 2, 3, 4])), shape=(1, n))
    z, status = BandLP().solve(
        c, sparse.vstack([A, wide]).tocsr(), np.append(b, 1e3), np.append(keys, 10**6),
        E, e, bounds,
    )  # fmt: skip
    assert z is None and status == "A row spans too many columns"


def test_warm_lp_answers_with_it_and_agrees_with_highs_alone():
    """The retimer's WarmLP: no fallback to HiGHS, HiGHS's optimal value."""
    c, A, b, keys, E, e, bounds, _ = _lp(2)
    compiled, highs = WarmLP(), WarmLP(compiled=False)
    always = np.zeros(len(b), dtype=bool)
    for step in range(2):
        cost = c * (1.0 + 0.2 * step * np.sin(np.arange(len(c))))
        z, _ = compiled.solve(cost, A, b, keys, E, e, bounds, always)
        z_highs, _ = highs.solve(cost, A, b, keys, E, e, bounds, always)
        assert z is not None and z_highs is not None
        assert cost @ z == pytest.approx(cost @ z_highs, rel=1e-7)
    assert compiled.fallbacks == 0 and compiled.solves == 0  # no HiGHS run
