"""Batched kinematics of the cup along a path, for a serial revolute chain.

Drake's Jacobian and bias queries cost about 20 us per configuration from
Python (:func:`rt_drake.dynamics.wrench.path_kinematics`); when the plant's
positions are exactly the joints from the world to the cup, the same
quantities come from a few compiled loops over all grid points at once
(:mod:`rt_drake.dynamics.chain_kernels`). The retimer samples the object wrench this
way (:mod:`rt_drake.retiming._samples`) and the MOVE optimiser scores its
candidate paths (:mod:`rt_drake.shaping.cup_chain`);
:func:`rt_drake.retiming.check_trajectory` keeps Drake's own route.

Chain: the revolute (and weld) joints from the world to the body of the cup
frame C, parents first. For joint j with fixed frames F (on the parent P)
and M (on the child B)::

    X_PB(q_j) = X_PF RotAxis_k(q_j) X_MB

so the axis ``z_j`` (unit, in W) and the origin ``o_j`` (m, in W) of joint
j are those of F. Along a joint path q(s) with ``q' = dq/ds`` and ``q'' =
d2q/ds2`` (per unit s), the angular velocity, the velocity of a point S
fixed in C and their s-derivatives are (all in W)::

    w    = sum_j z_j q'_j          w_j- = sum_{i<j} z_i q'_i   (body before j)
    v    = sum_j z_j x r_j q'_j    r_j = p_S - o_j
    al   = sum_j z_j q''_j + z'_j q'_j                 z'_j = w_j- x z_j
    a    = sum_j z_j x r_j q''_j + (z'_j x r_j + z_j x (v - o'_j)) q'_j
    o'_j = w_j- x o_j - sum_{i<j} q'_i z_i x o_i      (velocity of o_j)

``[al; a] = J q'' + Jdot q'`` is the spatial acceleration of S per unit x
= s'^2 (the Drake ``J q'' + bias`` of :mod:`rt_drake.dynamics.wrench`), ``[w; v] =
J q'`` the one per unit u = s''. The held object's wrench on it (Newton-Euler
about its centre of mass Scm, ``p = p_CoScm_C``, ``I = I_Scm_C``, all in C)::

    w_obj = a_w u + b_w x + c_w
    a_w = [I w_C + m p x v_C;  m v_C]
    b_w = [I al_C + w_C x (I w_C) + m p x a_C;  m a_C]
    c_w = [-m p x g_C;  -m g_C]

with ``(.)_C = R_WC^T (.)`` and ``g_C = R_WC^T g_W``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import BodyIndex, Frame, RevoluteJoint, WeldJoint

from rt_drake.dynamics.chain_kernels import (
    accelerations,
    frames,
    wrench_terms,
)
from rt_drake.errors import InputError

if TYPE_CHECKING:
    from rt_drake.types.held_object import HeldObject


class ChainError(InputError):
    """The plant's chain to the cup is not a serial chain of revolute joints."""


def chain_tables(
    plant: MultibodyPlant, body: BodyIndex
) -> tuple[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray], int]:
    """The joint steps from the world to ``body``, as :func:`frames` takes them.

    Step j is ``X_PF_j RotAxis(q[index_j]) X_MB_j`` (``pre``, the rotation,
    ``post``) for a revolute joint, and one fixed ``pre`` (``index_j = -1``)
    for a weld; ``axis_j`` is the revolute axis in F (unit).

    Returns:
        ``((pre (S, 4, 4), post (S, 4, 4), index (S,), axis (S, 3)), revolute
        joints on the way)``.

    Raises:
        ChainError: a body on the way has no inboard joint, or a joint is
            neither revolute nor weld.
    """
    inboard = {
        plant.get_joint(j).child_body().index(): plant.get_joint(j)
        for j in plant.GetJointIndices()
    }
    joints = []
    current = plant.get_body(body)
    while current.index() != plant.world_body().index():
        joint = inboard.get(current.index())
        if joint is None:
            raise ChainError(f"body {current.name()} has no inboard joint")
        joints.append(joint)
        current = joint.parent_body()
    joints.reverse()
    steps: list[tuple[np.ndarray, np.ndarray | None, int, Any]] = []
    for joint in joints:
        X_PF = joint.frame_on_parent().GetFixedPoseInBodyFrame().GetAsMatrix4()
        X_MB = joint.frame_on_child().GetFixedPoseInBodyFrame().inverse()
        X_MB = X_MB.GetAsMatrix4()
        if isinstance(joint, RevoluteJoint):
            k = np.asarray(joint.revolute_axis(), float)
            k /= np.linalg.norm(k)
            steps.append((X_PF, X_MB, joint.position_start(), k))
        elif isinstance(joint, WeldJoint):
            X = X_PF @ joint.X_FM().GetAsMatrix4() @ X_MB
            steps.append((X, None, -1, None))
        else:
            raise ChainError(
                f"joint {joint.name()}: only revolute and weld joints supported"
            )
    tables = (
        kernel_array(np.array([X for X, _, _, _ in steps]).reshape(-1, 4, 4)),
        kernel_array(
            np.array([np.eye(4) if Y is None else Y for _, Y, _, _ in steps]).reshape(
                -1, 4, 4
            )
        ),
        np.array([i for _, _, i, _ in steps], dtype=np.int64),
        kernel_array(
            np.array([np.zeros(3) if k is None else k for _, _, _, k in steps]).reshape(
                -1, 3
            )
        ),
    )
    return tables, sum(1 for _, _, i, _ in steps if i >= 0)


class SerialChain:
    """Batched forward kinematics of a frame C and its path derivatives.

    Args:
        plant: Finalized plant whose positions are exactly the revolute
            joints from the world to C's body (welds between them allowed).
        frame: The frame C (the cup frame).

    Raises:
        ChainError: a joint on the way to C is neither revolute nor weld, or
            the plant has positions outside the chain.
    """

    def __init__(self, plant: MultibodyPlant, frame: Frame) -> None:
        steps, revolute = chain_tables(plant, frame.body().index())
        if revolute != plant.num_positions() or revolute != plant.num_velocities():
            raise ChainError(
                f"{plant.num_positions()=} but the cup's chain has {revolute} "
                "revolute joints: the plant must hold only the arm"
            )
        self.num_joints = revolute
        #: Position index of the chain's k-th revolute joint.
        index = steps[2]
        self.order = index[index >= 0]
        X_BC = frame.GetFixedPoseInBodyFrame().GetAsMatrix4()
        self._tables = (*steps, kernel_array(X_BC))
        #: Gravity of the plant when the chain was built (m/s^2, in W).
        self.gravity_W = np.asarray(plant.gravity_field().gravity_vector(), float)

    @classmethod
    def of(cls, plant: MultibodyPlant, frame: Frame) -> SerialChain | None:
        """The chain to ``frame``, or None if ``plant`` is not that chain alone."""
        try:
            return cls(plant, frame)
        except ChainError:
            return None

    def frames(
        self, q: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Joint axes and origins and the pose of C at configurations q.

        Args:
            q: (..., n) joint angles (rad).

        Returns:
            ``(z, o, R_WC, p_WC)``: axes z_j (..., n, 3), origins o_j (m,
            (..., n, 3)), all in W; R_WC (..., 3, 3) and p_WC (m, (..., 3)).
        """
        q = np.asarray(q, float)
        flat = kernel_array(q.reshape(-1, q.shape[-1]))
        count, n = flat.shape
        z, o = np.empty((count, n, 3)), np.empty((count, n, 3))
        R, p = np.empty((count, 3, 3)), np.empty((count, 3))
        frames(flat, *self._tables, z, o, R, p)
        shape = q.shape[:-1]
        return (
            z.reshape(*shape, n, 3),
            o.reshape(*shape, n, 3),
            R.reshape(*shape, 3, 3),
            p.reshape(*shape, 3),
        )

    def path_accelerations(
        self, q: np.ndarray, dq: np.ndarray, ddq: np.ndarray, p_CoS_C: np.ndarray
    ) -> tuple[np.ndarray, ...]:
        """Velocity and acceleration terms of a point S fixed in C, per unit s.

        Args:
            q: (..., n) the path's configurations q(s) (rad).
            dq: (..., n) q'(s) (rad per unit s).
            ddq: (..., n) q''(s) (rad per unit s^2).
            p_CoS_C: (3,) the point S from Co, in C (m).

        Returns:
            ``(R_WC, w, v, al, a)``: the rotation of C and, in W, ``[w; v] =
            J q'`` and ``[al; a] = J q'' + Jdot q'`` of S (module docstring).
        """
        q = np.asarray(q, float)
        shape = q.shape[:-1]
        R, out = self._motion(q, dq, ddq, p_CoS_C)
        return (R.reshape(*shape, 3, 3), *(x.reshape(*shape, 3) for x in out))

    def _motion(
        self, q: np.ndarray, dq: np.ndarray, ddq: np.ndarray, p_CoS_C: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray]:
        """R_WC (count, 3, 3) and ``(w, v, al, a)`` (4, count, 3), q flattened."""
        n = q.shape[-1]
        flat = [
            kernel_array(np.broadcast_to(x, q.shape).reshape(-1, n))
            for x in (q, dq, ddq)
        ]
        count = flat[0].shape[0]
        z, o = np.empty((count, n, 3)), np.empty((count, n, 3))
        R, p = np.empty((count, 3, 3)), np.empty((count, 3))
        out = np.empty((4, count, 3))
        frames(flat[0], *self._tables, z, o, R, p)
        accelerations(
            z,
            o,
            R,
            p,
            kernel_array(flat[1][:, self.order]),
            kernel_array(flat[2][:, self.order]),
            kernel_array(p_CoS_C),
            out,
        )
        return R, out

    def wrench_coefficients(
        self,
        held: HeldObject,
        q: np.ndarray,
        dq: np.ndarray,
        ddq: np.ndarray,
        gravity_W: np.ndarray | None = None,
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(a_w, b_w, c_w)``, each (..., 6): the object wrench ``a u + b x + c``.

        The wrench the cup exerts on ``held`` about Co, in C (N m, N), as
        :func:`rt_drake.dynamics.wrench.path_wrench_coefficients` (module docstring),
        under gravity ``gravity_W`` (m/s^2, in W; default: the plant's when
        the chain was built).
        """
        g_W = self.gravity_W if gravity_W is None else gravity_W
        q = np.asarray(q, float)
        shape = q.shape[:-1]
        R_WC, motion = self._motion(q, dq, ddq, held.p_CoScm_C)
        count = len(R_WC)
        a_w, b_w, c_w = (np.empty((count, 6)) for _ in range(3))
        wrench_terms(
            R_WC,
            motion,
            held.mass,
            kernel_array(held.p_CoScm_C),
            kernel_array(held.I_Scm_C),
            kernel_array(g_W),
            a_w,
            b_w,
            c_w,
        )
        return a_w.reshape(*shape, 6), b_w.reshape(*shape, 6), c_w.reshape(*shape, 6)


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Cross product over the last axis (broadcast), faster than ``np.cross``."""
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    return np.stack([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0], -1)


def kernel_array(x: np.ndarray) -> np.ndarray:
    """``x`` as a writeable C-ordered float64 array (a copy only if it is not).

    numba compiles one specialisation per array layout and writeability; the
    kernels are compiled ahead of time (:func:`rt_drake.retiming.warm_up`,
    :func:`rt_drake.shaping.warm_up`) for C-ordered writeable arrays
    only, so every call passes those, else a timed retime or MOVE would pay a
    compilation (seconds).
    """
    return np.require(x, float, ("C", "W"))


__all__ = ["ChainError", "SerialChain", "cross", "kernel_array"]
