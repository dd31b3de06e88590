"""Collision-free paths for the pick-and-place cycle (paper Section III-A).

- :mod:`.scene`: the collision world (Drake's ``SceneGraphCollisionChecker``
  on a ``RobotDiagram``; objects as added shapes, the carried one on the cup).
- :mod:`._ik`: cup-pose IK with Drake's ``InverseKinematics``.
- :mod:`._rrt`: OMPL RRT-Connect and shortcutting.
- :mod:`rt_drake.types.path`: the clamped C2 spline handed to the retimer.
- :mod:`.dense_check`, :mod:`._bounds`,
  :mod:`rt_drake.dynamics.body_kinematics`: the spline's dense check,
  certified by clearance; :mod:`._smooth`: its refinement.
- :mod:`._connect`, :mod:`._cycle_planner`: the phases APPROACH, REACH, MOVE;
  :mod:`._pick`: retreat, APPROACH and REACH blended into one path.
- :mod:`._transport_queries`: random transport queries (the paper's Table I).
"""

from rt_drake.planning._cycle_planner import CyclePlanner
from rt_drake.planning._pick import LineDeviation, PlannedPick, line_deviation
from rt_drake.planning._planning_errors import (
    GoalInCollisionError,
    NoPathError,
    PlanningError,
    StartInCollisionError,
    UnreachablePoseError,
)
from rt_drake.planning._transport_queries import sample_transports
from rt_drake.planning.result import PlannedPath, PlanTiming
from rt_drake.planning.scene import PlanningScene
from rt_drake.types.path import GeometricPath

__all__ = [
    "CyclePlanner",
    "GeometricPath",
    "GoalInCollisionError",
    "LineDeviation",
    "NoPathError",
    "PlanTiming",
    "PlannedPath",
    "PlannedPick",
    "PlanningError",
    "PlanningScene",
    "StartInCollisionError",
    "UnreachablePoseError",
    "line_deviation",
    "sample_transports",
]
