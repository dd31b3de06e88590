"""The cup frame's name and its look-up in a plant (Drake frames, no dynamics).

The shipped tool names its cup frame :data:`DEFAULT_CUP_FRAME`;
:func:`find_frame` finds a frame by name, possibly scoped to a model
instance, and refuses a missing or ambiguous name in one line.
"""

from __future__ import annotations

from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import Frame, ModelInstanceIndex

from rt_drake.errors import InputError

#: The cup frame's name in the shipped tool (models/tool/suction_tool.urdf).
DEFAULT_CUP_FRAME = "suction_cup"


def find_frame(
    plant: MultibodyPlant,
    name: str,
    model_instance: ModelInstanceIndex | None = None,
) -> Frame:
    """The frame ``name`` of ``plant`` (finalized or not).

    ``name`` may be scoped, ``"instance::frame"``; unscoped, it must be the
    name of one frame in the whole plant unless ``model_instance`` is given.

    Raises:
        InputError: no such frame or model instance, or an ambiguous name.
    """
    if "::" in name and model_instance is None:
        instance_name, name = name.rsplit("::", 1)
        if not plant.HasModelInstanceNamed(instance_name):
            raise InputError(f"the plant has no model instance '{instance_name}'")
        model_instance = plant.GetModelInstanceByName(instance_name)
    if model_instance is not None:
        if not plant.HasFrameNamed(name, model_instance):
            instance = plant.GetModelInstanceName(model_instance)
            raise InputError(f"model instance '{instance}' has no frame '{name}'")
        return plant.GetFrameByName(name, model_instance)
    owners = [
        plant.GetModelInstanceName(ModelInstanceIndex(i))
        for i in range(plant.num_model_instances())
        if plant.HasFrameNamed(name, ModelInstanceIndex(i))
    ]
    if not owners:
        raise InputError(
            f"the plant has no frame named '{name}' (name the cup frame, e.g. "
            "CupFrame.of(plant, 'my_tool_tip'))"
        )
    if len(owners) > 1:
        raise InputError(
            f"frame '{name}' is in several model instances ({', '.join(owners)}): "
            "give the model instance of the cup to use"
        )
    return plant.GetFrameByName(name)


__all__ = ["DEFAULT_CUP_FRAME", "find_frame"]
