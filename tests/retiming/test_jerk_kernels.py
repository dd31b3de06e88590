"""The jerk-limited retimer's compiled grasp screen against numpy's products."""

import numpy as np

from rt_drake.retiming._jerk_kernels import grasp_screen


def test_grasp_screen_matches_the_matrix_product():
    """Each pair's ``F_r w_p / g_r >= threshold`` and each point's largest ratio.

    Reference: ``w = a u + b x + c`` and ``(w @ F.T) / g`` as dense numpy
    products (BLAS), on random wrenches and rows, with a threshold inside
    the ratios' range so that both outcomes occur.
    """
    rng = np.random.default_rng(3)
    a, b, c = (rng.normal(size=(40, 6)) for _ in range(3))
    x, u = rng.random(40), rng.normal(size=40)
    F, g = rng.normal(size=(25, 6)), 0.5 + rng.random(25)
    ratio = ((a * u[:, None] + b * x[:, None] + c) @ F.T) / g
    threshold = float(np.median(ratio))
    over, largest = np.empty((40, 25), dtype=bool), np.empty(40)
    scaled_t = np.ascontiguousarray((F / g[:, None]).T)
    grasp_screen(a, b, c, x, u, scaled_t, threshold, over, largest)
    np.testing.assert_allclose(largest, ratio.max(axis=1), rtol=1e-12, atol=1e-12)
    near = np.abs(ratio - threshold) < 1e-12  # rounding may decide these
    np.testing.assert_array_equal(over[~near], (ratio >= threshold)[~near])
    assert 0 < over.sum() < over.size
