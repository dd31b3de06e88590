"""Collision-free paths for the pick-and-place cycle (paper Section III-A).

- :mod:`.scene`: the collision world (Drake's ``SceneGraphCollisionChecker``
  on a ``RobotDiagram``; objects as added shapes, the carried one on the cup).
- :mod:`.ik`: cup-pose IK with Drake's ``InverseKinematics``.
- :mod:`.rrt`: OMPL RRT-Connect and shortcutting.
- :mod:`.path`: the clamped C2 spline handed to the retimer.
- :mod:`.dense_check`, :mod:`.bounds`, :mod:`.kinematics`: the spline's
  dense check, certified by clearance; :mod:`.smooth`: its refinement.
- :mod:`.connect`, :mod:`.cycle_planner`: the phases APPROACH, REACH, MOVE;
  :mod:`.pick`: retreat, APPROACH and REACH blended into one path.
- :mod:`.transport`: random transport queries (the paper's Table I).
"""

from rt_drake.planning.cycle_planner import CyclePlanner
from rt_drake.planning.pick import PlannedPick
from rt_drake.planning.planning_errors import (
    GoalInCollisionError,
    NoPathError,
    PlanningError,
    StartInCollisionError,
    UnreachablePoseError,
)
from rt_drake.planning.result import PlannedPath, PlanTiming
from rt_drake.planning.scene import PlanningScene
from rt_drake.planning.transport_queries import sample_transports
from rt_drake.types.path import GeometricPath

__all__ = [
    "CyclePlanner",
    "GeometricPath",
    "GoalInCollisionError",
    "NoPathError",
    "PlanTiming",
    "PlannedPath",
    "PlannedPick",
    "PlanningError",
    "PlanningScene",
    "StartInCollisionError",
    "UnreachablePoseError",
    "sample_transports",
]
