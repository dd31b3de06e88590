"""Batched clamped splines of the MOVE optimiser against scipy's."""

from __future__ import annotations

import numpy as np
from scipy.interpolate import CubicSpline

from rt_drake.retiming import chord_knots
from rt_drake.shaping._spline import (
    chord_knots_batch,
    evaluate_splines,
)


def test_batched_splines_match_scipy():
    rng = np.random.default_rng(0)
    for count in (2, 3, 9):
        W = np.cumsum(rng.normal(size=(4, count, 6)), axis=1)
        s = np.linspace(0.0, 1.0, 57)
        q, dq, ddq = evaluate_splines(W, s)
        for p in range(4):
            spline = CubicSpline(chord_knots(W[p]), W[p], bc_type="clamped")
            np.testing.assert_allclose(q[p], spline(s), atol=1e-12)
            np.testing.assert_allclose(dq[p], spline(s, 1), atol=1e-10)
            np.testing.assert_allclose(ddq[p], spline(s, 2), atol=1e-9)


def test_batched_knots_are_the_planners():
    rng = np.random.default_rng(1)
    W = rng.normal(size=(3, 5, 6))
    knots = chord_knots_batch(W)
    for p in range(3):
        np.testing.assert_allclose(knots[p], chord_knots(W[p]), atol=1e-15)
