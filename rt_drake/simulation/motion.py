"""What the sequencer asks for and gets: timed motions, planned ahead.

A :class:`MotionSource` (e.g. :class:`~.online_motions.OnlineMotions`, which
plans and retimes online) hands the :class:`~._sequencer.Sequencer` two
:class:`Motion` per object: the pick (APPROACH and REACH in one motion,
split by :class:`PhasePart`) and the MOVE. A motion carries everything a
caller needs afterwards (its path, its retiming, the grasp it was retimed
under, the wall time it took), so nobody has to read it back from the
source.

The two clocks. Planning runs for real, on the wall clock, inside the
sequencer's update at simulated time ``t_r`` (when the motion is requested);
the simulation does not advance meanwhile. The planner is modelled as a
processor of its own that runs in real time beside the robot: a motion whose
planning and retiming took ``w`` wall seconds is ready at simulated time
``t_r + w`` (:class:`PendingMotion`). A phase that needs it at simulated time
``t_n`` starts its motion at ``max(t_n, t_r + w)``: it waits
``max(0, w - (t_n - t_r))``, the part of the planning that did not fit in
the ``t_n - t_r`` seconds available before it (the plan on the critical
path). One wall second counts as one simulated second. The planner plans
one motion at a time: a motion requested while it is busy (the MOVE the
sequencer asks for right after the pick planned ahead) is requested when
it is free, at the previous one's ``ready_at``.

A staged motion (:attr:`Motion.staged`: the cycle's first pick, its
straight APPROACH and then its REACH) is planned part by part, in order,
and each part is needed only when the arm begins it: part k, ready at
``t_r + W_k`` (``W_k`` the wall time of parts 0..k) and begun ``b_k``
seconds after the motion's start (``b_0 = 0``, then the previous part's
end), lets the motion start at ``t_r + max_k (W_k - b_k)``
(:attr:`PendingMotion.start_at`). The arm thus starts once the first part
is ready, and waits longer only if a later part would not be ready when it
reaches it. The planner is busy until ``t_r + W`` (all parts,
:attr:`PendingMotion.ready_at`); the next request waits for it.
"""

from __future__ import annotations

import dataclasses
from typing import Protocol

import numpy as np
from pydrake.trajectories import Trajectory

from rt_drake.model.scenario import ObjectConfig
from rt_drake.planning import PlannedPath
from rt_drake.retiming import GraspConstraint, RetimeResult
from rt_drake.types.phase import Phase


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


@dataclasses.dataclass(frozen=True)
class PhasePart:
    """The share of one phase in a motion that spans several.

    Attributes:
        phase: the phase.
        end_s: s after the motion's start at which the phase ends.
        times: wall seconds spent planning (and retiming) its part.
    """

    phase: Phase
    end_s: float
    times: PlanTimes


@dataclasses.dataclass(frozen=True, eq=False)
class Motion:
    """A timed joint motion for one phase, or for consecutive phases.

    Attributes:
        trajectory: q(t) for t in [0, duration] (rad); derivatives q', q''.
        times: wall seconds spent producing it (all of it).
        planned: the planned path it follows, if it came from the planner
            (a staged motion: its last part's, e.g. the first pick's REACH).
        retimed: the retiming of that path (its trajectory is ``trajectory``
            unless the source plays it faster or the motion is staged).
        grasp: the grasp constraint it was retimed under, if any.
        guarantee: for a MOVE, what holds the object, in words (the nominal
            object, every object of its uncertainty set, or none); "" else.
        parts: for a motion over several phases (the pick: APPROACH then
            REACH), each phase's end and plan times, in order; empty for a
            motion of one phase.
        release_s: for a MOVE, s before its end at which the valve may
            close: the grasp holds over that last stretch with the force
            certain as the vacuum decays (:mod:`._release`); 0: on arrival.
        grasp_price_s: for a MOVE retimed under a grasp, what the grasp costs
            on its path: its duration at the acceleration limits with the
            grasp less without it (s, both on adaptive grids); NaN for other
            motions and for a MOVE not shaped (the figure is computed beside
            the optimiser's own acceleration-limited retime only).
        staged: its ``parts`` were planned one after the other, each part's
            ``times`` its own, and each is needed only when the arm begins
            it (the module docstring); False: the whole motion is needed
            before it starts.
        grasp_margin: for a MOVE retimed under a grasp, the share m of the
            set kept free (``planning.grasp_margin``, or the one its ring
            needed with ``ring``); 0 for other motions.
    """

    trajectory: Trajectory
    times: PlanTimes = PlanTimes()
    planned: PlannedPath | None = None
    retimed: RetimeResult | None = None
    grasp: GraspConstraint | None = None
    guarantee: str = ""
    parts: tuple[PhasePart, ...] = ()
    release_s: float = 0.0
    grasp_price_s: float = float("nan")
    staged: bool = False
    grasp_margin: float = 0.0

    def phase_end(self, phase: Phase) -> float:
        """Seconds after the start at which ``phase`` ends (duration if no parts)."""
        for part in self.parts:
            if part.phase is phase:
                return part.end_s
        return self.duration

    def plan_times(self, phase: Phase) -> PlanTimes:
        """Wall seconds spent on ``phase``'s part (all of ``times`` if no parts)."""
        for part in self.parts:
            if part.phase is phase:
                return part.times
        return self.times

    @property
    def duration(self) -> float:
        """Seconds the motion lasts."""
        return self.trajectory.end_time() - self.trajectory.start_time()

    @property
    def q_end(self) -> np.ndarray:
        """Final joint positions (rad)."""
        return self.trajectory.value(self.trajectory.end_time()).ravel()


@dataclasses.dataclass(frozen=True, eq=False)
class PendingMotion:
    """A motion planned ahead: a future, ready on the simulated clock.

    Attributes:
        motion: the planned motion (its ``times`` measured on the wall clock).
        requested_at: simulated s at which it was requested (and planned).
    """

    motion: Motion
    requested_at: float

    @property
    def wall_s(self) -> float:
        """Wall seconds its planning and retiming took."""
        return self.motion.times.total_s

    @property
    def ready_at(self) -> float:
        """Simulated s at which all of it is ready: ``requested_at + wall_s``."""
        return self.requested_at + self.wall_s

    @property
    def start_at(self) -> float:
        """Simulated s from which it may start.

        ``ready_at``; for a staged motion ``requested_at + max_k (W_k -
        b_k)`` over its parts (the module docstring).
        """
        motion = self.motion
        if not motion.staged or not motion.parts:
            return self.ready_at
        planned, begun, lead = 0.0, 0.0, 0.0
        for part in motion.parts:
            planned += part.times.total_s
            lead = max(lead, planned - begun)
            begun = part.end_s
        return self.requested_at + lead

    def wait_s(self, needed_at: float) -> float:
        """``max(0, start_at - needed_at)``: the wait of a phase starting then."""
        return max(0.0, self.start_at - needed_at)


class MotionSource(Protocol):
    """Plans and retimes the motions of each object, online."""

    def pick(self, q_start: np.ndarray, obj: ObjectConfig, retreat: bool) -> Motion:
        """From q_start to the grasp of ``obj``: APPROACH then REACH (parts).

        ``retreat``: the cup rests on an object just placed at q_start.
        """
        ...

    def move(
        self, q_start: np.ndarray, obj: ObjectConfig, pick: Motion | None
    ) -> Motion:
        """Carrying ``obj`` from its grasp to its goal pose.

        ``pick`` is the motion that ended at ``q_start`` (None if the arm got
        there otherwise).
        """
        ...


__all__ = ["Motion", "MotionSource", "PendingMotion", "PhasePart", "PlanTimes"]
