"""The jerk retimer's grasp check that skips points far from the limit."""

import types

import numpy as np

from rt_drake.retiming._jerk_points import DENSE, DensePoints, GraspRows
from rt_drake.retiming._jerk_screen import grasp_check


def test_a_check_from_a_reference_finds_the_same_pairs_and_bounds_the_rest():
    """Against every ratio ``F_r w_p / g_r`` as a dense numpy product.

    Random wrench coefficients at 6 segments' dense points, a first check
    (every point), then the profile moved a little and checked again from
    the first: the pairs at or over the threshold are the reference's
    exactly, the grid points' largest ratios are exact, and every skipped
    point's stand-in is at least its true largest ratio and under the
    threshold.
    """
    rng = np.random.default_rng(5)
    points = 6 * len(DENSE)
    a, b, c = (rng.normal(size=(points, 6)) for _ in range(3))
    F, g = rng.normal(size=(40, 6)), 2.0 + rng.random(40)
    k = np.tile(np.arange(len(DENSE)), 6)
    dense = DensePoints(
        s=np.linspace(0.0, 1.0, points), k=k,
        samples=types.SimpleNamespace(wrench=(a, b, c)),  # type: ignore[arg-type]
        maps=None, band=None, grasp=GraspRows(F, g),  # type: ignore[arg-type]
    )  # fmt: skip

    def ratios(x, u):
        return ((a * u[:, None] + b * x[:, None] + c) @ F.T) / g

    x, u = rng.random(points), rng.normal(size=points)
    threshold = float(np.quantile(ratios(x, u).max(axis=1), 0.7))
    _, largest, reference = grasp_check(dense, x, u, threshold, None)
    np.testing.assert_allclose(largest, ratios(x, u).max(axis=1), rtol=1e-12)
    x2, u2 = x + 0.01 * rng.random(points), u + 0.01 * rng.normal(size=points)
    over, largest, _ = grasp_check(dense, x2, u2, threshold, reference)
    exact = ratios(x2, u2)
    near = np.abs(exact - threshold) < 1e-12
    np.testing.assert_array_equal(over[~near], (exact >= threshold)[~near])
    assert over.any()
    most = exact.max(axis=1)
    skipped = ~np.isclose(largest, most, rtol=1e-12, atol=1e-12)
    assert 0 < skipped.sum() < points - np.count_nonzero(k == 0)
    assert not np.any(skipped & (k == 0))
    assert np.all(largest[skipped] >= most[skipped])
    assert np.all(largest[skipped] < threshold)
