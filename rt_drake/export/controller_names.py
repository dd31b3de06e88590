"""The joint names a controller knows: the plant's, renamed by a map.

A model and the controller that drives the real arm often name the same
joints differently: the shipped UR5e calls them ``joint1`` .. ``joint6``,
UR's ROS 2 driver ``shoulder_pan_joint`` .. ``wrist_3_joint``. The scenario
key ``robot.joint_names`` maps the plant's names to the controller's;
joints it does not name keep the plant's name.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from pydrake.multibody.plant import MultibodyPlant

from rt_drake import arguments
from rt_drake.errors import InputError

#: Where the map comes from, for messages.
MAP_KEY = "robot.joint_names"


def plant_joint_names(plant: MultibodyPlant) -> list[str]:
    """The names of the plant's joints in the order of its positions q.

    Raises:
        InputError: a joint has more than one position (a floating or
            ball joint: no controller joint name fits it).
    """
    where = "plant_joint_names"
    arguments.instance(plant, "plant", MultibodyPlant, where=where)
    names = [""] * plant.num_positions()
    for index in plant.GetJointIndices():
        joint = plant.get_joint(index)
        if joint.num_positions() == 0:
            continue
        if joint.num_positions() != 1:
            raise InputError(
                f"{where}: joint '{joint.name()}' has {joint.num_positions()} "
                "positions; only one-position joints have a controller name"
            )
        names[joint.position_start()] = joint.name()
    return names


def controller_joint_names(
    plant: MultibodyPlant, mapping: Mapping[str, str] | None = None
) -> list[str]:
    """The plant's joint names (position order), renamed by ``mapping``.

    Raises:
        InputError: a key of ``mapping`` is not one of the plant's joints,
            or the renamed joints are not distinct (each names ``MAP_KEY``).
    """
    names = plant_joint_names(plant)
    mapping = dict(mapping or {})
    unknown = sorted(set(mapping) - set(names))
    if unknown:
        raise InputError(
            f"key '{MAP_KEY}': '{unknown[0]}' is not a joint of the plant "
            f"(its joints: {', '.join(names)})"
        )
    renamed = [mapping.get(name, name) for name in names]
    check_joint_names(renamed, len(names), MAP_KEY)
    return renamed


def check_joint_names(names: Sequence[str], count: int, what: str) -> list[str]:
    """``names`` as a list: ``count`` distinct non-empty strings, CSV-safe.

    Raises:
        InputError: naming ``what`` (an argument, flag or key) and the fault.
    """
    if isinstance(names, str) or not all(isinstance(n, str) for n in names):
        raise InputError(
            f"{what}: joint names must be a list of strings, got {names!r}"
        )
    names = list(names)
    if len(names) != count:
        raise InputError(
            f"{what}: {len(names)} joint names for a trajectory of {count} joints"
        )
    blank = [i for i, name in enumerate(names) if not name.strip()]
    if blank:
        raise InputError(f"{what}: joint name {blank[0] + 1} is empty")
    broken = [name for name in names if any(c in name for c in ',"\n\r')]
    if broken:
        raise InputError(
            f"{what}: joint name {broken[0]!r} holds a comma, quote or line break "
            "(it would break a CSV header)"
        )
    repeated = sorted({name for name in names if names.count(name) > 1})
    if repeated:
        raise InputError(f"{what}: joint name '{repeated[0]}' is given twice")
    return names


__all__ = [
    "MAP_KEY",
    "check_joint_names",
    "controller_joint_names",
    "plant_joint_names",
]
