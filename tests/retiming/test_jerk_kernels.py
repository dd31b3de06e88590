"""The jerk-limited retimer's compiled grasp screen against numpy's products."""

import numpy as np

from rt_drake.retiming._jerk_kernels import grasp_screen, jerk_ratios


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


def test_jerk_ratios_match_the_jerk_by_finite_differences():
    """``|q'''_j| / J_j`` at points of a segment against differences in time.

    Reference: on one interior segment with u linear in s (k = du/ds
    constant), q(s) is a polynomial with known derivatives and s(t) is
    integrated finely from ``s' = sqrt(x)``, ``s'' = u``; the joint jerk is
    the third central difference of ``q(s(t))`` at the point's time.
    """
    s_grid = np.array([0.0, 1.0])
    x0, u0, u1 = 4.0, 1.5, -2.0
    z = np.array([x0, x0 + (u0 + u1), u0, u1])
    c3 = np.array([[0.3, -0.2], [0.1, 0.4], [-0.5, 0.2], [0.05, 0.1]])  # q = sum c s^i

    def q(s, order):
        powers = np.arange(4)
        out = np.zeros((len(s), 2))
        for i in powers[order:]:
            factor = np.prod(np.arange(i - order + 1, i + 1))
            out += factor * np.outer(s ** (i - order), c3[i])
        return out

    sigma = np.array([0.1, 0.35, 0.6, 0.9])
    from rt_drake.retiming._jerk_rows import Band
    from rt_drake.retiming._jerk_timed_path import Piece

    band = Band.of(s_grid, np.array([Piece.INTERIOR]), np.zeros(4, dtype=int), sigma)
    jerk = np.array([2.0, 3.0])
    out = np.empty((4, 2))
    jerk_ratios(
        band.cols, band.X, band.U, band.K, z, q(sigma, 1), q(sigma, 2), q(sigma, 3),
        jerk, np.ones(4, dtype=bool), out,
    )  # fmt: skip
    # s(t) from s'' = u(s) = u0 + (u1 - u0) s, s'(0) = sqrt(x0): RK4, 1e-5 s steps.
    step = 1e-5

    def field(state):
        return np.array([state[1], u0 + (u1 - u0) * state[0]])

    state, t_s = np.array([0.0, np.sqrt(x0)]), [0.0]
    while state[0] < 1.0:
        k1 = field(state)
        k2 = field(state + 0.5 * step * k1)
        k3 = field(state + 0.5 * step * k2)
        k4 = field(state + step * k3)
        state = state + step / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        t_s.append(state[0])
    path = q(np.array(t_s), 0)
    h = 10  # differences over 10 steps (1e-4 s)
    for p, target in enumerate(sigma):
        i = int(np.searchsorted(t_s, target))
        window = path[i - 2 * h : i + 2 * h + 1 : h]
        third = (window[4] - 2 * window[3] + 2 * window[1] - window[0]) / (
            2.0 * (h * step) ** 3
        )
        np.testing.assert_allclose(out[p], np.abs(third) / jerk, rtol=2e-3, atol=2e-4)
