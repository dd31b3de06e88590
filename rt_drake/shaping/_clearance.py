"""A cheap clearance estimate of the cup's body and its load, for the search.

The search scores thousands of configurations per MOVE; the collision
checker costs about 70 us each. This model is a guide, not a certificate
(the final path gets the planner's continuous check,
:func:`rt_drake.planning.dense_check.check_path`):

- the geometries on the cup's body (tool, cup, carried object) become
  spheres fixed in the cup frame C: a sphere is itself, a cylinder or
  capsule a row of spheres of its radius along its axis, a box a grid of
  spheres of half its smallest size over its mid-plane (1.5 radii apart, so
  a face is covered to within a third of a radius);
- the environment's geometries (everything not part of the robot, in the
  scene's current state) become boxes in W: a box is itself, a sphere,
  cylinder or capsule its bounding box; other shapes are left out.

The clearance of a configuration is ``min over spheres i, boxes b of
sdf_b(p_Wi) - r_i`` (m; negative: penetration), with the box's signed
distance ``sdf(p) = |max(|p_B| - h, 0)| + min(max_k(|p_B|_k - h_k), 0)`` for
``p_B`` the point in the box frame and ``h`` its half sizes. The arm's links
are not modelled.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from pydrake.geometry import Box, Capsule, Cylinder, Role, Sphere
from pydrake.math import RigidTransform

from rt_drake.planning.scene import PlanningScene
from rt_drake.shaping.cup_chain import CupChain

#: Sphere spacing along a row or grid, in sphere radii.
SPACING = 1.5
#: m, what :meth:`ClearanceModel.swept` adds to its cap above ``floor``.
FLOOR_SLACK = 1e-9


def _spheres(shape, X_CG: RigidTransform) -> list[tuple[np.ndarray, float]]:
    """Spheres (centre in C, radius) standing in for ``shape`` at X_CG."""
    if isinstance(shape, Sphere):
        points, radius = np.zeros((1, 3)), shape.radius()
    elif isinstance(shape, Cylinder | Capsule):
        radius = shape.radius()
        half = 0.5 * shape.length()
        if isinstance(shape, Cylinder):
            half = max(0.0, half - radius)
        count = int(math.ceil(2.0 * half / (SPACING * radius))) + 1
        points = np.zeros((count, 3))
        points[:, 2] = np.linspace(-half, half, count)
    elif isinstance(shape, Box):
        size = np.asarray(shape.size(), float)
        thin = int(np.argmin(size))
        radius = 0.5 * size[thin]
        axes = [k for k in range(3) if k != thin]
        spans = []
        for k in axes:
            half = max(0.0, 0.5 * size[k] - radius)
            count = int(math.ceil(2.0 * half / (SPACING * radius))) + 1
            spans.append(np.linspace(-half, half, count))
        u, v = np.meshgrid(spans[0], spans[1], indexing="ij")
        points = np.zeros((u.size, 3))
        points[:, axes[0]], points[:, axes[1]] = u.ravel(), v.ravel()
    else:
        return []
    centres = X_CG.rotation().matrix() @ points.T + X_CG.translation()[:, None]
    return [(centre, radius) for centre in centres.T]


def _bounding_box(shape) -> np.ndarray | None:
    """Half sizes (m) of a box holding the shape in its own frame, or None."""
    if isinstance(shape, Box):
        return 0.5 * np.asarray(shape.size(), float)
    if isinstance(shape, Sphere):
        return np.full(3, shape.radius())
    if isinstance(shape, Cylinder):
        return np.array([shape.radius(), shape.radius(), 0.5 * shape.length()])
    if isinstance(shape, Capsule):
        r = shape.radius()
        return np.array([r, r, 0.5 * shape.length() + r])
    return None


class ClearanceModel:
    """Sphere-box clearance of the cup's body (load included) in a scene.

    Reads the scene's geometry at construction: build it after the scene is
    prepared for the MOVE (load attached, other objects placed).

    Args:
        scene: The planning scene.
        chain: Kinematics of the same arm (for the cup pose).
    """

    def __init__(self, scene: PlanningScene, chain: CupChain) -> None:
        plant = scene.plant
        checker = scene.checker
        context = checker.model_context()
        plant_context = context.plant_context()
        inspector = (
            checker.model()
            .scene_graph()
            .get_query_output_port()
            .Eval(context.scene_graph_context())
            .inspector()
        )
        cup_body = scene.cup_frame.body()
        X_BC = scene.cup_frame.GetFixedPoseInBodyFrame()
        spheres, boxes = [], []
        for geometry in inspector.GetAllGeometryIds(Role.kProximity):
            body = plant.GetBodyFromFrameId(inspector.GetFrameId(geometry))
            shape = inspector.GetShape(geometry)
            X_BG = inspector.GetPoseInFrame(geometry)
            if body is not None and checker.IsPartOfRobot(body):
                if body.index() == cup_body.index():
                    spheres += _spheres(shape, X_BC.InvertAndCompose(X_BG))
                continue
            half = _bounding_box(shape)
            if half is None:
                continue
            X_WB = (
                RigidTransform()
                if body is None
                else plant.EvalBodyPoseInWorld(plant_context, body)
            )
            X_WG = X_WB @ X_BG
            boxes.append((X_WG.rotation().matrix(), X_WG.translation(), half))
        self._set(chain, spheres, boxes)

    @classmethod
    def of_shapes(
        cls,
        chain: CupChain | None,
        spheres: list[tuple[np.ndarray, float]],
        boxes: list[tuple[np.ndarray, np.ndarray, np.ndarray]],
    ) -> ClearanceModel:
        """The model of given spheres and boxes, without a scene.

        Args:
            chain: Kinematics for :meth:`clearance` (None: poses only).
            spheres: ``(centre in C (3,) m, radius m)``.
            boxes: ``(R_WB (3, 3), p_WB (3,) m, half sizes (3,) m)``.
        """
        model = cls.__new__(cls)
        model._set(chain, spheres, boxes)
        return model

    def _set(
        self,
        chain: CupChain | None,
        spheres: list[tuple[np.ndarray, float]],
        boxes: list[tuple[np.ndarray, np.ndarray, np.ndarray]],
    ) -> None:
        self._chain = chain
        self.centres_C = np.array([c for c, _ in spheres], float).reshape(-1, 3)
        self.radii = np.array([r for _, r in spheres], float)
        self.box_R = np.array([b[0] for b in boxes], float).reshape(-1, 3, 3)
        self.box_p = np.array([b[1] for b in boxes], float).reshape(-1, 3)
        self.box_half = np.array([b[2] for b in boxes], float).reshape(-1, 3)
        self._reach = float(
            (np.linalg.norm(self.centres_C, axis=1) + self.radii).max(initial=0.0)
        )

    @property
    def reach(self) -> float:
        """m, the farthest sphere centre from the cup origin Co."""
        return float(np.linalg.norm(self.centres_C, axis=1).max(initial=0.0))

    def swept(
        self,
        R_WC: np.ndarray,
        p_WC: np.ndarray,
        cutoff: float = 0.05,
        floor: float | None = None,
    ) -> np.ndarray:
        """A lower bound (m) of the clearance between consecutive cup poses.

        For poses (..., M) along a path, segment i (..., M - 1): every sphere
        centre moves at most ``delta_i = |p_{i+1} - p_i| + r theta_i`` from
        pose i to i + 1 (r: :attr:`reach`; theta_i: the angle of
        ``R_i^T R_{i+1}``; chords for arcs, so for samples close enough
        that the motion between them is nearly straight), and the clearance
        is 1-Lipschitz in the position, so at any pose in between it is at
        least ``min(d_i, d_{i+1}) - delta_i / 2``.

        With ``floor``, the pose clearances are capped at ``min(cutoff, floor
        + max_i delta_i / 2 + e)`` (e: :data:`FLOOR_SLACK`, above rounding)
        instead of ``cutoff``: a bound the cap lowers is still above
        ``floor``, so the bounds below ``floor`` (and which segments have
        one) are those of ``cutoff`` alone, and the sphere-box kernel skips
        more boxes (its broad phase prunes at the cap).
        """
        step = np.linalg.norm(np.diff(p_WC, axis=-2), axis=-1)
        trace = np.einsum("...ij,...ij->...", R_WC[..., :-1, :, :], R_WC[..., 1:, :, :])
        theta = np.arccos(np.clip(0.5 * (trace - 1.0), -1.0, 1.0))
        delta = step + self.reach * theta
        if floor is not None:
            top = floor + 0.5 * float(delta.max(initial=0.0)) + FLOOR_SLACK
            cutoff = min(cutoff, top)
        d = self.clearance_at(R_WC, p_WC, cutoff)
        return np.minimum(d[..., :-1], d[..., 1:]) - 0.5 * delta

    def clearance(self, q: np.ndarray, cutoff: float = 0.05) -> np.ndarray:
        """Clearance (m) at configurations q (..., n), capped at ``cutoff``."""
        if self._chain is None:
            raise ValueError("ClearanceModel.of_shapes(None, ...) has no kinematics")
        R_WC, p_WC = self._chain.cup_pose(q)
        return self.clearance_at(R_WC, p_WC, cutoff)

    def clearance_at(
        self, R_WC: np.ndarray, p_WC: np.ndarray, cutoff: float = 0.05
    ) -> np.ndarray:
        """Clearance (m) with the cup at poses (R_WC (..., 3, 3), p_WC (..., 3))."""
        shape = p_WC.shape[:-1]
        out = np.empty(int(np.prod(shape, dtype=int)))
        _clearance(
            np.ascontiguousarray(R_WC.reshape(-1, 3, 3)),
            np.ascontiguousarray(p_WC.reshape(-1, 3)),
            self.centres_C,
            self.radii,
            self.box_R,
            self.box_p,
            self.box_half,
            self._reach,
            float(cutoff),
            out,
        )
        return out.reshape(shape)


@njit(cache=True)
def _clearance(R, p, centres, radii, box_R, box_p, box_half, reach, cutoff, out):  # noqa: D417
    """Minimum over spheres and boxes of the sphere-box signed distance."""
    spheres = centres.shape[0]
    boxes = box_p.shape[0]
    world = np.empty((spheres, 3))
    for i in range(p.shape[0]):
        for k in range(spheres):
            for r in range(3):
                world[k, r] = (
                    p[i, r]
                    + R[i, r, 0] * centres[k, 0]
                    + R[i, r, 1] * centres[k, 1]
                    + R[i, r, 2] * centres[k, 2]
                )
        best = cutoff
        for b in range(boxes):
            B = box_R[b]
            w0 = p[i, 0] - box_p[b, 0]
            w1 = p[i, 1] - box_p[b, 1]
            w2 = p[i, 2] - box_p[b, 2]
            # broad phase: the box's distance to the spheres' bounding ball
            e0 = abs(B[0, 0] * w0 + B[1, 0] * w1 + B[2, 0] * w2) - box_half[b, 0]
            e1 = abs(B[0, 1] * w0 + B[1, 1] * w1 + B[2, 1] * w2) - box_half[b, 1]
            e2 = abs(B[0, 2] * w0 + B[1, 2] * w1 + B[2, 2] * w2) - box_half[b, 2]
            far = math.sqrt(max(e0, 0.0) ** 2 + max(e1, 0.0) ** 2 + max(e2, 0.0) ** 2)
            if far - reach > best:
                continue
            h0, h1, h2 = box_half[b, 0], box_half[b, 1], box_half[b, 2]
            for k in range(spheres):
                w0 = world[k, 0] - box_p[b, 0]
                w1 = world[k, 1] - box_p[b, 1]
                w2 = world[k, 2] - box_p[b, 2]
                e0 = abs(B[0, 0] * w0 + B[1, 0] * w1 + B[2, 0] * w2) - h0
                e1 = abs(B[0, 1] * w0 + B[1, 1] * w1 + B[2, 1] * w2) - h1
                e2 = abs(B[0, 2] * w0 + B[1, 2] * w1 + B[2, 2] * w2) - h2
                outside = max(e0, 0.0) ** 2 + max(e1, 0.0) ** 2 + max(e2, 0.0) ** 2
                inside = min(max(e0, max(e1, e2)), 0.0)
                distance = math.sqrt(outside) + inside - radii[k]
                if distance < best:
                    best = distance
        out[i] = best


__all__ = ["ClearanceModel"]
