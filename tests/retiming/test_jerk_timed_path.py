"""The Stumpff functions of the jerk-limited timed path against closed forms."""

import cmath

import numpy as np


def test_stumpff_is_the_closed_form_on_both_signs_and_near_zero():
    """``C0 = cosh sqrt z``, ``C1 = sinh sqrt z / sqrt z``, ``C2 = (C0 - 1) / z``.

    Reference: the complex square root (one formula for both signs of z)
    in Python's ``cmath``, elementwise; ``C2`` by its half-angle form
    ``2 sinh^2(r/2) / r^2`` (no cancellation); near 0 the series agrees
    to its truncation error (``z^4``).
    """
    from rt_drake.retiming._jerk_timed_path import stumpff

    rng = np.random.default_rng(5)
    z = rng.normal(size=(30, 7)) * 10.0 ** rng.uniform(-6, 1.5, (30, 7))
    z[0, :3] = 0.0, 1e-3, -1e-3
    c0, c1, c2 = stumpff(z)
    assert c0.shape == c1.shape == c2.shape == z.shape
    for got, want in (
        (c0, lambda r: cmath.cosh(r)),
        (c1, lambda r: cmath.sinh(r) / r if r else 1.0),
        (c2, lambda r: 2.0 * cmath.sinh(r / 2) ** 2 / r**2 if r else 0.5),
    ):
        reference = np.array([want(cmath.sqrt(v)).real for v in z.ravel()])
        np.testing.assert_allclose(got.ravel(), reference, rtol=1e-12, atol=0.0)
