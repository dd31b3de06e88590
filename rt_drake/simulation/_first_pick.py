"""The cycle's first pick in two stages: a straight APPROACH, then the REACH.

The first pick has no motion before it to hide its planning behind: the arm
waits at home for it. So it is planned in the order it runs, and the arm
starts as soon as the first stage is ready (a staged
:class:`~.motion.Motion`; :mod:`.motion` charges the wait):

1. APPROACH (:func:`first_approach`): home to the approach pose along one
   straight joint-space line (:meth:`~rt_drake.planning.CyclePlanner.straight_approach`:
   IK of the approach pose, the line's dense check), timed from rest to rest
   by Ruckig with the joints in phase (:mod:`._line_motion`: time-optimal on
   that line under the velocity, acceleration and jerk limits, well under a
   millisecond). On the critical path: the IK, the check and Ruckig.
2. REACH (:func:`then_reach`): planned
   (:meth:`~rt_drake.planning.CyclePlanner.plan_reach`: the IK line down to
   the grasp, with the blended pick's turn point below its top, so the
   MOVE lifts along the same points as after a blended pick) and retimed
   from rest to rest while the APPROACH runs; the arm begins it at the
   approach pose.

The arm stops at the approach pose, where the blended pick
(:mod:`rt_drake.planning._pick`) keeps moving down; at the top of the
vertical line J1 is at rest either way (the line keeps J1 fixed), and the
stop costs a few milliseconds of motion (BENCHMARKS.md). Where the straight
line is not clean, or Ruckig finds no motion, :func:`first_approach`
returns None and the caller plans the blended pick.
"""

from __future__ import annotations

import time
from collections.abc import Callable

import numpy as np

from rt_drake.planning import CyclePlanner, GeometricPath
from rt_drake.retiming import JointLimits, RetimeResult
from rt_drake.simulation._joined import Joined
from rt_drake.simulation._line_motion import line_motion
from rt_drake.simulation.motion import Motion, PhasePart, PlanTimes
from rt_drake.types.phase import Phase


def first_approach(
    planner: CyclePlanner, limits: JointLimits, q_start: np.ndarray, name: str
) -> Motion | None:
    """The straight APPROACH from rest at ``q_start`` to above ``name``, or None.

    One part (APPROACH), ending at rest at the approach pose; ``planned``
    the straight path. ``limits`` without torque limits (Ruckig bounds the
    joints' velocity, acceleration and jerk only). The planner's scene must
    hold the objects as the pick sees them.
    """
    start = time.perf_counter()
    planned = planner.straight_approach(q_start, name)
    plan_s = time.perf_counter() - start
    if planned is None:
        return None
    start = time.perf_counter()
    trajectory = line_motion(planned.q_start, planned.q_goal, limits)
    retime_s = time.perf_counter() - start
    if trajectory is None:
        return None
    times = PlanTimes(plan_s=plan_s, retime_s=retime_s)
    part = PhasePart(Phase.APPROACH, trajectory.end_time(), times)
    return Motion(trajectory, times, planned=planned, parts=(part,))


def then_reach(
    approach: Motion,
    planner: CyclePlanner,
    retime: Callable[[GeometricPath], RetimeResult],
    name: str,
) -> Motion:
    """``approach`` followed by the REACH from its end: the staged first pick.

    The REACH is planned from the approach pose (``approach.planned``'s
    goal, exactly) and retimed by ``retime`` from rest to rest. The pick's
    ``planned`` and ``retimed`` are the REACH's (its descent is the line a
    MOVE lifts along); its trajectory plays the APPROACH, then the REACH.

    Raises:
        PlanningError: from :meth:`~rt_drake.planning.CyclePlanner.plan_reach`.
    """
    assert approach.planned is not None  # from first_approach
    start = time.perf_counter()
    reach = planner.plan_reach(approach.planned.q_goal, name, turn=True)
    plan_s = time.perf_counter() - start
    start = time.perf_counter()
    result = retime(reach.path)
    retime_s = time.perf_counter() - start
    first = approach.parts[0]
    reach_times = PlanTimes(plan_s=plan_s, retime_s=retime_s)
    parts = (first, PhasePart(Phase.REACH, first.end_s + result.duration, reach_times))
    times = PlanTimes(
        plan_s=approach.times.plan_s + plan_s,
        retime_s=approach.times.retime_s + retime_s,
    )
    return Motion(
        Joined([approach.trajectory, result.trajectory]),
        times,
        planned=reach,
        retimed=result,
        parts=parts,
        staged=True,
    )


__all__ = ["first_approach", "then_reach"]
