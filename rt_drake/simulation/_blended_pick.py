"""The blended pick as one timed motion: APPROACH and REACH without a stop.

The planner's blended pick (:meth:`~rt_drake.planning.CyclePlanner.plan_pick`:
a retreat after a place, the transit, the descent, one spline) is retimed
from rest to rest as a whole, and split into its phases where the retimed
motion passes the approach pose (:func:`._time_at.time_at`): APPROACH until
then, REACH after. Every pick after a place is this one; so is the first
where its straight APPROACH is blocked (:mod:`._first_pick`).

With ``shape`` (the cycle's MOVE optimisation on), the pick's transit is
shaped first (:func:`rt_drake.shaping.shape_pick`: the same lines, the
transit between them searched as a MOVE's), and the path it returns is the
one played, retimed there as any pick (the shaping's finish retimes its
candidates so); the search counts as planning, its final retimes as
retiming, as a shaped MOVE's.
"""

from __future__ import annotations

import time
from collections.abc import Callable

import numpy as np

from rt_drake.planning import CyclePlanner, GeometricPath, PlannedPick
from rt_drake.retiming import RetimeResult
from rt_drake.shaping import ShapedPick
from rt_drake.simulation._time_at import time_at
from rt_drake.simulation.motion import Motion, PhasePart, PlanTimes
from rt_drake.types.phase import Phase


def blended_pick(
    planner: CyclePlanner,
    retime: Callable[[GeometricPath, RetimeResult | None], RetimeResult],
    q_start: np.ndarray,
    name: str,
    retreat: bool,
    tried_s: float = 0.0,
    shape: Callable[[PlannedPick], ShapedPick | None] | None = None,
) -> Motion:
    """Plan (and shape, with ``shape``) and retime the blended pick of ``name``.

    Parts: APPROACH until the cup passes the approach pose (its plan times:
    the retreat, transit and blend, its shaping, ``tried_s`` wall seconds
    spent before on a route that did not work out, and the retime), then
    REACH (its plan times: the descent's IK line). ``retime(path, profile)``
    retimes a pick's path, ``profile`` its acceleration-limited retime if
    already done; ``shape`` returns the shaped pick, or None where it
    failed (the blended pick is then played). The planner's scene must hold
    the objects as the pick sees them.
    """
    start = time.perf_counter()
    planned = planner.plan_pick(q_start, name, retreat)
    plan_s = time.perf_counter() - start + tried_s
    result, retime_s = None, 0.0
    shaped = None if shape is None else shape(planned)
    if shaped is not None:
        found = shaped.optimized
        planned = shaped.pick
        result = found.played if found.improved else found.spline_played
        plan_s += found.wall_s - found.retime_wall_s
        retime_s = found.retime_wall_s
    start = time.perf_counter()
    if result is None:
        result = retime(planned.path.path, None)
    t_approach = time_at(result, planned.s_approach)
    retime_s += time.perf_counter() - start
    reach_s = min(planned.reach_timing.total_s, plan_s)
    parts = (
        PhasePart(
            Phase.APPROACH,
            t_approach,
            PlanTimes(plan_s=plan_s - reach_s, retime_s=retime_s),
        ),
        PhasePart(Phase.REACH, result.duration, PlanTimes(plan_s=reach_s)),
    )
    return Motion(
        result.trajectory,
        PlanTimes(plan_s=plan_s, retime_s=retime_s),
        planned=planned.path,
        retimed=result,
        parts=parts,
    )


__all__ = ["blended_pick"]
