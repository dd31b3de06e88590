"""The jerk-limited retimer's compiled loops against numpy and closed forms.

The grasp screen against numpy's products, the jerk ratios against
finite differences, the quadrature against numpy's sums and closed forms.
"""

import numpy as np

from rt_drake.retiming._jerk_kernels import grasp_screen, jerk_ratios


def test_grasp_screen_matches_the_matrix_product():
    """Each pair's ``F_r w_p / g_r >= threshold`` and each point's largest ratio.

    Reference: ``w = a u + b x + c`` and ``(w @ F.T) / g`` as dense numpy
    products (BLAS), on random wrenches and rows, with a threshold inside
    the ratios' range so that both outcomes occur; at every other point
    (the others untouched).
    """
    rng = np.random.default_rng(3)
    a, b, c = (rng.normal(size=(40, 6)) for _ in range(3))
    x, u = rng.random(40), rng.normal(size=40)
    F, g = rng.normal(size=(25, 6)), 0.5 + rng.random(25)
    ratio = ((a * u[:, None] + b * x[:, None] + c) @ F.T) / g
    threshold = float(np.median(ratio))
    over, largest = np.zeros((40, 25), dtype=bool), np.full(40, -np.inf)
    scaled_t = np.ascontiguousarray((F / g[:, None]).T)
    at = np.arange(1, 40, 2)  # every other point: the others left as they were
    grasp_screen(a, b, c, x, u, scaled_t, threshold, at, over, largest)
    np.testing.assert_allclose(
        largest[at], ratio[at].max(axis=1), rtol=1e-12, atol=1e-12
    )
    assert np.all(largest[::2] == -np.inf) and not over[::2].any()
    near = np.abs(ratio[at] - threshold) < 1e-12  # rounding may decide these
    np.testing.assert_array_equal(over[at][~near], (ratio[at] >= threshold)[~near])
    assert 0 < over.sum() < over[at].size


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


def test_the_compiled_quadrature_is_numpys_bit_for_bit_and_exact_where_x_is_flat():
    """``interior_duration`` against the numpy sums it replaced, and closed forms.

    References: (1) the numpy form ``sum(0.5 ds sum(w / sqrt(x(sigma))))``
    with numpy's pairwise sums, to the bit, on random segments of many
    sizes; (2) ``u = 0``: x constant on each segment, the duration ``sum ds
    / sqrt(x)``; (3) ``u_i = u_{i+1} = u``: x linear, ``2 ds / (sqrt(x_i) +
    sqrt(x_{i+1}))``; (4) inf where x reaches 0 inside a segment.
    """
    from rt_drake.retiming._jerk_kernels import interior_duration

    nodes, weights = np.polynomial.legendre.leggauss(16)
    sigma = 0.5 * (nodes + 1.0)
    rise, square = 2.0 * sigma - sigma**2, sigma**2
    rng = np.random.default_rng(7)
    for count in (0, 1, 7, 8, 9, 17, 113, 129, 300):
        ds = 0.01 + rng.random(count)
        x = 20.0 + 10.0 * rng.random(count)  # x > 0 all along
        u, u_next = 0.5 * rng.normal(size=count), 0.5 * rng.normal(size=count)
        xs = x[:, None] + ds[:, None] * (rise * u[:, None] + square * u_next[:, None])
        expected = float(np.sum(0.5 * ds * np.sum(weights / np.sqrt(xs), axis=1)))
        assert interior_duration(ds, x, u, u_next, rise, square, weights) == expected
    ds, x = 0.01 + rng.random(20), 1.0 + rng.random(20)
    zero = np.zeros(20)
    flat = interior_duration(ds, x, zero, zero, rise, square, weights)
    np.testing.assert_allclose(flat, np.sum(ds / np.sqrt(x)), rtol=1e-14)
    slope = np.full(20, 0.3)
    x_next = x + 2.0 * ds * slope
    linear = interior_duration(ds, x, slope, slope, rise, square, weights)
    np.testing.assert_allclose(
        linear, np.sum(2.0 * ds / (np.sqrt(x) + np.sqrt(x_next))), rtol=1e-12
    )
    # x = 1 - 4 sigma + 4 sigma^2 on [0, 1] (ds 1, u_0 = -2, u_1 = 2): 0 at 1/2.
    one = np.ones(1)
    stops = interior_duration(one, one, -2.0 * one, 2.0 * one, rise, square, weights)
    assert stops == np.inf


def test_joint_and_acceleration_ratios_are_numpys_to_the_bit():
    """``joint_ratios``, ``acceleration_ratios`` and ``row_max`` against numpy.

    Reference: the numpy forms they replaced in ``JerkPoints``: x and u by
    scipy's sparse product of the band's maps (x clipped at 0), the
    velocity ratio ``sqrt(x / x_cap)`` (0 where x is 0) and ``|q' u + q''
    x| / a`` per joint, reduced by ``np.max``; on random points, with
    profiles that go negative (x clipped), caps of 0 and inf.
    """
    from rt_drake.retiming._jerk_kernels import (
        acceleration_ratios,
        joint_ratios,
        row_max,
    )
    from rt_drake.retiming._jerk_rows import Band
    from rt_drake.retiming._jerk_timed_path import Piece

    rng = np.random.default_rng(11)
    segments, P, n = 6, 60, 7
    s = np.sort(np.concatenate([[0.0, 1.0], rng.random(segments - 1)]))
    kinds = np.full(segments, Piece.INTERIOR)
    band = Band.of(s, kinds, rng.integers(0, segments, P), rng.random(P))
    maps = band.maps(len(s))
    dq, ddq = rng.normal(size=(P, n)), rng.normal(size=(P, n))
    x_cap = 0.5 + rng.random(P)
    x_cap[:3] = 0.0, np.inf, 1e-300
    acceleration = 0.5 + rng.random(n)
    for _ in range(5):
        z = rng.normal(size=2 * len(s))  # some x < 0 at the points
        x, u = np.maximum(maps.X.tocsr() @ z, 0.0), maps.U.tocsr() @ z
        with np.errstate(divide="ignore", invalid="ignore"):
            velocity = np.sqrt(np.where(x > 0.0, x / x_cap, 0.0))
        ratio = np.abs(dq * u[:, None] + ddq * x[:, None]) / acceleration
        expected = np.maximum(velocity, np.max(ratio, axis=1))
        out = np.empty(P)
        joint_ratios(band.cols, band.X, band.U, z, dq, ddq, x_cap, acceleration, out)
        np.testing.assert_array_equal(out, expected)
        at = np.sort(rng.choice(P, 20, replace=False))
        some = np.empty((20, n))
        acceleration_ratios(
            band.cols, band.X, band.U, z, dq, ddq, acceleration, at, some
        )
        np.testing.assert_array_equal(some, ratio[at])
        largest = np.empty(P)
        row_max(ratio, largest)
        np.testing.assert_array_equal(largest, np.max(ratio, axis=1))
    assert np.any(maps.X.tocsr() @ z < 0.0)  # the clipping was exercised
