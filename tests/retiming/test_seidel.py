"""rt_drake.retiming.seidel: the compiled 2-variable LP and TOPP-RA passes.

The LP is compared with HiGHS (scipy) on random LPs that have a known
interior point (feasible) or two opposed rows that exclude each other
(infeasible); the passes with toppra's TOPPRA class on random constraints.
"""

import numpy as np
import pytest
import toppra
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import linprog
from toppra.algorithm import TOPPRA

from rt_drake.retiming import seidel
from rt_drake.retiming.passes import AffineConstraint, XBound, reachability


def _random_lp(seed: int, rows: int):
    """Rows ``a z0 + b z1 + c <= 0`` strictly satisfied at a random point."""
    rng = np.random.default_rng(seed)
    inside = rng.uniform(-1.0, 1.0, 2)
    a, b = rng.normal(size=(2, rows))
    c = -(a * inside[0] + b * inside[1]) - rng.uniform(0.1, 2.0, rows)
    v = rng.normal(size=2)
    return a, b, c, v, rng


def _solve(a, b, c, v, low, high, active=None):
    rows = len(a)
    active = np.full(2, -1, np.int64) if active is None else active
    return seidel.lp2d(
        v[0],
        v[1],
        a,
        b,
        c,
        low,
        high,
        active,
        np.zeros(rows, np.int64),
    )


@settings(max_examples=60, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), rows=st.integers(1, 60))
def test_lp2d_optimum_equals_highs(seed, rows):
    a, b, c, v, _ = _random_lp(seed, rows)
    low, high = np.array([-10.0, -10.0]), np.array([10.0, 10.0])
    feasible, z0, z1 = _solve(a, b, c, v, low, high)
    A_ub = np.column_stack([a, b])
    reference = linprog(-v, A_ub=A_ub, b_ub=-c, bounds=[(-10.0, 10.0)] * 2)
    assert feasible and reference.status == 0
    z = np.array([z0, z1])
    assert v @ z == pytest.approx(-reference.fun, rel=1e-9, abs=1e-9)
    assert np.all(a * z0 + b * z1 + c <= 1e-9)
    assert np.all((low - 1e-12 <= z) & (z <= high + 1e-12))


@settings(max_examples=30, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), rows=st.integers(1, 40))
def test_lp2d_warm_start_only_reorders(seed, rows):
    """Any pair of rows tried first gives the same optimum value."""
    a, b, c, v, rng = _random_lp(seed, rows)
    low, high = np.array([-10.0, -10.0]), np.array([10.0, 10.0])
    _, *cold = _solve(a, b, c, v, low, high)
    active = rng.integers(0, rows, 2).astype(np.int64)
    feasible, *warm = _solve(a, b, c, v, low, high, active)
    assert feasible
    assert v @ warm == pytest.approx(v @ cold, rel=1e-9, abs=1e-9)


@settings(max_examples=30, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), rows=st.integers(0, 20))
def test_lp2d_detects_infeasible(seed, rows):
    """Rows ``n z <= -1`` and ``-n z <= -1`` exclude each other."""
    a, b, c, v, rng = _random_lp(seed, rows)
    n = rng.normal(size=2)
    a, b = np.append(a, [n[0], -n[0]]), np.append(b, [n[1], -n[1]])
    c = np.append(c, [1.0, 1.0])
    order = rng.permutation(len(a))
    feasible, *_ = _solve(
        a[order], b[order], c[order], v, np.full(2, -10.0), np.full(2, 10.0)
    )
    assert not feasible


#: toppra's box on a stage's (u, x): |u| <= 1e8, 0 <= x <= 1e8.
_STAGE_LOW, _STAGE_HIGH = np.array([-1e8, 0.0]), np.array([1e8, 1e8])


def test_lp2d_row_with_tiny_coefficients_beside_the_box():
    """The stage-0 LP of a path whose joint 5 barely moves (3e-6 rad).

    Rows ``0.0202 u + x <= 14.98`` (the next controllable set) and
    ``1.8e-5 x <= 23.7`` (joint 5's acceleration at rest: q' = 0, tiny
    q''), max x. From the box corner (-1e8, 1e8) the optimum on the second
    row's line lies at t = 3.6e12 along d = (-1.8e-5, 0): toppra's bound
    |t| <= 1e10 called this LP infeasible (and the path not controllable).
    """
    a = np.array([0.0202, 0.0])
    b = np.array([1.0, 1.8e-5])
    c = np.array([-14.98, -23.7])
    v = np.array([-1e-9, 1.0])
    feasible, z0, z1 = _solve(a, b, c, v, _STAGE_LOW, _STAGE_HIGH)
    bounds = list(zip(_STAGE_LOW, _STAGE_HIGH, strict=True))
    reference = linprog(-v, A_ub=np.column_stack([a, b]), b_ub=-c, bounds=bounds)
    assert feasible and reference.status == 0
    # x, the stage LP's answer (u only breaks ties, below toppra's tolerance).
    assert z1 == pytest.approx(reference.x[1], rel=1e-12)
    assert np.all(a * z0 + b * z1 + c <= 1e-9) and -1e8 <= z0 <= 1e8


def test_lp2d_rows_nearly_parallel_but_not_parallel():
    """Two grasp rows of small coefficients at an angle of 1.8e-7 rad.

    From a path whose joints 1, 2, 4, 5 barely move beside a 0.56 rad turn
    of joint 3 (stage 17 of 100, notebook): ``n z + c <= 0`` with |n| ~
    0.01 and ``|d . n_j| = 1.2e-11``, below toppra's absolute 1e-10, so
    toppra took them for parallel, the second excluding the first's line:
    infeasible. Max x is the box; min u at that x, in closed form.
    """
    a = np.array([-0.003444943876944749, -0.0014877977106025717])
    b = np.array([-0.011540969795863412, -0.0049842951055596154])
    c = np.array([-0.2047887982667987, -0.08844393470496564])
    high = np.array([1e8, 36.24816423903144])
    feasible, z0, z1 = _solve(a, b, c, np.array([-1e-9, 1.0]), _STAGE_LOW, high)
    assert feasible and z1 == high[1]
    # a < 0: a u + b x + c <= 0 is u >= -(b x + c) / a.
    assert z0 == pytest.approx(np.max(-(b * high[1] + c) / a), rel=1e-9)


@settings(max_examples=60, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    rows=st.integers(0, 30),
    far=st.integers(1, 4),
    maximise_x=st.booleans(),
)
def test_lp2d_with_far_rows_of_tiny_coefficients_equals_highs(
    seed, rows, far, maximise_x
):
    """Rows of tiny coefficients far outside the region change nothing.

    ``eps (n z) + c <= 0`` with eps in [1e-7, 1e-4], c in [-30, -1]: the
    bound of a joint's acceleration where the joint barely moves, far from
    a region that rows of ordinary size bound (|u| <= 100, x <= 50, random
    rows through it), inside toppra's stage box; the stage objectives (max
    x, min x, toppra's tie-breaking weight on u). Compared with HiGHS.
    """
    rng = np.random.default_rng(seed)
    inside = np.array([rng.uniform(-5.0, 5.0), rng.uniform(0.5, 20.0)])
    n = rng.normal(size=(2, rows))
    c = -(n.T @ inside) - rng.uniform(0.1, 2.0, rows)
    eps = 10.0 ** rng.uniform(-7.0, -4.0, far)
    tiny = rng.normal(size=(2, far)) * eps
    a = np.concatenate([n[0], [1.0, -1.0, 0.0], tiny[0]])
    b = np.concatenate([n[1], [0.0, 0.0, 1.0], tiny[1]])
    c = np.concatenate([c, [-100.0, -100.0, -50.0], -rng.uniform(1.0, 30.0, far)])
    order = rng.permutation(len(a))
    a, b, c = a[order], b[order], c[order]
    v = np.array([-1e-9, 1.0]) if maximise_x else np.array([1e-9, -1.0])
    feasible, z0, z1 = _solve(a, b, c, v, _STAGE_LOW, _STAGE_HIGH)
    bounds = list(zip(_STAGE_LOW, _STAGE_HIGH, strict=True))
    reference = linprog(-v, A_ub=np.column_stack([a, b]), b_ub=-c, bounds=bounds)
    assert reference.status == 0 and feasible
    assert z1 == pytest.approx(reference.x[1], rel=1e-9, abs=1e-9)
    assert np.all(a * z0 + b * z1 + c <= 1e-9)


def test_lp1d_takes_the_bound_in_the_objective_direction():
    a, b = np.array([2.0, -1.0, 0.0]), np.array([-4.0, -1.0, 5.0])  # -1 <= t <= 2
    assert seidel.lp1d(1.0, a, b, 2, -10.0, 10.0)[:2] == (True, 2.0)
    assert seidel.lp1d(-1.0, a, b, 2, -10.0, 10.0)[:2] == (True, -1.0)
    assert not seidel.lp1d(1.0, a, b, 2, 3.0, 10.0)[0]


@settings(max_examples=20, deadline=None)
@given(seed=st.integers(0, 2**32 - 1))
def test_passes_equal_toppra_on_random_constraints(seed):
    """Random ``|F (a u + b x + c)| <= g`` along a grid: same s'(s) profile."""
    rng = np.random.default_rng(seed)
    points, m, k = 30, 3, 8
    grid = np.linspace(0.0, 1.0, points)
    a, b = rng.normal(size=(2, points, m))
    c = 0.1 * rng.normal(size=(points, m))
    F = rng.normal(size=(k, m))
    g = np.abs(F @ c.T).max(axis=1) + rng.uniform(0.5, 2.0, k)  # rest is inside
    x_bound = np.column_stack([np.zeros(points), rng.uniform(5.0, 50.0, points)])
    constraints = [XBound(x_bound), AffineConstraint(a, b, c, F, g)]
    ours = reachability(constraints, None, grid)
    path = toppra.SplineInterpolator(grid, np.zeros((points, 1)))
    stock = TOPPRA(constraints, path, grid, solver_wrapper="seidel")
    _, sd, _, K = stock.compute_parameterization(0.0, 0.0, return_data=True)
    if sd is None:
        assert ours.failed_stage is not None
        return
    assert ours.failed_stage is None
    np.testing.assert_allclose(ours.K, K, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(np.sqrt(ours.x), sd, rtol=1e-9, atol=1e-12)
