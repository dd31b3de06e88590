"""Object shapes for the collision checker.

- :func:`object_geometries`: the proximity shapes of an object model, posed
  in its body frame O, to add to the checker as environment or as the load.
- :func:`shrink_face`: a box with one face moved inward, the allowance that
  lets the cup touch the face it grasps.
- :func:`bounding_radius`: radius of a sphere about a shape's origin that
  holds it.
"""

from __future__ import annotations

import dataclasses
from functools import cache

import numpy as np
from pydrake.geometry import (
    Box,
    Capsule,
    Convex,
    Cylinder,
    Ellipsoid,
    Mesh,
    SceneGraph,
    Shape,
    Sphere,
)
from pydrake.math import RigidTransform
from pydrake.multibody.plant import AddMultibodyPlantSceneGraph, MultibodyPlant
from pydrake.multibody.tree import Body
from pydrake.systems.framework import DiagramBuilder

from rt_drake.model.object_model import OBJECT_BODY
from rt_drake.model.parser import make_parser


@dataclasses.dataclass(frozen=True)
class PosedShape:
    """A shape G and its pose X_FG in some frame F (m)."""

    shape: Shape
    X_FG: RigidTransform


def bounding_radius(shape: Shape) -> float:
    """Radius (m) of a sphere about the shape's origin that contains it."""
    if isinstance(shape, Box):
        return 0.5 * float(np.linalg.norm(shape.size()))
    if isinstance(shape, Sphere):
        return shape.radius()
    if isinstance(shape, Cylinder):
        return float(np.hypot(shape.radius(), 0.5 * shape.length()))
    if isinstance(shape, Capsule):
        return shape.radius() + 0.5 * shape.length()
    if isinstance(shape, Ellipsoid):
        return max(shape.a(), shape.b(), shape.c())
    if isinstance(shape, Mesh | Convex):
        vertices = shape.GetConvexHull().vertices()
        return max(float(np.linalg.norm(v)) for v in vertices)
    raise ValueError(f"no bounding radius for shape {shape!r}")


@cache
def object_geometries(model: str) -> tuple[PosedShape, ...]:
    """Proximity shapes of the body ``body`` of an object model, X_OG in O.

    Args:
        model: ``package://rt_drake/...`` URL or path of the object's SDF.
    """
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlantSceneGraph(builder, time_step=0.0)
    parser = make_parser(plant)
    if "://" in model:
        (instance,) = parser.AddModels(url=model)
    else:
        (instance,) = parser.AddModels(file_name=model)
    body = plant.GetBodyByName(OBJECT_BODY, instance)
    plant.Finalize()
    return tuple(_body_shapes(plant, scene_graph, body))


def _body_shapes(
    plant: MultibodyPlant, scene_graph: SceneGraph, body: Body
) -> list[PosedShape]:
    inspector = scene_graph.model_inspector()
    return [
        PosedShape(inspector.GetShape(g).Clone(), inspector.GetPoseInFrame(g))
        for g in plant.GetCollisionGeometriesForBody(body)
    ]


def shrink_face(
    posed: PosedShape, normal_F: np.ndarray, allowance: float
) -> PosedShape:
    """Move the box face whose outward normal is nearest ``normal_F`` inward.

    Args:
        posed: a box G posed in F; other shapes are returned unchanged.
        normal_F: direction (in F) of the face to move, e.g. the grasped face.
        allowance: m the face moves inward (the box gets thinner by that much).
    """
    if not isinstance(posed.shape, Box) or allowance <= 0.0:
        return posed
    normal_G = posed.X_FG.rotation().inverse() @ np.asarray(normal_F, float)
    axis = int(np.argmax(np.abs(normal_G)))
    size = posed.shape.size().copy()
    allowance = min(allowance, 0.5 * size[axis])
    size[axis] -= allowance
    shift = np.zeros(3)
    shift[axis] = -np.sign(normal_G[axis]) * 0.5 * allowance
    return PosedShape(Box(*size), posed.X_FG @ RigidTransform(shift))


def face_under_cup(
    model: str, X_WO: RigidTransform, X_WC: RigidTransform, tolerance: float
) -> np.ndarray | None:
    """Outward normal (in O) of the object's face the cup rests on, if any.

    The cup rests on an object when the cup frame's origin lies within
    ``tolerance`` (m) of one of the object's boxes; the face is the one
    facing the cup, normal -z_C.
    """
    X_OC = X_WO.InvertAndCompose(X_WC)
    for posed in object_geometries(model):
        if not isinstance(posed.shape, Box):
            continue
        p_GC = posed.X_FG.inverse().multiply(X_OC.translation())
        if np.all(np.abs(p_GC) <= 0.5 * posed.shape.size() + tolerance):
            return -X_OC.rotation().col(2)
    return None


__all__ = [
    "PosedShape",
    "bounding_radius",
    "face_under_cup",
    "object_geometries",
    "shrink_face",
]
