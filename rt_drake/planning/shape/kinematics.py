"""Batched kinematics of the cup along many paths at once (numba kernels).

The optimiser scores hundreds of candidate paths per MOVE; Drake's Jacobian
and bias queries cost about 20 us per configuration from Python, so the
search evaluates the same quantities here, batched over every candidate and
grid point. The final path is retimed by :func:`rt_drake.retime`
with Drake's own kinematics; the tests compare both.

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
= s'^2 (the Drake ``J q'' + bias`` of :mod:`rt_drake.dynamics`), ``[w; v] =
J q'`` the one per unit u = s''. The held object's wrench on it (Newton-Euler
about its centre of mass Scm, ``p = p_CoScm_C``, ``I = I_Scm_C``, all in C)::

    w_obj = a_w u + b_w x + c_w
    a_w = [I w_C + m p x v_C;  m v_C]
    b_w = [I al_C + w_C x (I w_C) + m p x a_C;  m a_C]
    c_w = [-m p x g_C;  -m g_C]

with ``(.)_C = R_WC^T (.)`` and ``g_C = R_WC^T g_W``.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import RevoluteJoint, WeldJoint

from rt_drake.cup_frame import CupFrame
from rt_drake.dynamics import HeldObject
from rt_drake.errors import InputError
from rt_drake.planning.shape._fk import accelerations, frames, solve_poses


class KinematicsError(InputError):
    """The plant's chain to the cup is not a serial chain of revolute joints."""


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Cross product over the last axis (broadcast), faster than ``np.cross``."""
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    return np.stack([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0], -1)


def _rotation_vector(R: np.ndarray) -> np.ndarray:
    """Rotation vectors (..., 3) (axis times angle, rad) of rotations (..., 3, 3)."""
    cos = np.clip((np.trace(R, axis1=-2, axis2=-1) - 1.0) / 2.0, -1.0, 1.0)
    angle = np.arccos(cos)
    vee = np.stack(
        [
            R[..., 2, 1] - R[..., 1, 2],
            R[..., 0, 2] - R[..., 2, 0],
            R[..., 1, 0] - R[..., 0, 1],
        ],
        -1,
    )
    sin = np.sin(angle)
    scale = np.where(sin > 1e-9, angle / np.where(sin > 1e-9, 2.0 * sin, 1.0), 0.5)
    return vee * scale[..., None]


class CupChain:
    """Batched forward kinematics of the cup frame C and its path derivatives.

    Args:
        plant: Finalized plant whose positions are exactly the chain's
            revolute joints (the retimer's arm plant or the planner's).
        cup: The cup frame C (:class:`rt_drake.CupFrame`).
    """

    def __init__(self, plant: MultibodyPlant, cup: CupFrame) -> None:
        cup_frame = cup.frame
        body = cup_frame.body()
        inboard = {
            plant.get_joint(j).child_body().index(): plant.get_joint(j)
            for j in plant.GetJointIndices()
        }
        steps = []
        while body.index() != plant.world_body().index():
            joint = inboard.get(body.index())
            if joint is None:
                raise KinematicsError(f"body {body.name()} has no inboard joint")
            steps.append(joint)
            body = joint.parent_body()
        steps.reverse()
        self._steps: list[tuple[np.ndarray, np.ndarray | None, int, Any]] = []
        revolute = 0
        for joint in steps:
            X_PF = joint.frame_on_parent().GetFixedPoseInBodyFrame().GetAsMatrix4()
            X_MB = joint.frame_on_child().GetFixedPoseInBodyFrame().inverse()
            X_MB = X_MB.GetAsMatrix4()
            if isinstance(joint, RevoluteJoint):
                k = np.asarray(joint.revolute_axis(), float)
                k /= np.linalg.norm(k)
                self._steps.append((X_PF, X_MB, joint.position_start(), k))
                revolute += 1
            elif isinstance(joint, WeldJoint):
                X = X_PF @ joint.X_FM().GetAsMatrix4() @ X_MB
                self._steps.append((X, None, -1, None))
            else:
                raise KinematicsError(
                    f"joint {joint.name()}: only revolute and weld joints supported"
                )
        if revolute != plant.num_positions():
            raise KinematicsError(
                f"{plant.num_positions()=} but the cup's chain has {revolute} "
                "revolute joints: the plant must hold only the arm"
            )
        self.num_joints = revolute
        #: Position index of the chain's k-th revolute joint.
        self.order = np.array([i for _, _, i, _ in self._steps if i >= 0])
        self._order = self.order.astype(np.int64)
        X_BC = cup_frame.GetFixedPoseInBodyFrame().GetAsMatrix4()
        self._tables = (
            np.array([X for X, _, _, _ in self._steps]),
            np.array([np.eye(4) if Y is None else Y for _, Y, _, _ in self._steps]),
            np.array([i for _, _, i, _ in self._steps], dtype=np.int64),
            np.array([np.zeros(3) if k is None else k for _, _, _, k in self._steps]),
            _kernel_array(X_BC),
        )
        self.gravity_W = np.asarray(plant.gravity_field().gravity_vector(), float)

    def frames(
        self, q: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Joint axes and origins and the cup pose at configurations q.

        Args:
            q: (..., n) joint angles (rad).

        Returns:
            ``(z, o, R_WC, p_WC)``: axes z_j (..., n, 3), origins o_j (m,
            (..., n, 3)), all in W; R_WC (..., 3, 3) and p_WC (m, (..., 3)).
        """
        q = np.asarray(q, float)
        flat = _kernel_array(q.reshape(-1, q.shape[-1]))
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

    def cup_pose(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """R_WC (..., 3, 3) and p_WC (m, (..., 3)) at configurations q (..., n)."""
        return self.frames(q)[2:]

    def tilt(self, q: np.ndarray) -> np.ndarray:
        """Angle (rad) between the cup axis z_C and gravity: 0 = cup facing down.

        ``tilt = arccos(z_C . g_W / |g_W|)``, (...,) for q (..., n).
        """
        R_WC = self.cup_pose(q)[0]
        down = self.gravity_W / np.linalg.norm(self.gravity_W)
        return np.arccos(np.clip(R_WC[..., :, 2] @ down, -1.0, 1.0))

    def jacobian(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Spatial Jacobian of the cup origin Co in W: ``[w; v] = J qdot``.

        Returns:
            ``(J, R_WC, p_WC)``: J (..., 6, n) (rows: angular, then
            translational, in W), and the cup pose.
        """
        z, o, R_WC, p_WC = self.frames(q)
        J_v = _cross(z, p_WC[..., None, :] - o)
        J = np.concatenate([np.swapaxes(z, -1, -2), np.swapaxes(J_v, -1, -2)], -2)
        return J, R_WC, p_WC

    def solve_pose(
        self,
        R_WC: np.ndarray,
        p_WC: np.ndarray,
        q_seed: np.ndarray,
        iterations: int = 8,
        tolerance: float = 1e-10,
    ) -> tuple[np.ndarray, np.ndarray]:
        """Newton's method for q with the cup at poses (R_WC, p_WC), from seeds.

        Each step solves ``J dq = [theta_err; p_err]`` (least squares, ``dq
        = J^T (J J^T + 1e-12 I)^-1 r``) with ``theta_err`` the rotation
        vector of ``R_target R_WC(q)^T`` (rad) and ``p_err`` the position
        error (m), both in W. For targets near the seeds (a few cm, a few
        tens of degrees) it converges in 3-5 steps. One compiled loop per
        pose (:func:`._fk.solve_poses`), each stopping on its own.

        Args:
            R_WC: (..., 3, 3) target rotations.
            p_WC: (..., 3) target positions (m).
            q_seed: (..., n) initial configurations (rad).
            iterations: Most Newton steps.
            tolerance: A pose stops once its error is below it (rad + m).

        Returns:
            ``(q, error)``: configurations (..., n) and the final pose error
            ``|theta_err| + |p_err|`` (...,) (rad + m).
        """
        shape = p_WC.shape[:-1]
        q = _kernel_array(
            np.broadcast_to(q_seed, (*shape, self.num_joints)).reshape(
                -1, self.num_joints
            )
        ).copy()
        error = np.empty(len(q))
        solve_poses(
            q,
            _kernel_array(np.broadcast_to(R_WC, (*shape, 3, 3)).reshape(-1, 3, 3)),
            _kernel_array(np.reshape(p_WC, (-1, 3))),
            *self._tables[:4],
            self._tables[4],
            self._order,
            int(iterations),
            float(tolerance),
            error,
        )
        return q.reshape(*shape, self.num_joints), error.reshape(shape)

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
            ``(R_WC, w, v, al, a)``: the cup's rotation and, in W, ``[w; v] =
            J q'`` and ``[al; a] = J q'' + Jdot q'`` of S (module docstring).
        """
        q = np.asarray(q, float)
        shape, n = q.shape[:-1], q.shape[-1]
        flat = [
            _kernel_array(np.broadcast_to(x, q.shape).reshape(-1, n))
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
            _kernel_array(flat[1][:, self.order]),
            _kernel_array(flat[2][:, self.order]),
            _kernel_array(p_CoS_C),
            out,
        )
        return (R.reshape(*shape, 3, 3), *(x.reshape(*shape, 3) for x in out))

    def wrench_coefficients(
        self, held: HeldObject, q: np.ndarray, dq: np.ndarray, ddq: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(a_w, b_w, c_w)``, each (..., 6): the object wrench ``a u + b x + c``.

        The wrench the cup exerts on ``held`` about Co, in C (N m, N), as
        :func:`rt_drake.dynamics.path_wrench_coefficients` (module docstring).
        """
        m, p, inertia = held.mass, held.p_CoScm_C, held.I_Scm_C
        R_WC, w, v, al, a = self.path_accelerations(q, dq, ddq, p)
        to_C = np.swapaxes(R_WC, -1, -2)
        w_C, v_C, al_C, a_C = (to_C @ x[..., None] for x in (w, v, al, a))
        w_C, v_C, al_C, a_C = (x[..., 0] for x in (w_C, v_C, al_C, a_C))
        g_C = to_C @ self.gravity_W
        Iw = w_C @ inertia.T
        a_w = np.concatenate([Iw + m * _cross(p, v_C), m * v_C], -1)
        b_w = np.concatenate(
            [al_C @ inertia.T + _cross(w_C, Iw) + m * _cross(p, a_C), m * a_C], -1
        )
        c_w = np.concatenate([-m * _cross(p, g_C), -m * g_C], -1)
        return a_w, b_w, c_w


def _kernel_array(x: np.ndarray) -> np.ndarray:
    """``x`` as a writeable C-ordered float64 array (a copy only if it is not).

    numba compiles one specialisation per array layout and writeability; the
    kernels are compiled ahead of time (:func:`rt_drake.planning.shape.warm_up`)
    for C-ordered writeable arrays only, so every call passes those, else a
    timed MOVE would pay a compilation (seconds).
    """
    return np.require(x, float, ("C", "W"))


__all__ = ["CupChain", "KinematicsError"]
