"""The natural periods of an object held by a tool of bellows cups.

The tool T is held still; each cup i (frame C_i at ``X_TCi``) hangs its lip
L_i on a bushing (:mod:`._bellows`: torque ``-K_t q`` with ``K_t =
diag(k_tilt, k_tilt, k_tor)``, force ``-K_f p`` with ``K_f = diag(k_lat,
k_lat, k_ax)``, in C_i), and the object rides on the lips as one rigid body.
For a small displacement ``d = [theta; x]`` of that body at T's origin
(rotation theta, rad, and translation x, m, both in T), cup i's bushing
deflects by

    J_i d = [R_TCi^T theta; R_TCi^T (x - [p_TCi]x theta)]

(rotation and translation in C_i), so the bushings in parallel store
``1/2 d^T K d`` with the tool's stiffness (6 x 6, in T, about T's origin)

    K = sum_i J_i^T diag(K_t, K_f) J_i.

Two cups a distance ``d_i`` off the tool's axis thus stiffen torsion about
it by ``k_lat d_i^2`` each and tilt about an axis in their face plane by
``k_ax`` times their squared distance from it. The held body (object and
lips) has the spatial inertia at T's origin

    M = [[I_To, m [p]x], [-m [p]x, m 1]],   I_To = I_cm + m [p]x^T [p]x,

``p`` its centre of mass from T's origin, in T. The modes solve
``K v = omega^2 M v``; the periods are ``2 pi / omega`` (s).
"""

from __future__ import annotations

import numpy as np
from pydrake.math import RigidTransform
from scipy.linalg import eigh

from rt_drake.errors import InputError
from rt_drake.model.cup_physics import BellowsCup
from rt_drake.types.held_object import HeldObject


def _skew(p: np.ndarray) -> np.ndarray:
    """``[p]x``: ``[p]x v = p x v``."""
    return np.array([[0.0, -p[2], p[1]], [p[2], 0.0, -p[0]], [-p[1], p[0], 0.0]])


def tool_stiffness(cup: BellowsCup, X_TCs: list[RigidTransform]) -> np.ndarray:
    """``K`` (6, 6, in T about T's origin, ``[theta; x]``; N m/rad, N/m).

    The sum over the cups of ``J_i^T diag(K_t, K_f) J_i`` (module docstring).
    """
    if not X_TCs:
        raise InputError("tool_stiffness: X_TCs must hold at least one cup pose")
    K_local = np.diag(
        [
            cup.tilt_stiffness,
            cup.tilt_stiffness,
            cup.torsion_stiffness,
            cup.lateral_stiffness,
            cup.lateral_stiffness,
            cup.axial_stiffness,
        ]
    )
    K = np.zeros((6, 6))
    for X_TC in X_TCs:
        R = X_TC.rotation().matrix()
        J = np.zeros((6, 6))
        J[:3, :3] = R.T
        J[3:, :3] = -R.T @ _skew(X_TC.translation())
        J[3:, 3:] = R.T
        K += J.T @ K_local @ J
    return K


def held_inertia(
    held: HeldObject, cup: BellowsCup, X_TCs: list[RigidTransform]
) -> np.ndarray:
    """``M`` (6, 6, in T about T's origin, ``[theta; x]``; kg m^2, kg).

    The object (``held``, its inertia in the tool frame T) and the lips: a
    mass ``lip_mass`` at each cup origin with moment of inertia
    ``lip_inertia`` about each axis.
    """
    bodies = [(held.mass, np.asarray(held.p_CoScm_C), np.asarray(held.I_Scm_C))]
    bodies += [
        (cup.lip_mass, X_TC.translation(), cup.lip_inertia * np.eye(3))
        for X_TC in X_TCs
    ]
    M = np.zeros((6, 6))
    for mass, p, I_cm in bodies:
        S = _skew(p)
        M[:3, :3] += I_cm + mass * S.T @ S
        M[:3, 3:] += mass * S
        M[3:, :3] -= mass * S
        M[3:, 3:] += mass * np.eye(3)
    return M


def mode_periods(K: np.ndarray, M: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The periods (s, longest first) and mode shapes (columns) of ``K v = w^2 M v``."""
    omega2, modes = eigh(K, M)
    if omega2[0] <= 0.0:
        raise InputError(f"mode_periods: K is not positive definite ({omega2[0]=})")
    order = np.argsort(omega2)
    return 2.0 * np.pi / np.sqrt(omega2[order]), modes[:, order]


__all__ = ["held_inertia", "mode_periods", "tool_stiffness"]
