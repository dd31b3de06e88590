"""Vectorised forward kinematics of the robot's bodies over many configurations.

The dense check needs the pose of every robot body at thousands of spline
samples; Drake's ``CalcRelativeTransform`` costs microseconds per call from
Python, numpy does all samples at once. Supported joints: revolute and weld
(a serial or tree-shaped arm welded to the world). For each body B with
inboard joint J (frames F on the parent P, M on B)::

    X_WB(q) = X_WP(q) X_PF X_FM(q_J) X_BM^-1,   X_FM = RotAxis(q_J) (revolute)

Poses come back samples-last, (B, 3, 3, N) and (B, 3, N), in W (m).
"""

from __future__ import annotations

import numpy as np
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import BodyIndex, RevoluteJoint, WeldJoint

from rt_drake.errors import ScenarioError


class BodyKinematics:
    """Forward kinematics of ``bodies`` (in an order with parents first)."""

    def __init__(self, plant: MultibodyPlant, bodies: list[BodyIndex]) -> None:
        inboard = {
            plant.get_joint(j).child_body().index(): plant.get_joint(j)
            for j in plant.GetJointIndices()
        }
        # Per body: parent column (-1: world), q index (-1: weld) and the
        # constant terms of X_PB(q) = X_PF RotAxis(q) X_MB, with
        # RotAxis = I + sin(q) K + (1 - cos(q)) K^2 (Rodrigues):
        # R_PB = A0 + sin A1 + (1 - cos) A2, p_PB = b0 + sin b1 + (1 - cos) b2.
        self._steps = []
        columns: dict[BodyIndex, int] = {}
        for column, body in enumerate(bodies):
            joint = inboard.get(body)
            name = plant.get_body(body).name()
            if joint is None:
                raise ScenarioError(f"body {name} has no inboard joint")
            parent = joint.parent_body().index()
            if parent in columns:
                parent_column = columns[parent]
            elif parent == plant.world_body().index():
                parent_column = -1
            else:
                raise ScenarioError(f"body {name}: parent not listed before it")
            X_PF = joint.frame_on_parent().GetFixedPoseInBodyFrame().GetAsMatrix4()
            X_MB = (
                joint.frame_on_child()
                .GetFixedPoseInBodyFrame()
                .inverse()
                .GetAsMatrix4()
            )
            if isinstance(joint, RevoluteJoint):
                k = np.asarray(joint.revolute_axis(), float)
                k = k / np.linalg.norm(k)
                K = np.array(
                    [[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]]
                )
                terms = [np.eye(3), K, K @ K]
                index = joint.position_start()
            elif isinstance(joint, WeldJoint):
                X_PF = X_PF @ joint.X_FM().GetAsMatrix4()
                terms = [np.eye(3), np.zeros((3, 3)), np.zeros((3, 3))]
                index = -1
            else:
                raise ScenarioError(
                    f"joint {joint.name()}: only revolute and weld joints are supported"
                )
            R_PF, p_PF, R_MB, p_MB = (
                X_PF[:3, :3],
                X_PF[:3, 3],
                X_MB[:3, :3],
                X_MB[:3, 3],
            )
            A = np.array([R_PF @ T @ R_MB for T in terms])
            b = np.array([R_PF @ T @ p_MB for T in terms])
            b[0] += p_PF
            self._steps.append((parent_column, index, A, b))
            columns[body] = column
        self._num_bodies = len(bodies)

    def poses(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Poses of every body at every row of q (N, n), samples last.

        Returns:
            ``(R, p)``: R[b, :, :, k] is R_WB of body b at sample k, (B, 3, 3,
            N); p[b, :, k] is p_WBo (m), (B, 3, N).
        """
        q = np.atleast_2d(q)
        n = q.shape[0]
        R = np.empty((self._num_bodies, 3, 3, n))
        p = np.empty((self._num_bodies, 3, n))
        for column, (parent, index, A, b) in enumerate(self._steps):
            if index < 0:
                R_PB = np.broadcast_to(A[0][:, :, None], (3, 3, n))
                p_PB = np.broadcast_to(b[0][:, None], (3, n))
            else:
                sin, vers = np.sin(q[:, index]), 1.0 - np.cos(q[:, index])
                R_PB = (
                    A[0][:, :, None] + A[1][:, :, None] * sin + A[2][:, :, None] * vers
                )
                p_PB = b[0][:, None] + b[1][:, None] * sin + b[2][:, None] * vers
            if parent < 0:
                R[column], p[column] = R_PB, p_PB
                continue
            R_WP, p_WP = R[parent], p[parent]
            R[column] = (
                R_WP[:, 0:1] * R_PB[0:1]
                + R_WP[:, 1:2] * R_PB[1:2]
                + R_WP[:, 2:3] * R_PB[2:3]
            )
            p[column] = (
                R_WP[:, 0] * p_PB[0]
                + R_WP[:, 1] * p_PB[1]
                + R_WP[:, 2] * p_PB[2]
                + p_WP
            )
        return R, p


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
