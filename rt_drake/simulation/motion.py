"""What the sequencer asks for and gets: a timed motion for one phase.

A :class:`MotionSource` (e.g. :class:`~.online_motions.OnlineMotions`, which
plans and retimes online) hands the :class:`~.sequencer.Sequencer` one
:class:`Motion` per moving phase. The motion carries everything a caller
needs afterwards (its path, its retiming, the grasp it was retimed under),
so nobody has to read it back from the source.
"""

from __future__ import annotations

import dataclasses
from typing import Protocol

import numpy as np
from pydrake.trajectories import Trajectory

from rt_drake.planning import PlannedPath
from rt_drake.retiming import GraspConstraint, RetimeResult
from rt_drake.scenario import ObjectConfig


@dataclasses.dataclass(frozen=True)
class PlanTimes:
    """Wall seconds spent producing one motion (the paper's Table II rows).

    Attributes:
        plan_s: planning the path (IK, collision checks, spline).
        retime_s: retiming it.
    """

    plan_s: float = 0.0
    retime_s: float = 0.0

    @property
    def total_s(self) -> float:
        """``plan_s + retime_s``."""
        return self.plan_s + self.retime_s


@dataclasses.dataclass(frozen=True, eq=False)
class Motion:
    """A timed joint motion for one phase.

    Attributes:
        trajectory: q(t) for t in [0, duration] (rad); derivatives q', q''.
        times: wall seconds spent producing it.
        planned: the planned path it follows, if it came from the planner.
        retimed: the retiming of that path (its trajectory is ``trajectory``
            unless the source plays it faster).
        grasp: the grasp constraint it was retimed under, if any.
        guarantee: for a MOVE, what holds the object, in words (the nominal
            object, every object of its uncertainty set, or none); "" else.
    """

    trajectory: Trajectory
    times: PlanTimes = PlanTimes()
    planned: PlannedPath | None = None
    retimed: RetimeResult | None = None
    grasp: GraspConstraint | None = None
    guarantee: str = ""

    @property
    def duration(self) -> float:
        """Seconds the motion lasts."""
        return self.trajectory.end_time() - self.trajectory.start_time()

    @property
    def q_end(self) -> np.ndarray:
        """Final joint positions (rad)."""
        return self.trajectory.value(self.trajectory.end_time()).ravel()


class MotionSource(Protocol):
    """Plans and retimes the motion of each moving phase, online."""

    def approach(self, q_start: np.ndarray, obj: ObjectConfig) -> Motion:
        """From q_start to above ``obj`` at its start pose."""
        ...

    def reach(self, q_start: np.ndarray, obj: ObjectConfig) -> Motion:
        """From above ``obj`` down to its grasp."""
        ...

    def move(
        self, q_start: np.ndarray, obj: ObjectConfig, reach: Motion | None
    ) -> Motion:
        """Carrying ``obj`` from its grasp to its goal pose.

        ``reach`` is the REACH motion that ended at ``q_start`` (None if
        the arm got there otherwise).
        """
        ...


__all__ = ["Motion", "MotionSource", "PlanTimes"]
