"""rt_drake.retiming.stage_rows: grasp rows at rest, ray-shooting selection, check.

The compiled kernels are compared with plain numpy on the scenario cup's
exact polytope (834 rows) and random wrench coefficients.
"""

import dataclasses

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rt_drake.contact._cache import cached_wrench_polytope
from rt_drake.model.held import held_object_of
from rt_drake.retiming import (
    _row_groups as row_groups,
)
from rt_drake.retiming import (
    seidel,
)
from rt_drake.retiming import (
    stage_rows as rows,
)
from rt_drake.retiming._precompile import warm_up


@pytest.fixture(scope="module")
def polytope(scenario):
    return cached_wrench_polytope(scenario.cup)


def _coefficients(seed: int, points: int = 12):
    """Random a, b and a gravity-sized c (object of about 0.5 kg)."""
    rng = np.random.default_rng(seed)
    a = rng.normal(size=(points, 6)) * [0.05, 0.05, 0.02, 0.5, 0.5, 0.5]
    b = rng.normal(size=(points, 6)) * [0.05, 0.05, 0.02, 0.5, 0.5, 0.5]
    c = np.tile([0.0, 0.0, 0.0, 0.0, 0.0, 4.9], (points, 1))
    c[:, 3:5] += rng.normal(size=(points, 2))
    return a, b, c, rng.uniform(1.0, 30.0, points)


def _first_hits(alpha, beta, slack, x_cap):
    """The rows ray shooting must find at one point (plain numpy)."""
    hits = set()
    with np.errstate(divide="ignore", invalid="ignore"):
        up = beta / slack
        x_top = x_cap
        if up.max() > 0:
            hits.add(int(up.argmax()))
            x_top = min(x_cap, 1.0 / up.max())
        for h in rows.RAY_HEIGHTS:
            ratio = alpha / (slack - h * x_top * beta)
            for side in (ratio, -ratio):
                if side.max() > 0:
                    hits.add(int(side.argmax()))
    return hits


@settings(max_examples=15, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), stride=st.integers(1, 3))
def test_rest_and_candidates_equal_numpy(polytope, seed, stride):
    F, g = polytope.F, polytope.g
    a, b, c, x_cap = _coefficients(seed)
    rest, selected = rows.rest_and_candidates(
        a, b, c, rows.normalised_rows(F, g), x_cap, stride
    )
    np.testing.assert_allclose(rest, (c @ F.T / g).max(axis=1), rtol=1e-12)
    assert np.all(rest < 1.0)
    expected = set()
    for i in range(0, len(c), stride):
        slack = 1.0 - F @ c[i] / g
        expected |= _first_hits(F @ a[i] / g, F @ b[i] / g, slack, x_cap[i])
    assert set(selected.tolist()) == expected


def test_no_rows_selected_when_the_object_falls_at_rest(polytope):
    a, b, c, x_cap = _coefficients(0)
    c[5, 3:] = [50.0, 0.0, 0.0]  # 50 N sideways: beyond any friction
    rest, selected = rows.rest_and_candidates(
        a, b, c, rows.normalised_rows(polytope.F, polytope.g), x_cap
    )
    assert rest[5] > 1.0 and np.all(np.delete(rest, 5) < 1.0)
    assert selected.size == 0


@settings(max_examples=15, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    scale=st.floats(0.5, 3.0),
    floor=st.sampled_from([-np.inf, 0.5, 0.9]),
    exact=st.sampled_from([None, 0, 13, 40]),
)
def test_wrench_ratios_equal_numpy(polytope, seed, scale, floor, exact):
    """Every row evaluated by numpy; with a floor, the skipped groups change
    nothing but the maxima of rows that stay at or below the floor; past the
    first ``exact`` wrenches, a wrench's ratio is exact only above the
    floor."""
    F, g = polytope.F, polytope.g
    rng = np.random.default_rng(seed)
    wrenches = scale * rng.normal(size=(40, 6)) * [0.2, 0.2, 0.1, 3.0, 3.0, 6.0]
    ratio, violated, row_max = rows.wrench_ratios(
        wrenches, rows.normalised_rows(F, g), g, 1e-9, floor=floor, exact=exact
    )
    expected_max = (wrenches @ F.T / g).max(axis=0)
    above = expected_max > floor + 1e-12
    np.testing.assert_allclose(
        row_max[above], expected_max[above], rtol=1e-12, atol=1e-12
    )
    assert np.all(row_max[~above] <= floor + 2e-12)
    products = wrenches @ F.T
    largest = (products / g).max(axis=1)
    known = np.arange(40) < (40 if exact is None else exact)
    known |= largest > min(floor, 1.0) + 1e-12
    np.testing.assert_allclose(ratio[known], largest[known], rtol=1e-12)
    assert np.all(ratio[~known] <= min(floor, 1.0) + 2e-12)
    expected = np.flatnonzero((products - g > 1e-9).any(axis=0))
    np.testing.assert_array_equal(violated, expected)


def test_warm_up_compiles_what_retime_uses(plant, scenario, polytope):
    """After warm_up a retime with a grasp adds no compiled specialisation."""
    from rt_drake.dynamics import chain_kernels as _chain_kernels
    from rt_drake.retiming import (
        GraspConstraint,
        JointLimits,
        retime,
    )
    from rt_drake.retiming import (
        _between_kernels as between_kernels,
    )
    from rt_drake.retiming import (
        _jerk_kernels as jerk_kernels,
    )
    from rt_drake.retiming import (
        _segments as sub_points,
    )

    kernels = [
        seidel.passes,
        seidel.project,
        row_groups._build,
        row_groups.grouped_ratios,
        rows._rest_and_rays,
        sub_points._lagrange_kernel,
        *(getattr(between_kernels, name) for name in between_kernels.__all__),
        *(getattr(_chain_kernels, name) for name in _chain_kernels.__all__),
        *(getattr(jerk_kernels, name) for name in jerk_kernels.__all__),
    ]
    warm_up()
    before = [len(kernel.signatures) for kernel in kernels]
    held = held_object_of(scenario.object("notebook"))
    grasp = GraspConstraint(held, polytope.F, polytope.g)
    home = np.array([0.0, 0.35, 1.75, 0.0, 1.04, 0.0])
    limits = JointLimits.from_plant(plant, scenario.robot, torque=True)
    retime(plant, np.array([home, home + 0.3]), limits, grasp)
    # The jerk-limited retimer's kernels (a curve through a third waypoint).
    jerk = dataclasses.replace(limits, jerk=20.0 * limits.acceleration)
    waypoints = np.array([home, home + 0.3, home + [0.5, 0.2, 0.1, 0.0, 0.3, 0.1]])
    retime(plant, waypoints, jerk, grasp)
    assert [len(kernel.signatures) for kernel in kernels] == before
