"""An object's box and centre of mass, read from its model (SDF).

The CoM half-widths of an :class:`~rt_drake.types.object_uncertainty.ObjectUncertainty`
must keep the centre of mass inside the object: this module reads the box
(the collision geometry of body ``body``, centred at the body frame O, axes
along O) and the nominal CoM ``p_OoScm_O`` of a scenario object.
"""

from __future__ import annotations

import numpy as np
from pydrake.geometry import Box, SceneGraph
from pydrake.multibody.plant import MultibodyPlant

from rt_drake.errors import InputError
from rt_drake.model.object_model import OBJECT_BODY
from rt_drake.model.parser import make_parser


def object_box(model: str, name: str) -> tuple[np.ndarray, np.ndarray]:
    """``(p_OoScm_O, half_extents)`` (m) of the object model ``model``.

    Args:
        model: The model's URL (``package://rt_drake/...``) or file path.
        name: The object's name, for messages.

    Raises:
        InputError: the body has no box collision geometry at its frame.
    """
    plant = MultibodyPlant(0.0)
    scene_graph = SceneGraph()
    plant.RegisterAsSourceForSceneGraph(scene_graph)
    url = model if "://" in model else f"file://{model}"
    (instance,) = make_parser(plant).AddModels(url=url)
    body = plant.GetBodyByName(OBJECT_BODY, instance)
    inspector = scene_graph.model_inspector()
    boxes = [
        (inspector.GetShape(g), inspector.GetPoseInFrame(g))
        for g in plant.GetCollisionGeometriesForBody(body)
        if isinstance(inspector.GetShape(g), Box)
    ]
    if len(boxes) != 1 or not boxes[0][1].IsExactlyIdentity():
        raise InputError(
            f"object '{name}': its model needs one box collision geometry at "
            "the body frame to bound its centre of mass"
        )
    shape = boxes[0][0]
    assert isinstance(shape, Box)
    p_OoScm_O = body.default_spatial_inertia().get_com()
    return np.asarray(p_OoScm_O, dtype=float), np.array(shape.size()) / 2.0


__all__ = ["object_box"]
