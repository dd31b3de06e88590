"""GeometricPath: the spline convention shared with the retimer."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from toppra.interpolator import SplineInterpolator

from rt_drake.types.path import (
    GeometricPath,
    chord_knots,
    drop_repeated,
)

waypoint_arrays = arrays(
    float,
    st.tuples(st.integers(2, 8), st.just(6)),
    elements=st.floats(-3.0, 3.0, allow_nan=False),
).filter(lambda w: np.all(np.linalg.norm(np.diff(w, axis=0), axis=1) > 1e-3))


@settings(max_examples=40, deadline=None)
@given(waypoint_arrays)
def test_spline_is_toppras_clamped_chord_length_spline(waypoints):
    path = GeometricPath.from_waypoints(waypoints)
    chords = np.linalg.norm(np.diff(waypoints, axis=0), axis=1)
    np.testing.assert_allclose(path.knots, np.r_[0, np.cumsum(chords)] / chords.sum())
    toppra_path = SplineInterpolator(path.knots, waypoints, bc_type="clamped")
    s = np.linspace(0.0, 1.0, 97)
    np.testing.assert_allclose(path.value(s), toppra_path(s), atol=1e-12)
    np.testing.assert_allclose(path.deriv(s), toppra_path(s, 1), atol=1e-9)
    np.testing.assert_allclose(path.deriv2(s), toppra_path(s, 2), atol=1e-6)


@settings(max_examples=40, deadline=None)
@given(waypoint_arrays)
def test_spline_interpolates_rests_at_ends_and_is_c2(waypoints):
    path = GeometricPath.from_waypoints(waypoints)
    np.testing.assert_array_equal(path.value(0.0), waypoints[0])
    np.testing.assert_allclose(path.value(path.knots), waypoints, atol=1e-12)
    np.testing.assert_allclose(path.deriv(np.array([0.0, 1.0])), 0.0, atol=1e-12)
    # q'' continuous across interior knots (left and right limits agree).
    inner = path.knots[1:-1]
    scale = 1.0 + np.abs(path.deriv2(path.knots)).max()
    eps = 1e-9
    np.testing.assert_allclose(
        path.deriv2(inner - eps), path.deriv2(inner + eps), atol=1e-5 * scale
    )


def test_evaluation_is_vectorised():
    path = GeometricPath.from_waypoints(np.array([[0.0, 0.0], [1.0, 2.0], [2.0, 0.0]]))
    assert path.value(0.5).shape == (2,)
    assert path.deriv(np.linspace(0, 1, 5)).shape == (5, 2)
    assert path.deriv2(np.linspace(0, 1, 5)).shape == (5, 2)
    assert path.num_positions == 2
    assert path.joint_length() == pytest.approx(2 * np.sqrt(5))


def test_repeated_waypoints_are_rejected_or_dropped():
    waypoints = np.array([[0.0, 0.0], [0.0, 0.0], [1.0, 1.0]])
    with pytest.raises(ValueError, match="waypoints 0 and 1 are equal"):
        chord_knots(waypoints)
    kept = drop_repeated(np.array([[0, 0], [0, 0], [1, 1], [1, 1 + 1e-12]], float))
    np.testing.assert_array_equal(kept, [[0, 0], [1, 1 + 1e-12]])
    with pytest.raises(ValueError, match="N >= 2"):
        chord_knots(np.zeros((1, 6)))
