"""Forward kinematics of the robot's bodies over many configurations at once.

The dense check needs the pose of every robot body at thousands of spline
samples; Drake's ``CalcRelativeTransform`` costs microseconds per call from
Python. Each body's pose is the serial chain from the world to it, computed
by the one forward-kinematics kernel of rt_drake
(:func:`rt_drake.dynamics.chain_kernels.frames`, numba), the one the retimer
uses for the cup. Supported joints: revolute and weld. For each body B with
the joints j on its way from the world (frames F_j on the parent, M_j on the
child)::

    X_WB(q) = prod_j X_PF_j RotAxis(q_j) X_MB_j       (RotAxis = I for a weld)

Poses come back samples-last, (B, 3, 3, N) and (B, 3, N), in W (m).
"""

from __future__ import annotations

import numpy as np
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import BodyIndex

from rt_drake.dynamics.chain import ChainError, chain_tables, kernel_array
from rt_drake.dynamics.chain_kernels import frames
from rt_drake.errors import ScenarioError


class BodyKinematics:
    """Forward kinematics of ``bodies``: each body's serial chain from the world."""

    def __init__(self, plant: MultibodyPlant, bodies: list[BodyIndex]) -> None:
        self._chains = []
        for body in bodies:
            try:
                tables, revolute = chain_tables(plant, body)
            except ChainError as error:
                raise ScenarioError(str(error)) from None
            self._chains.append((tables, revolute))
        self._num_bodies = len(bodies)

    def poses(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Poses of every body at every row of q (N, n), samples last.

        Returns:
            ``(R, p)``: R[b, :, :, k] is R_WB of body b at sample k, (B, 3, 3,
            N); p[b, :, k] is p_WBo (m), (B, 3, N).
        """
        q = kernel_array(np.atleast_2d(q))
        n = q.shape[0]
        R = np.empty((self._num_bodies, 3, 3, n))
        p = np.empty((self._num_bodies, 3, n))
        R_b, p_b = np.empty((n, 3, 3)), np.empty((n, 3))
        for column, (tables, revolute) in enumerate(self._chains):
            z, o = np.empty((n, revolute, 3)), np.empty((n, revolute, 3))
            frames(q, *tables, _IDENTITY, z, o, R_b, p_b)
            R[column] = R_b.transpose(1, 2, 0)
            p[column] = p_b.T
        return R, p


#: The body frame itself (X_BC = I): the kernel's last step.
_IDENTITY = np.eye(4)


def step_motion(R: np.ndarray, p: np.ndarray, radius: np.ndarray) -> np.ndarray:
    """Bound on how far any point of each body moves between consecutive samples.

    ``|p_{k+1} - p_k| + theta_k rho_b`` with theta_k the rotation angle of
    ``R_k^T R_{k+1}`` and rho_b the body's bounding radius about its origin.

    Args:
        R: body rotations R_WB, (B, 3, 3, N), from :meth:`BodyKinematics.poses`.
        p: body origins p_WBo (m), (B, 3, N).
        radius: (B,) bounding radii rho_b (m).

    Returns:
        (N - 1, B) motion bounds (m).
    """
    dp = np.sqrt((np.diff(p, axis=2) ** 2).sum(axis=1))  # (B, N - 1)
    trace = (R[..., :-1] * R[..., 1:]).sum(axis=(1, 2))
    theta = np.arccos(np.clip(0.5 * (trace - 1.0), -1.0, 1.0))
    return (dp + theta * radius[:, None]).T


__all__ = ["BodyKinematics", "step_motion"]
