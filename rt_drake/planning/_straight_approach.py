"""The APPROACH as one straight joint-space line, if that line is clean.

From ``q_start`` (the arm at rest, holding nothing) to the approach pose
above an object (:meth:`~._cycle_planner.CyclePlanner.approach_goal`: the
grasp raised by the object's line height, the IK solution nearest
``q_start``), the path ``q(s) = q_start + h(s) (q_goal - q_start)`` with
``h`` the clamped cubic of :class:`~rt_drake.types.path.GeometricPath`
through the two ends (a straight segment in joint space). It is certified by
the dense check (:func:`~.dense_check.check_path`: collisions and joint
limits, every robot point within ``GRID_STEP`` between samples) in the
APPROACH scene (every object at its pose, no touch allowance). No RRT and no
refinement: a line that is not clean gives None, and the caller plans
otherwise (the cycle's first pick then falls back to the blended pick,
:mod:`._pick`).

A straight line in joint space can be timed without a retimer: every joint
moves in proportion, so a time-optimal point-to-point profile that keeps the
joints in phase stays on it (the cycle's first pick,
:mod:`rt_drake.simulation.online_motions`).
"""

from __future__ import annotations

import numpy as np

from rt_drake.planning._pick import PickPlanner
from rt_drake.planning.dense_check import check_path
from rt_drake.planning.result import PlannedPath
from rt_drake.types.path import GeometricPath
from rt_drake.types.phase import Phase


def straight_approach(
    planner: PickPlanner, q_start: np.ndarray, name: str
) -> PlannedPath | None:
    """The straight APPROACH from ``q_start`` to above ``name``; None if blocked.

    The returned path's ``polyline`` is its two ends; its timing holds the
    scene update, the IK of the approach pose and the line's dense check.

    Raises:
        PlanningError: from :meth:`~._cycle_planner.CyclePlanner.approach_goal`
            (start in collision, approach pose unreachable or colliding).
    """
    goal = planner.approach_goal(q_start, name)
    ends = np.array([goal.q_start, goal.q_goal])
    with goal.attempt.watch("spline"):
        path = GeometricPath.from_waypoints(ends)
    with goal.attempt.watch("check"):
        check = check_path(planner.scene, path)
    if not check.ok:
        return None
    timing = goal.attempt.watch.timing()
    return PlannedPath(Phase.APPROACH, name, path, ends, goal.X_OC, timing)


__all__ = ["straight_approach"]
