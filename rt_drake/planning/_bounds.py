"""Bounds on how far the robot's points move: the planner's distance metric.

For each robot joint j and robot body b, ``R[j, b]`` (m) bounds the distance
from joint j's axis to any point of b's geometry (a carried load counts as
part of the tool body). Moving the joints by ``dq`` moves any point of b by
at most ``sum_j R[j, b] |dq_j|``. That bound weighs the checker's edge
steps and, with the vectorised kinematics, drives the clearance certificate
of :mod:`rt_drake.planning.dense_check`.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from pydrake.geometry import SceneGraph
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import Body, BodyIndex, JointIndex, ModelInstanceIndex

from rt_drake.dynamics.body_kinematics import BodyKinematics
from rt_drake.planning._geometry import bounding_radius


class MotionBounds:
    """Lever arms and bounding radii of the robot's bodies, per carried load.

    Attributes:
        joints: the robot's movable joints (rows of ``radii``).
        bodies: the robot's bodies, parents first (columns of ``radii``).
        column_lookup: per plant body index, its column, or -1.
        kinematics: vectorised forward kinematics of ``bodies``.
        body_radius: (B,) bounding radius rho_b of each body about its
            origin (m), the load included in the tool's.
        radii, outboard: ``R[j, b]`` (m) and "b moves with joint j", (J, B).
        self_pairs: robot body pairs (columns a < o) that may collide; set
            by the owner once the collision filters are known.
    """

    def __init__(
        self,
        plant: MultibodyPlant,
        scene_graph: SceneGraph,
        instances: list[ModelInstanceIndex],
        tool: BodyIndex,
    ) -> None:
        self._plant = plant
        self._scene_graph = scene_graph
        self._tool = tool
        self.joints = [
            j
            for instance in instances
            for j in plant.GetJointIndices(instance)
            if plant.get_joint(j).num_positions() > 0
        ]
        self.bodies = [
            b for instance in instances for b in plant.GetBodyIndices(instance)
        ]
        self.column_lookup = [-1] * plant.num_bodies()
        for column, body in enumerate(self.bodies):
            self.column_lookup[int(body)] = column
        self.kinematics = BodyKinematics(plant, self.bodies)
        self.self_pairs: list[tuple[int, int]] = []
        self._cache: dict[float, list] = {}
        self.set_load(0.0)

    def set_self_pairs(self, filtered: Callable[[Body, Body], bool]) -> None:
        """Keep the robot body pairs for which ``filtered(a, o)`` is False."""
        get = self._plant.get_body
        self.self_pairs = [
            (a, o)
            for a in range(len(self.bodies))
            for o in range(a + 1, len(self.bodies))
            if not filtered(get(self.bodies[a]), get(self.bodies[o]))
        ]
        self._cache = {}
        self.set_load(self._load)

    def set_load(self, radius: float) -> None:
        """A load reaching ``radius`` (m) from the tool body's origin (0: none)."""
        if radius not in self._cache:
            rho = body_radii(
                self._plant, self._scene_graph, self.bodies, {self._tool: radius}
            )
            radii, outboard = displacement_radii(
                self._plant, self.joints, self.bodies, rho
            )
            self._cache[radius] = [rho, radii, outboard, None]
        self.body_radius, self.radii, self.outboard, _ = self._cache[radius]
        self._load = radius

    def pair_levers(self) -> np.ndarray:
        """Lever arms (m/rad) of each pair in ``self_pairs``, (P, J).

        Row (a, o): the joints that move exactly one of the two bodies count,
        each with the larger of the two arms; the pair's relative motion is
        at most ``sum_j lever_j |dq_j|``.
        """
        cached = self._cache[self._load]
        if cached[3] is None:
            rows = [
                np.where(
                    self.outboard[:, a] ^ self.outboard[:, o],
                    np.maximum(self.radii[:, a], self.radii[:, o]),
                    0.0,
                )
                for a, o in self.self_pairs
            ]
            cached[3] = np.array(rows).reshape(len(rows), len(self.joints))
        return cached[3]


def body_radii(
    plant: MultibodyPlant,
    scene_graph: SceneGraph,
    bodies: list[BodyIndex],
    extra: dict[BodyIndex, float] | None = None,
) -> np.ndarray:
    """Bounding radius rho_b (m) of each body's proximity geometry about its origin.

    ``extra[b]`` (e.g. a carried load's radius about b's origin) counts if larger.
    """
    extra = extra or {}
    inspector = scene_graph.model_inspector()
    return np.array(
        [
            max(
                [0.0, extra.get(b, 0.0)]
                + [
                    float(np.linalg.norm(inspector.GetPoseInFrame(g).translation()))
                    + bounding_radius(inspector.GetShape(g))
                    for g in plant.GetCollisionGeometriesForBody(plant.get_body(b))
                ]
            )
            for b in bodies
        ]
    )


def displacement_radii(
    plant: MultibodyPlant,
    joints: list[JointIndex],
    bodies: list[BodyIndex],
    rho: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """Bound the lever arm of every joint over every robot body.

    ``R[j, b] = |p_Jj_Bo| bound + rho_b`` for b outboard of joint j, where
    the origin bound sums the joint-frame offsets along the chain from j to b
    and ``rho_b`` is b's bounding radius (:func:`body_radii`).

    Returns:
        ``(R, outboard)``: (num joints, num bodies) radii in m, and the
        boolean matrix "body b moves with joint j".
    """
    inboard_joint = {
        plant.get_joint(j).child_body().index(): plant.get_joint(j)
        for j in plant.GetJointIndices()
    }
    radii = np.zeros((len(joints), len(bodies)))
    outboard = np.zeros((len(joints), len(bodies)), dtype=bool)
    for column, b in enumerate(bodies):
        # Walk from b to the world, summing offsets between joint origins.
        origin_bound = 0.0
        body_index = b
        while body_index in inboard_joint:
            joint = inboard_joint[body_index]
            origin_bound += float(
                np.linalg.norm(
                    joint.frame_on_child().GetFixedPoseInBodyFrame().translation()
                )
            )
            if joint.index() in joints and joint.num_positions() > 0:
                row = joints.index(joint.index())
                radii[row, column] = origin_bound + rho[column]
                outboard[row, column] = True
            origin_bound += float(
                np.linalg.norm(
                    joint.frame_on_parent().GetFixedPoseInBodyFrame().translation()
                )
            )
            body_index = joint.parent_body().index()
    return radii, outboard


__all__ = ["MotionBounds", "body_radii", "displacement_radii"]
