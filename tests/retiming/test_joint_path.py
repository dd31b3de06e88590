"""Any path: waypoints, Drake trajectories and toppra interpolators retime alike.

The same geometry in different types gives the same duration (the path is
used, never resampled); a path of another kind retimes within every limit;
what is not a path is refused with a typed error.
"""

from __future__ import annotations

import numpy as np
import pytest
import toppra
from pydrake.math import BsplineBasis
from pydrake.trajectories import BsplineTrajectory, PiecewisePolynomial, Trajectory
from scipy.interpolate import CubicSpline, make_interp_spline

from rt_drake.model.held import held_object_of
from rt_drake.retiming import (
    GraspConstraint,
    JointLimits,
    RetimeInputError,
    check_trajectory,
    chord_knots,
    retime,
)
from rt_drake.retiming._joint_path import as_joint_path

HOME = np.array([0.0, 0.35, 1.75, 0.0, 1.04, 0.0])
WAYPOINTS = np.array(
    [
        HOME,
        HOME + [0.2, -0.25, -0.3, 0.0, 0.35, 0.2],
        HOME + [0.9, -0.15, -0.2, 0.1, 0.3, 0.6],
        HOME + [1.3, 0.05, 0.1, 0.0, -0.15, 1.0],
    ]
)


@pytest.fixture(scope="module")
def setting(plant, scenario):
    limits = JointLimits.from_plant(plant, scenario.robot)
    held = held_object_of(scenario.object("notebook"))
    return limits, GraspConstraint.for_cup(held, scenario.cup)


def _spline():
    return CubicSpline(chord_knots(WAYPOINTS), WAYPOINTS, bc_type="clamped")


def piecewise_polynomial(t0=0.0, t1=1.0):
    """The same C2 spline as cubic Hermite pieces, on [t0, t1]."""
    spline, knots = _spline(), chord_knots(WAYPOINTS)
    times = t0 + knots * (t1 - t0)
    return PiecewisePolynomial.CubicHermite(
        times, WAYPOINTS.T, spline(knots, 1).T / (t1 - t0)
    )


def bspline():
    """The same clamped cubic spline as a B-spline (order 4)."""
    knots = chord_knots(WAYPOINTS)
    fit = make_interp_spline(
        knots, WAYPOINTS, k=3, bc_type=([(1, np.zeros(6))], [(1, np.zeros(6))])
    )
    basis = BsplineBasis(4, list(fit.t))
    return BsplineTrajectory(basis, [row.reshape(-1, 1) for row in fit.c])


def test_one_geometry_in_every_type_has_one_duration(plant, setting):
    limits, grasp = setting
    reference = retime(plant, WAYPOINTS, limits, grasp)
    toppra_spline = toppra.SplineInterpolator(
        chord_knots(WAYPOINTS), WAYPOINTS, bc_type="clamped"
    )
    for path in (piecewise_polynomial(), piecewise_polynomial(2.0, 5.5), bspline(),
                 toppra_spline):  # fmt: skip
        joint_path = as_joint_path(path)
        s = np.linspace(0.0, 1.0, 57)
        for order in range(3):
            np.testing.assert_allclose(
                joint_path(s, order), _spline()(s, order), rtol=1e-9, atol=1e-9
            )
        assert joint_path.cubic
        np.testing.assert_allclose(joint_path.breaks, chord_knots(WAYPOINTS))
        result = retime(plant, path, limits, grasp)
        assert result.duration == pytest.approx(reference.duration, rel=1e-9)


def test_a_non_cubic_path_retimes_within_every_limit(plant, setting):
    """A B-spline of order 6: derivatives between grid points come from the
    path itself, and the limits hold at 1 kHz all the same."""
    limits, grasp = setting
    path = bspline_of_order(6)
    assert not as_joint_path(path).cubic
    result = retime(plant, path, limits, grasp)
    check = check_trajectory(plant, result.trajectory, limits, grasp)
    assert check.min_margin() >= -1e-3, check.summary()
    np.testing.assert_allclose(result.trajectory.value(0.0).ravel(), HOME, atol=1e-9)


#: Zero velocity and acceleration at an end (for the order-6 B-spline).
REST = [(1, np.zeros(6)), (2, np.zeros(6))]


def bspline_of_order(order):
    """A B-spline of the given order through the waypoints (not cubic)."""
    knots = chord_knots(WAYPOINTS)
    fit = make_interp_spline(
        knots,
        WAYPOINTS,
        k=order - 1,
        bc_type=(REST, REST),
    )
    basis = BsplineBasis(order, list(fit.t))
    return BsplineTrajectory(basis, [row.reshape(-1, 1) for row in fit.c])


class _NoDerivative(Trajectory):
    def __init__(self):
        Trajectory.__init__(self)

    def do_value(self, t):
        return HOME.reshape(-1, 1)

    def do_has_derivative(self):
        return False

    def do_rows(self):
        return 6

    def do_cols(self):
        return 1

    def do_start_time(self):
        return 0.0

    def do_end_time(self):
        return 1.0

    def Clone(self):
        return _NoDerivative()


@pytest.mark.parametrize(
    "path, words",
    [
        ("a string", "unsupported path of type str"),
        ({"waypoints": 1}, "unsupported path of type dict"),
        (_NoDerivative(), "has no derivatives"),
        (PiecewisePolynomial(np.ones((6, 2))), "column vector"),
    ],
)
def test_what_is_not_a_path_is_refused(plant, setting, path, words):
    limits, _ = setting
    with pytest.raises(RetimeInputError, match=words):
        retime(plant, path, limits)
