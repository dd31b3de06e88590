"""The held object's wrench by another route: body accelerations + Newton-Euler.

:mod:`rt_drake.dynamics.wrench` builds the wrench from the cup frame's Jacobian and
bias acceleration (and, when it can, gravity from a base joint's Jacobian
column). This module computes the same wrench without any of that, for
checks (:func:`rt_drake.retiming.check_trajectory`) and tests: at each state
(q, v, vdot),

- Drake's ``CalcSpatialAccelerationsFromVdot`` gives the spatial
  acceleration ``A_WB = [alpha; a_WBo]`` of the cup's body B (in W),
  ``EvalBodySpatialVelocityInWorld`` its velocity ``[omega; v_WBo]`` and
  ``EvalPoseInWorld`` its pose;
- the object's centre of mass Scm is ``p_BoScm = R_WB (X_BC p_CoScm_C)``, so
  ``a_Scm = a_WBo + alpha x p_BoScm + omega x (omega x p_BoScm)``;
- Newton-Euler in W: ``f = m (a_Scm - g_W)``, ``tau_Scm = I_W alpha +
  omega x (I_W omega)`` with ``I_W = R_WC I_Scm_C R_WCᵀ``;
- the wrench on the object about Co, in C: ``f_C = R_WCᵀ f``, ``tau_C =
  R_WCᵀ tau_Scm + p_CoScm_C x f_C``.

Units: m, rad, s, kg; wrench ``[torque; force]`` in N m and N.
"""

from __future__ import annotations

import numpy as np
from pydrake.multibody.plant import MultibodyPlant
from pydrake.systems.framework import Context

from rt_drake.dynamics.cup_frame import CupFrame
from rt_drake.types.held_object import HeldObject


def reference_object_wrench(
    plant: MultibodyPlant,
    held: HeldObject,
    cup: CupFrame,
    q: np.ndarray,
    v: np.ndarray,
    vdot: np.ndarray,
    context: Context | None = None,
) -> np.ndarray:
    """The wrenches (N, 6) the cup exerts on the object at N states.

    Args:
        plant: Finalized plant (positions and velocities: q, v).
        held: The object's inertia in C.
        cup: The cup frame C.
        q: (N, n) positions, rad.
        v: (N, n) velocities, rad/s.
        vdot: (N, n) accelerations, rad/s^2.
        context: Scratch context of ``plant``.
    """
    q, v, vdot = (np.atleast_2d(np.asarray(a, dtype=float)) for a in (q, v, vdot))
    context = context or plant.CreateDefaultContext()
    body = cup.frame.body()
    X_BC = cup.frame.GetFixedPoseInBodyFrame()
    p_BoScm_B = X_BC.multiply(held.p_CoScm_C)
    R_BC = X_BC.rotation().matrix()
    g_W = plant.gravity_field().gravity_vector()
    wrenches = np.empty((len(q), 6))
    for i in range(len(q)):
        plant.SetPositionsAndVelocities(context, np.concatenate([q[i], v[i]]))
        A_WB = plant.CalcSpatialAccelerationsFromVdot(context, vdot[i])[body.index()]
        V_WB = plant.EvalBodySpatialVelocityInWorld(context, body)
        R_WB = body.EvalPoseInWorld(context).rotation().matrix()
        alpha, a_Bo = A_WB.rotational(), A_WB.translational()
        omega = V_WB.rotational()
        p = R_WB @ p_BoScm_B
        a_Scm = a_Bo + np.cross(alpha, p) + np.cross(omega, np.cross(omega, p))
        R_WC = R_WB @ R_BC
        I_W = R_WC @ held.I_Scm_C @ R_WC.T
        f_W = held.mass * (a_Scm - g_W)
        tau_W = I_W @ alpha + np.cross(omega, I_W @ omega)
        f_C = R_WC.T @ f_W
        wrenches[i, :3] = R_WC.T @ tau_W + np.cross(held.p_CoScm_C, f_C)
        wrenches[i, 3:] = f_C
    return wrenches


def reference_object_wrenches(
    plant: MultibodyPlant,
    objects: list[HeldObject],
    cup: CupFrame,
    q: np.ndarray,
    v: np.ndarray,
    vdot: np.ndarray,
    context: Context | None = None,
) -> np.ndarray:
    """The wrenches (K, N, 6) on each of K objects at N states.

    The same route as :func:`reference_object_wrench` (Drake's body
    accelerations, then Newton-Euler in W), the cup body's motion evaluated
    once per state for all the objects.
    """
    q, v, vdot = (np.atleast_2d(np.asarray(a, dtype=float)) for a in (q, v, vdot))
    context = context or plant.CreateDefaultContext()
    body = cup.frame.body()
    X_BC = cup.frame.GetFixedPoseInBodyFrame()
    R_BC = X_BC.rotation().matrix()
    count = len(q)
    R_WB = np.empty((count, 3, 3))
    alpha = np.empty((count, 3))
    omega = np.empty((count, 3))
    a_Bo = np.empty((count, 3))
    for i in range(count):
        plant.SetPositionsAndVelocities(context, np.concatenate([q[i], v[i]]))
        A_WB = plant.CalcSpatialAccelerationsFromVdot(context, vdot[i])[body.index()]
        V_WB = plant.EvalBodySpatialVelocityInWorld(context, body)
        R_WB[i] = body.EvalPoseInWorld(context).rotation().matrix()
        alpha[i], a_Bo[i] = A_WB.rotational(), A_WB.translational()
        omega[i] = V_WB.rotational()
    g_W = plant.gravity_field().gravity_vector()
    R_WC = R_WB @ R_BC
    out = np.empty((len(objects), count, 6))
    for k, held in enumerate(objects):
        p = R_WB @ X_BC.multiply(held.p_CoScm_C)  # (N, 3) Bo to Scm, in W
        a_Scm = a_Bo + np.cross(alpha, p) + np.cross(omega, np.cross(omega, p))
        I_W = R_WC @ held.I_Scm_C @ np.swapaxes(R_WC, 1, 2)
        f_W = held.mass * (a_Scm - g_W)
        tau_W = np.einsum("nij,nj->ni", I_W, alpha) + np.cross(
            omega, np.einsum("nij,nj->ni", I_W, omega)
        )
        f_C = np.einsum("nji,nj->ni", R_WC, f_W)
        tau_C = np.einsum("nji,nj->ni", R_WC, tau_W)
        out[k, :, :3] = tau_C + np.cross(held.p_CoScm_C, f_C)
        out[k, :, 3:] = f_C
    return out


__all__ = ["reference_object_wrench", "reference_object_wrenches"]
