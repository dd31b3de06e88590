"""The bellows' ring under a load: ``bellows_wrench`` against closed forms.

References: the step response of a damped oscillator peaks at ``1 +
exp(-zeta pi / sqrt(1 - zeta^2))`` of the step; an undamped one under a
ramp of x periods to a constant load at ``1 + |sin(pi x) / (pi x)|``
(Chopra, Dynamics of Structures, "step force with finite rise time"); a
full 6-DOF ``M d'' + C d' + K d = w`` with proportional damping integrated
by ``scipy.integrate.solve_ivp``.
"""

from __future__ import annotations

import numpy as np
import pytest
from pydrake.math import RigidTransform, RollPitchYaw
from scipy.integrate import solve_ivp

from rt_drake.dynamics.bellows_modes import (
    bellows_wrench,
    modal_damping_ratios,
    tool_damping,
    tool_stiffness,
)
from rt_drake.errors import InputError
from rt_drake.model.cup_physics import load_bellows_cup

PERIOD_S = 0.3
OMEGA = 2.0 * np.pi / PERIOD_S


def oscillators(zeta: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Six uncoupled unit masses, the first of period PERIOD_S, others stiffer."""
    omega = OMEGA * np.array([1.0, 1.3, 1.7, 2.1, 2.6, 3.2])
    return np.diag(omega**2), np.diag(2.0 * zeta * omega), np.eye(6)


@pytest.mark.parametrize("zeta", [0.0, 0.07, 0.3])
def test_a_step_peaks_at_one_plus_the_damped_overshoot(zeta):
    K, C, M = oscillators(zeta)
    t = np.linspace(0.0, 1.0, 20001)  # the step rises over 5e-5 s, 1/6000 period
    w = np.zeros((t.size, 6))
    w[1:, 0] = 3.0  # N m on the slowest mode
    peak = np.abs(bellows_wrench(t, w, K, C, M)[:, 0]).max() / 3.0
    expected = 1.0 + np.exp(-zeta * np.pi / np.sqrt(1.0 - zeta**2))
    assert peak == pytest.approx(expected, abs=2e-3)


@pytest.mark.parametrize("x", [0.5, 1.0, 1.43, 2.3])
def test_an_undamped_ramp_peaks_at_one_plus_its_sinc(x):
    K, C, M = oscillators(0.0)
    t = np.linspace(0.0, x * PERIOD_S + 1.0, 4001)
    w = np.zeros((t.size, 6))
    w[:, 3] = 5.0  # a constant load on another mode: it stays in equilibrium
    w[:, 0] = 2.0 * np.clip(t / (x * PERIOD_S), 0.0, 1.0)
    carried = bellows_wrench(t, w, K, C, M)
    expected = 1.0 + abs(np.sin(np.pi * x) / (np.pi * x))
    assert carried[:, 0].max() / 2.0 == pytest.approx(expected, abs=2e-3)
    np.testing.assert_allclose(carried[:, 3], 5.0, atol=1e-9)


def two_cup_carton() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """K, C of two catalogue cups 12 cm apart; M a carton off their axis."""
    cup = load_bellows_cup("vs060_bellows")
    X_TCs = [RigidTransform([0.06, 0.0, 0.0]), RigidTransform([-0.06, 0.0, 0.0])]
    m, p = 2.2, np.array([0.01, -0.005, 0.03])
    S = np.array([[0.0, -p[2], p[1]], [p[2], 0.0, -p[0]], [-p[1], p[0], 0.0]])
    R = RollPitchYaw(0.1, 0.2, 0.3).ToRotationMatrix().matrix()
    I_cm = R @ np.diag([0.004, 0.02, 0.022]) @ R.T
    M = np.block([[I_cm + m * S.T @ S, m * S], [-m * S, m * np.eye(3)]])
    return tool_stiffness(cup, X_TCs), tool_damping(cup, X_TCs), M


def test_the_modes_ring_as_the_full_coupled_system_does():
    K, _, M = two_cup_carton()
    C = 0.4 * M + 1e-3 * K  # proportional: exactly diagonal in the modes
    t = np.linspace(0.0, 1.2, 1201)
    rng = np.random.default_rng(3)
    knots = rng.normal(size=(7, 6)) * [0.5, 0.5, 0.2, 8.0, 8.0, 20.0]
    w = np.array(
        [np.interp(t, np.linspace(0, 1.2, 7), knots[:, j]) for j in range(6)]
    ).T
    carried = bellows_wrench(t, w, K, C, M)

    def load(s: float) -> np.ndarray:
        return np.array([np.interp(s, t, w[:, j]) for j in range(6)])

    def rhs(s: float, y: np.ndarray) -> np.ndarray:
        d, v = y[:6], y[6:]
        return np.concatenate([v, np.linalg.solve(M, load(s) - C @ v - K @ d)])

    d0 = np.linalg.solve(K, w[0])
    ref = solve_ivp(
        rhs, (0.0, 1.2), np.concatenate([d0, np.zeros(6)]), t_eval=t,
        rtol=1e-9, atol=1e-12, max_step=1e-3,
    )  # fmt: skip
    expected = (K @ ref.y[:6]).T
    scale = np.abs(expected).max(axis=0)
    np.testing.assert_allclose(carried / scale, expected / scale, atol=1e-4)
    _, zeta, _ = modal_damping_ratios(K, C, M)
    omega = np.sqrt(np.linalg.eigvals(np.linalg.solve(M, K)).real)
    omega = np.sort(omega)
    np.testing.assert_allclose(zeta, 0.2 / omega + 5e-4 * omega, rtol=1e-6)


def test_a_constant_load_stays_in_equilibrium():
    K, C, M = two_cup_carton()
    t = np.linspace(0.0, 1.0, 501)
    w = np.tile([0.1, -0.2, 0.05, 1.0, -2.0, -21.6], (t.size, 1))
    np.testing.assert_allclose(bellows_wrench(t, w, K, C, M), w, atol=1e-9)


def test_unequal_steps_are_refused_in_one_line():
    K, C, M = oscillators(0.1)
    with pytest.raises(InputError, match="equally spaced"):
        bellows_wrench(np.array([0.0, 0.1, 0.3]), np.zeros((3, 6)), K, C, M)
