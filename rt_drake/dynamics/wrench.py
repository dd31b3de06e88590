"""The wrench a suction cup must exert on a held object, from a Drake plant.

Frames and symbols (monogram notation):

- W: world frame (plant gravity ``g_W``, e.g. (0, 0, -9.81) m/s^2).
- C: the cup frame (:class:`rt_drake.dynamics.cup_frame.CupFrame`; by default the
  frame ``suction_cup``), origin Co at the centre of the contact face, +z out
  of the cup into the object.
- S: the held object, rigidly attached to C; Scm its centre of mass at
  ``p_CoScm_C`` (m), ``I_Scm_C`` its rotational inertia about Scm expressed in
  C (kg m^2), ``m`` its mass (kg).
- A wrench is ``w = [torque; force]`` (N m, N), the wrench the cup exerts ON
  THE OBJECT, about Co, expressed in C (the frame of ``F w <= g`` in
  :mod:`rt_drake.contact`).

Newton-Euler about Scm (paper eq. 6), with ``alpha``, ``omega`` the angular
acceleration and velocity of C in W and ``a`` the acceleration of Scm in W,
all expressed in C, and ``g_C = R_CW g_W``::

    f = m (a - g_C)
    w = [I alpha + omega x (I omega) + p x f;  f]      (p = p_CoScm_C)

Along a joint path ``q(s)`` with time scaling ``s(t)``, ``u = s''`` and
``x = s'^2``, the joint velocity is ``v = q'(s) s'`` and the acceleration
``vdot = q'(s) u + q''(s) x``. Drake's Jacobian J (``kV``, of point Scm fixed
in C, measured in W, expressed in C) and bias ``A_bias(q, v)``, which is
quadratic in v, give the spatial acceleration ``[alpha; a] = J vdot +
A_bias(q, q') x``. Hence the wrench is affine in (u, x) (paper eq. 1)::

    w = a(s) u + b(s) x + c(s)

with ``c`` the gravity term ``[p x (-m g_C); -m g_C]``, ``a`` the inertial
term of ``J q'`` and ``b`` that of ``J q'' + A_bias(q, q')`` plus the
gyroscopic term ``omega1 x (I omega1)`` with ``omega1 = J_w q'``. One
Jacobian and one bias per grid point (and the cup's rotation, unless a base
joint of the cup's chain has its axis along gravity:
:func:`rt_drake.dynamics.cup_frame.vertical_base_joint`); the rest is numpy. Every
function takes the cup frame as ``cup`` (default: the plant's
``suction_cup``; build a :class:`~rt_drake.dynamics.cup_frame.CupFrame` once and pass
it when calling often).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import JacobianWrtVariable, MultibodyForces
from pydrake.systems.framework import Context

from rt_drake import arguments
from rt_drake.dynamics.cup_frame import (
    CupFrame,
    vertical_base_joint,
)
from rt_drake.errors import InputError
from rt_drake.types.held_object import HeldObject


class PathCoefficients(NamedTuple):
    """Coefficients of ``y = a u + b x + c`` at N grid points, each (N, k)."""

    a: np.ndarray
    b: np.ndarray
    c: np.ndarray


def path_wrench_coefficients(
    plant: MultibodyPlant,
    held: HeldObject,
    q: np.ndarray,
    dq: np.ndarray,
    ddq: np.ndarray,
    context: Context | None = None,
    cup: CupFrame | None = None,
) -> PathCoefficients:
    """Return a, b, c (each (N, 6)) with ``w = a u + b x + c`` on the object.

    Args:
        plant: Finalized plant whose positions are the path's joints (objects
            left out or welded).
        held: The object's inertia in C.
        q: (N, n) path q(s) at the grid points, rad.
        dq: (N, n) q'(s), rad per unit s.
        ddq: (N, n) q''(s), rad per unit s^2.
        context: Scratch context of ``plant`` (made if None).
        cup: The cup frame C (default: ``suction_cup``).
    """
    q, dq, ddq = _as_rows(q, dq, ddq)
    kin = path_kinematics(plant, held.p_CoScm_C, q, dq, ddq, context, cup)
    return _wrench_coefficients(held, kin, dq, ddq)


def path_torque_coefficients(
    plant: MultibodyPlant,
    q: np.ndarray,
    dq: np.ndarray,
    ddq: np.ndarray,
    held: HeldObject | None = None,
    context: Context | None = None,
    cup: CupFrame | None = None,
) -> PathCoefficients:
    """Return a, b, c (each (N, n)) with joint torques ``tau = a u + b x + c``.

    ``tau = M vdot + C(q, v) v - tau_g(q) + J_Coᵀ w`` (N m): inverse dynamics
    of the arm plus the reaction of the held object's wrench ``w`` at Co
    (``J_Co``: spatial Jacobian of Co in W, expressed in C).
    """
    q, dq, ddq = _as_rows(q, dq, ddq)
    p = np.zeros(3) if held is None else held.p_CoScm_C
    kin = path_kinematics(plant, p, q, dq, ddq, context, cup, dynamics=True)
    assert kin.M is not None and kin.Cv is not None and kin.tau_g is not None
    a = _matvec(kin.M, dq)
    b = _matvec(kin.M, ddq) + kin.Cv
    c = -kin.tau_g
    if held is not None:
        w = _wrench_coefficients(held, kin, dq, ddq)
        J_Co_T = np.swapaxes(_shift_jacobian(kin.J, -p), 1, 2)
        a = a + _matvec(J_Co_T, w.a)
        b = b + _matvec(J_Co_T, w.b)
        c = c + _matvec(J_Co_T, w.c)
    return PathCoefficients(a, b, c)


def object_wrench(
    plant: MultibodyPlant,
    held: HeldObject,
    q: np.ndarray,
    v: np.ndarray,
    vdot: np.ndarray,
    context: Context | None = None,
    cup: CupFrame | None = None,
) -> np.ndarray:
    """Return the wrenches (N, 6) the cup exerts on the object at N states.

    Evaluated at each state on its own: ``[alpha; a] = J vdot + A_bias(q, v)``
    and ``omega = J_w v`` for Scm, then Newton-Euler (module docstring).
    """
    where = "object_wrench"
    arguments.instance(plant, "plant", MultibodyPlant, where=where)
    arguments.instance(held, "held", HeldObject, where=where)
    q, v, vdot = (
        arguments.array(x, name, ("...", "n"), where=where)
        for x, name in ((q, "q"), (v, "v"), (vdot, "vdot"))
    )
    q, v, vdot = _as_rows(q, v, vdot)
    kin = path_kinematics(plant, held.p_CoScm_C, q, v, vdot, context, cup)
    alpha, acc = np.split(_matvec(kin.J, vdot) + kin.bias, 2, axis=1)
    omega = _matvec(kin.J[:, :3], v)
    f = held.mass * (acc - kin.g_C)
    torque = alpha @ held.I_Scm_C.T + _cross(omega, omega @ held.I_Scm_C.T)
    return np.hstack([torque + _cross(held.p_CoScm_C, f), f])


def joint_torques(
    plant: MultibodyPlant,
    q: np.ndarray,
    v: np.ndarray,
    vdot: np.ndarray,
    held: HeldObject | None = None,
    context: Context | None = None,
    cup: CupFrame | None = None,
) -> np.ndarray:
    """Return joint torques (N, n), N m, at N states by Drake inverse dynamics.

    ``CalcInverseDynamics`` with the force elements' forces (gravity) as
    applied forces, plus ``J_Coᵀ w`` for the held object's wrench ``w`` from
    :func:`object_wrench`.
    """
    q, v, vdot = _as_rows(q, v, vdot)
    context = context or plant.CreateDefaultContext()
    cup = cup or CupFrame.of(plant)
    w = None if held is None else object_wrench(plant, held, q, v, vdot, context, cup)
    forces = MultibodyForces(plant)
    frame, world = cup.frame, plant.world_frame()
    tau = np.empty_like(q)
    for i in range(len(q)):
        plant.SetPositionsAndVelocities(context, np.concatenate([q[i], v[i]]))
        plant.CalcForceElementsContribution(context, forces)
        tau[i] = plant.CalcInverseDynamics(context, vdot[i], forces)
        if w is not None:
            J_Co = plant.CalcJacobianSpatialVelocity(
                context, JacobianWrtVariable.kV, frame, np.zeros(3), world, frame
            )
            tau[i] += J_Co.T @ w[i]
    return tau


class PathKinematics(NamedTuple):
    """Drake's kinematics of a point of C (and optionally the arm's dynamics)."""

    J: np.ndarray  # (N, 6, n) of Scm, kV, in W, expressed in C
    bias: np.ndarray  # (N, 6) A_bias(q, dq)
    g_C: np.ndarray  # (N, 3) gravity expressed in C
    M: np.ndarray | None = None  # (N, n, n)
    Cv: np.ndarray | None = None  # (N, n) C(q, dq) dq
    tau_g: np.ndarray | None = None  # (N, n)


def path_kinematics(
    plant: MultibodyPlant,
    p_CoScm_C: np.ndarray,
    q: np.ndarray,
    dq: np.ndarray,
    ddq: np.ndarray,
    context: Context | None,
    cup: CupFrame | None,
    dynamics: bool = False,
) -> PathKinematics:
    """Evaluate Drake at each (q, dq): the only per-point Python loop.

    Returns the Jacobian and bias acceleration of the point ``p_CoScm_C`` of
    C (``kV``, in W, expressed in C), gravity in C and, with ``dynamics``,
    the arm's mass matrix, bias term and gravity torques.
    """
    n = plant.num_positions()
    if plant.num_velocities() != n or q.shape[1:] != (n,):
        raise InputError(
            f"{q.shape=} but {plant.num_positions()=} and {plant.num_velocities()=}:"
            " the plant must hold only the path's joints (objects welded or left out)"
        )
    if not (q.shape == dq.shape == ddq.shape):
        raise InputError(f"{q.shape=}, {dq.shape=}, {ddq.shape=} must be equal")
    context = context or plant.CreateDefaultContext()
    cup = cup or CupFrame.of(plant)
    frame = cup.frame
    world = plant.world_frame()
    kV = JacobianWrtVariable.kV
    p = np.asarray(p_CoScm_C, dtype=float)
    set_state = plant.SetPositionsAndVelocities
    jacobian = plant.CalcJacobianSpatialVelocity
    bias = plant.CalcBiasSpatialAcceleration
    base = vertical_base_joint(plant, cup)
    rotation = frame.CalcRotationMatrixInWorld if base is None else None
    Js, biases, rotations, Ms, Cvs, gravities = [], [], [], [], [], []
    for state in np.hstack([q, dq]):
        set_state(context, state)
        Js.append(jacobian(context, kV, frame, p, world, frame))
        biases.append(bias(context, kV, frame, p, world, frame))
        if rotation is not None:
            rotations.append(rotation(context))
        if dynamics:
            Ms.append(plant.CalcMassMatrix(context))
            Cvs.append(plant.CalcBiasTerm(context))
            gravities.append(plant.CalcGravityGeneralizedForces(context))
    J = np.array(Js)
    A_bias = np.array([A.get_coeffs() for A in biases])
    M, Cv, tau_g = (np.array(x) if dynamics else None for x in (Ms, Cvs, gravities))
    if base is None:
        R_WC = np.array([R.matrix() for R in rotations])
        g_C = np.einsum("nji,j->ni", R_WC, plant.gravity_field().gravity_vector())
    else:
        index, g_along_axis = base
        g_C = g_along_axis * J[:, :3, index]
    return PathKinematics(J, A_bias, g_C, M, Cv, tau_g)


def _wrench_coefficients(
    held: HeldObject, kin: PathKinematics, dq: np.ndarray, ddq: np.ndarray
) -> PathCoefficients:
    """Newton-Euler (module docstring) split into its u, x and constant terms.

    Linear in the acceleration ``A = [alpha; a]`` of Scm: ``w = L A`` with
    ``L = [[I, m [p]x], [0, m 1]]``, plus the gyroscopic torque in b and the
    gravity wrench ``c = -m [[p]x; 1] g_C``.
    """
    m, p, inertia = held.mass, held.p_CoScm_C, held.I_Scm_C
    p_cross = np.array([[0.0, -p[2], p[1]], [p[2], 0.0, -p[0]], [-p[1], p[0], 0.0]])
    L = np.zeros((6, 6))
    L[:3, :3], L[:3, 3:], L[3:, 3:] = inertia, m * p_cross, m * np.eye(3)
    A = np.matmul(kin.J, np.stack([dq, ddq], axis=2))  # (N, 6, 2)
    A_u = A[:, :, 0]  # [alpha; a] per unit u
    A_x = A[:, :, 1] + kin.bias  # [alpha; a] per unit x
    omega1 = A_u[:, :3]  # omega = omega1 sqrt(x)
    b = A_x @ L.T
    b[:, :3] += _cross(omega1, omega1 @ inertia.T)
    return PathCoefficients(
        a=A_u @ L.T, b=b, c=kin.g_C @ (-m * np.vstack([p_cross, np.eye(3)])).T
    )


def _as_rows(*arrays: np.ndarray) -> tuple[np.ndarray, ...]:
    """Return float arrays of shape (N, n) (a single point becomes N = 1)."""
    return tuple(np.atleast_2d(np.asarray(x, dtype=float)) for x in arrays)


def _matvec(A: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Batched ``A[i] @ x[i]``."""
    return np.matmul(A, x[..., None])[..., 0]


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row-wise cross product of (..., 3) arrays (faster than np.cross)."""
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    out = np.empty(np.broadcast_shapes(a.shape, b.shape), np.result_type(a, b))
    out[..., 0] = a1 * b2 - a2 * b1
    out[..., 1] = a2 * b0 - a0 * b2
    out[..., 2] = a0 * b1 - a1 * b0
    return out


def _shift_jacobian(J: np.ndarray, p_ScmCo_C: np.ndarray) -> np.ndarray:
    """Jacobian of the point at ``p_ScmCo_C`` from Scm (same body, same frame).

    ``v_Co = v_Scm + omega x p_ScmCo`` so ``J_v += -[p]x J_w``.
    """
    shifted = J.copy()
    shifted[:, 3:] += np.swapaxes(_cross(np.swapaxes(J[:, :3], 1, 2), p_ScmCo_C), 1, 2)
    return shifted


__all__ = [
    "PathCoefficients",
    "PathKinematics",
    "joint_torques",
    "object_wrench",
    "path_kinematics",
    "path_torque_coefficients",
    "path_wrench_coefficients",
]
