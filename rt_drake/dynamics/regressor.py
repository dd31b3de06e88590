"""The object wrench along a path as a linear map of its inertial parameters.

For the ten parameters ``pi = (m, h, I_Co)`` of :mod:`rt_drake.uncertainty.inertial_set`
(mass kg, first moment ``h = m p_CoScm_C`` kg m, rotational inertia about the
cup origin Co kg m^2, all in the cup frame C), Newton-Euler about Co reads::

    f   = m (a - g_C) + alpha x h + omega x (omega x h)
    tau = I_Co alpha + omega x (I_Co omega) + h x (a - g_C)

with ``[alpha; a] = J vdot + A_bias`` the spatial acceleration of Co (Drake's
``kV`` Jacobian J and bias of the point Co of C, in W, expressed in C),
``omega = J_w v`` and gravity ``g_C`` in C. Along a path ``q(s)`` with
``u = s''``, ``x = s'^2``: ``vdot = q' u + q'' x``, ``A_bias(q, q' s') =
A_bias(q, q') x`` and ``omega = omega1 sqrt(x)`` with ``omega1 = J_w q'``, so
the wrench on the object is ``w = (Y_a u + Y_b x + Y_c) pi`` with, at each
grid point (each (6, 10), rows ``[tau; f]``, columns ``[m | h | I_Co]``)::

    Y_a = [[0, -[a_u]x,               L(alpha_u)],
           [a_u, [alpha_u]x,           0]]
    Y_b = [[0, -[a_x]x,               L(alpha_x) + [omega1]x L(omega1)],
           [a_x, [alpha_x]x + [omega1]x^2, 0]]
    Y_c = [[0, [g_C]x, 0],
           [-g_C, 0,   0]]

(``[v]x`` the cross-product matrix, ``L(v)`` the 3x6 map of the entries of
I to ``I v``; ``A_u = J q'``, ``A_x = J q'' + A_bias(q, q')``). One Jacobian
and bias per grid point for every object: the wrench coefficients of any
set of parameter vectors are products with Y.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from pydrake.multibody.plant import MultibodyPlant
from pydrake.systems.framework import Context

from rt_drake.dynamics.cup_frame import CupFrame
from rt_drake.dynamics.wrench import (
    PathKinematics,
    path_kinematics,
)


class WrenchRegressor(NamedTuple):
    """``w = (a u + b x + c) pi`` at G grid points: each (G, 6, 10)."""

    a: np.ndarray
    b: np.ndarray
    c: np.ndarray

    def coefficients(self, parameters: np.ndarray) -> tuple[np.ndarray, ...]:
        """a, b, c wrench coefficients of parameter vectors.

        Args:
            parameters: (10,) one vector, or (P, 10) several.

        Returns:
            Each (G, 6) for one vector, (G, P, 6) for several.
        """
        pi = np.asarray(parameters, dtype=float)
        if pi.ndim == 1:
            return tuple(Y @ pi for Y in self)
        return tuple(np.ascontiguousarray(np.swapaxes(Y @ pi.T, 1, 2)) for Y in self)


def path_wrench_regressor(
    plant: MultibodyPlant,
    q: np.ndarray,
    dq: np.ndarray,
    ddq: np.ndarray,
    context: Context | None = None,
    cup: CupFrame | None = None,
    dynamics: bool = False,
) -> tuple[WrenchRegressor, PathKinematics]:
    """Return Y_a, Y_b, Y_c (module docstring) and Drake's kinematics of Co.

    Args:
        plant: Finalized plant whose positions are the path's joints.
        q: (G, n) the path at the grid points, rad.
        dq: (G, n) q'(s), rad per unit s.
        ddq: (G, n) q''(s), rad per unit s^2.
        context: Scratch context of ``plant``.
        cup: The cup frame C (default ``suction_cup``).
        dynamics: Also evaluate the arm's mass matrix, bias and gravity
            torques (for the joint torques, :func:`torque_regressor`).
    """
    q, dq, ddq = (np.atleast_2d(np.asarray(v, dtype=float)) for v in (q, dq, ddq))
    kin = path_kinematics(plant, np.zeros(3), q, dq, ddq, context, cup, dynamics)
    A = np.matmul(kin.J, np.stack([dq, ddq], axis=2))  # (G, 6, 2)
    A_u, A_x = A[:, :, 0], A[:, :, 1] + kin.bias
    alpha_u, a_u = A_u[:, :3], A_u[:, 3:]
    alpha_x, a_x = A_x[:, :3], A_x[:, 3:]
    omega1 = alpha_u
    count = len(q)
    Y_a, Y_b, Y_c = (np.zeros((count, 6, 10)) for _ in range(3))
    Y_a[:, 3:, 0] = a_u
    Y_a[:, :3, 1:4] = -_skew(a_u)
    Y_a[:, 3:, 1:4] = _skew(alpha_u)
    Y_a[:, :3, 4:] = _inertia_action(alpha_u)
    spin = _skew(omega1)
    Y_b[:, 3:, 0] = a_x
    Y_b[:, :3, 1:4] = -_skew(a_x)
    Y_b[:, 3:, 1:4] = _skew(alpha_x) + spin @ spin
    Y_b[:, :3, 4:] = _inertia_action(alpha_x) + spin @ _inertia_action(omega1)
    Y_c[:, 3:, 0] = -kin.g_C
    Y_c[:, :3, 1:4] = _skew(kin.g_C)
    return WrenchRegressor(Y_a, Y_b, Y_c), kin


def torque_regressor(
    kin: PathKinematics, dq: np.ndarray, ddq: np.ndarray, Y: WrenchRegressor
) -> tuple[tuple[np.ndarray, ...], WrenchRegressor]:
    """Joint torques ``tau = arm + J_Coᵀ w``: the arm's a, b, c and J_Coᵀ Y.

    Args:
        kin: Kinematics of Co with the arm's dynamics
            (``path_wrench_regressor(..., dynamics=True)``).
        dq: (G, n) q'(s).
        ddq: (G, n) q''(s).
        Y: The wrench regressor.

    Returns:
        The arm's own torque coefficients a, b, c (each (G, n): ``M q'``,
        ``M q'' + C(q, q') q'``, ``-tau_g``) and the torques per unit of
        each parameter (each (G, n, 10)).
    """
    assert kin.M is not None and kin.Cv is not None and kin.tau_g is not None
    arm = (
        np.matmul(kin.M, dq[..., None])[..., 0],
        np.matmul(kin.M, ddq[..., None])[..., 0] + kin.Cv,
        -kin.tau_g,
    )
    J_T = np.swapaxes(kin.J, 1, 2)  # (G, n, 6), Jacobian of Co
    return arm, WrenchRegressor(*(J_T @ y for y in Y))


def _skew(v: np.ndarray) -> np.ndarray:
    """(G, 3, 3) cross-product matrices of (G, 3) vectors."""
    out = np.zeros((*v.shape[:-1], 3, 3))
    out[..., 0, 1], out[..., 0, 2] = -v[..., 2], v[..., 1]
    out[..., 1, 0], out[..., 1, 2] = v[..., 2], -v[..., 0]
    out[..., 2, 0], out[..., 2, 1] = -v[..., 1], v[..., 0]
    return out


def _inertia_action(v: np.ndarray) -> np.ndarray:
    """(G, 3, 6) ``L(v)``: ``I v = L(v) [I_xx, I_yy, I_zz, I_xy, I_xz, I_yz]``."""
    x, y, z = v[..., 0], v[..., 1], v[..., 2]
    out = np.zeros((*v.shape[:-1], 3, 6))
    out[..., 0, 0], out[..., 0, 3], out[..., 0, 4] = x, y, z
    out[..., 1, 1], out[..., 1, 3], out[..., 1, 5] = y, x, z
    out[..., 2, 2], out[..., 2, 4], out[..., 2, 5] = z, x, y
    return out


__all__ = ["WrenchRegressor", "path_wrench_regressor", "torque_regressor"]
