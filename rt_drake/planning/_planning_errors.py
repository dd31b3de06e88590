"""Typed planning failures; each message starts with the phase and object.

Example: ``MOVE notebook: goal configuration in collision (vs060::link3 with
cell::top_plate)``.
"""

from __future__ import annotations

from rt_drake.errors import InputError, RtDrakeError
from rt_drake.types.phase import Phase


class PlanningError(RtDrakeError):
    """A phase of the cycle could not be planned.

    Attributes:
        phase: The phase (APPROACH, REACH or MOVE).
        object: name of the object the phase is for.
        detail: what went wrong.
    """

    def __init__(self, phase: Phase, obj: str, detail: str) -> None:
        self.phase = phase
        self.object = obj
        self.detail = detail
        super().__init__(f"{phase.label} {obj}: {detail}")


class PlanningInputError(PlanningError, InputError):
    """A configuration or pose given to the planner is malformed.

    Wrong size, NaN or inf: refused before any collision query or IK.
    """


class UnreachablePoseError(PlanningError):
    """No IK solution within the joint limits for a cup pose."""


class StartInCollisionError(PlanningError):
    """The start configuration collides or leaves the joint limits."""


class GoalInCollisionError(PlanningError):
    """The goal pose is reachable, but only by colliding configurations."""


class NoPathError(PlanningError):
    """No collision-free path within the time budget (or a straight move collides)."""


__all__ = [
    "GoalInCollisionError",
    "NoPathError",
    "PlanningError",
    "PlanningInputError",
    "StartInCollisionError",
    "UnreachablePoseError",
]
