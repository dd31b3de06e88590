"""Checks of a grasp constraint's cup or tool, and its words for a cup.

A cup holds an object only with friction > 0: a frictionless rim exerts no
tangential force, so its wrench set has no interior and the grasp
constraint ``F w <= g`` would need g > 0 on rows whose g is 0.
"""

from __future__ import annotations

from typing import Any

from rt_drake import arguments
from rt_drake.contact import CupParameters, ToolParameters
from rt_drake.retiming._retime_errors import RetimeInputError


def check_single_cup(cup: object, method: str) -> None:
    """Sets of objects are held by one cup (not yet by a multi-cup tool)."""
    if not isinstance(cup, CupParameters):
        raise RetimeInputError(
            f"GraspConstraint.{method} needs one cup (CupParameters), got "
            f"{type(cup).__name__}"
        )


def check_grip(cup: object, where: str) -> None:
    """A cup (or every cup of a tool) with friction > 0, which can hold an object.

    A frictionless rim exerts no tangential force, so its wrench set has no
    interior: the grasp constraint would need g > 0 on rows whose g is 0.
    """
    arguments.instance(
        cup,
        "cup",
        (CupParameters, ToolParameters),
        where=where,
        error=RetimeInputError,
    )
    cups = [m.cup for m in cup.cups] if isinstance(cup, ToolParameters) else [cup]
    for index, one in enumerate(cups):
        which = f"cups[{index}]." if isinstance(cup, ToolParameters) else "cup."
        for name in ("friction", "friction_min"):
            value = getattr(one, name)
            if value is not None and not value > 0.0:
                raise RetimeInputError(
                    f"{where}: {which}{name} must be > 0 to hold an object "
                    f"(a frictionless rim exerts no sideways force), got {value!r}"
                )


def check_source(grasp: Any, name: str, kind: type) -> None:
    """A family member's cup or tool (``grasp.<name>``): a ``kind``, friction > 0."""
    where = type(grasp).__name__
    value = getattr(grasp, name)
    arguments.instance(value, name, kind, where=where, error=RetimeInputError)
    check_grip(value, where)


def suction_text(cup: CupParameters) -> str:
    """``, suction 20 N`` and `` (at least 18 N)`` with a suction range."""
    text = f", suction {cup.suction_force:.3g} N"
    if cup.suction_force_min is not None:
        text += f" (at least {cup.suction_force_min:.3g} N)"
    return text
