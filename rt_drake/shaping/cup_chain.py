"""Batched kinematics of the cup along many paths at once (numba kernels).

The optimiser scores hundreds of candidate paths per MOVE; Drake's Jacobian
and bias queries cost about 20 us per configuration from Python, so the
search evaluates the same quantities batched over every candidate and grid
point: :class:`CupChain` is the retimer's :class:`rt_drake.dynamics.chain.SerialChain`
(forward kinematics, path accelerations and the object wrench's
coefficients; its docstring has the maths) with the cup pose, its tilt, the
Jacobian and Newton's method for poses added. The final path is retimed by
:func:`rt_drake.retime`; the tests compare both with Drake.
"""

from __future__ import annotations

import numpy as np
from pydrake.multibody.plant import MultibodyPlant

from rt_drake.dynamics.chain import (
    ChainError,
    SerialChain,
    cross,
    kernel_array,
)
from rt_drake.dynamics.cup_frame import CupFrame
from rt_drake.shaping._pose_kernels import solve_poses

#: The plant's chain to the cup is not a serial chain of revolute joints.
KinematicsError = ChainError


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


class CupChain(SerialChain):
    """Batched forward kinematics of the cup frame C and its path derivatives.

    Args:
        plant: Finalized plant whose positions are exactly the chain's
            revolute joints (the retimer's arm plant or the planner's).
        cup: The cup frame C (:class:`rt_drake.CupFrame`).

    Raises:
        KinematicsError: the plant is not that chain alone.
    """

    def __init__(self, plant: MultibodyPlant, cup: CupFrame) -> None:
        super().__init__(plant, cup.frame)
        self._order = self.order.astype(np.int64)

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
        J_v = cross(z, p_WC[..., None, :] - o)
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
        q = kernel_array(
            np.broadcast_to(q_seed, (*shape, self.num_joints)).reshape(
                -1, self.num_joints
            )
        ).copy()
        error = np.empty(len(q))
        solve_poses(
            q,
            kernel_array(np.broadcast_to(R_WC, (*shape, 3, 3)).reshape(-1, 3, 3)),
            kernel_array(np.reshape(p_WC, (-1, 3))),
            *self._tables[:4],
            self._tables[4],
            self._order,
            int(iterations),
            float(tolerance),
            error,
        )
        return q.reshape(*shape, self.num_joints), error.reshape(shape)


__all__ = ["CupChain", "KinematicsError"]
