"""The phases of one object's pick-and-place cycle, in order.

One enum for the planner (which plans APPROACH, REACH and MOVE), the
sequencer (which runs all of them) and the reports. Messages print a phase
by its name (``MOVE notebook: ...``), files by its value (``"move"``).
"""

from __future__ import annotations

import enum


class Phase(enum.Enum):
    """A phase of the cycle of one object (paper Section V-B)."""

    APPROACH = "approach"  # from where the arm is to above the object
    REACH = "reach"  # straight down onto the object
    ATTACH = "attach"  # valve on, wait for the seal
    MOVE = "move"  # carry the object to its goal
    DETACH = "detach"  # valve off, wait for the release
    DONE = "done"  # every object placed

    @property
    def moves_the_arm(self) -> bool:
        """True for the phases with a planned motion."""
        return self in (Phase.APPROACH, Phase.REACH, Phase.MOVE)

    @property
    def label(self) -> str:
        """The name used in messages and tables, e.g. ``"MOVE"``."""
        return self.name


__all__ = ["Phase"]
