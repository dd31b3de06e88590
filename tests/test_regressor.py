"""The wrench regressor: linear in the inertial parameters, equal to Newton-Euler."""

import numpy as np
import pytest
from scipy.interpolate import CubicSpline

from rt_drake.dynamics.regressor import (
    path_wrench_regressor,
    torque_regressor,
)
from rt_drake.dynamics.wrench import (
    path_torque_coefficients,
    path_wrench_coefficients,
)
from rt_drake.types.held_object import HeldObject
from rt_drake.uncertainty.inertial_set import inertial_parameters

HOME = np.array([0.0, 0.35, 1.75, 0.0, 1.04, 0.0])
WAYPOINTS = np.array(
    [
        HOME,
        HOME + [0.5, -0.2, 0.3, 0.4, -0.3, 1.0],
        HOME + [1.2, 0.1, -0.2, -0.3, 0.2, 2.0],
    ]
)


@pytest.fixture(scope="module")
def path_samples():
    spline = CubicSpline([0.0, 0.4, 1.0], WAYPOINTS, bc_type="clamped")
    s = np.linspace(0.0, 1.0, 23)
    return spline(s), spline(s, 1), spline(s, 2)


def _objects():
    rng = np.random.default_rng(5)
    for _ in range(4):
        # A body: I = tr(C) 1 - C for a second moment C of its mass (>= 0).
        A = rng.normal(size=(3, 3)) * 1e-2
        C = A @ A.T + 1e-4 * np.eye(3)
        yield HeldObject(
            rng.uniform(0.1, 2.0),
            rng.normal(size=3) * 0.03,
            np.trace(C) * np.eye(3) - C,
        )


def test_regressor_times_parameters_is_the_wrench_and_torques(plant, path_samples):
    q, dq, ddq = path_samples
    Y, kin = path_wrench_regressor(plant, q, dq, ddq, dynamics=True)
    arm, torque_per_parameter = torque_regressor(kin, dq, ddq, Y)
    for held in _objects():
        pi = inertial_parameters(held)
        expected = path_wrench_coefficients(plant, held, q, dq, ddq)
        for got, want in zip(Y.coefficients(pi), expected, strict=True):
            np.testing.assert_allclose(got, want, atol=1e-12 * np.abs(want).max())
        tau = path_torque_coefficients(plant, q, dq, ddq, held)
        for own, part, want in zip(arm, torque_per_parameter, tau, strict=True):
            np.testing.assert_allclose(
                own + part @ pi, want, atol=1e-11 * np.abs(want).max()
            )


def test_coefficients_of_many_parameter_vectors(plant, path_samples):
    q, dq, ddq = path_samples
    Y, _ = path_wrench_regressor(plant, q, dq, ddq)
    many = np.array([inertial_parameters(h) for h in _objects()])
    stacked = Y.coefficients(many)
    for p, pi in enumerate(many):
        for got, one in zip(stacked, Y.coefficients(pi), strict=True):
            np.testing.assert_allclose(got[:, p], one, atol=1e-15)
