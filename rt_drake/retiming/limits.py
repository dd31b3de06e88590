"""What the retimer constrains: joint limits and the grasp of a held object.

The names of :mod:`.joint_limits` (:class:`JointLimits`: velocity,
acceleration, torque and jerk per joint) and :mod:`.grasp_constraint`
(:class:`GraspConstraint` ``F w <= g`` and its family :class:`CupGrasp`,
:class:`ToolGrasp`, :class:`ObjectSetGrasp`), in one place: import them
from :mod:`rt_drake.retiming` (or here).
"""

from __future__ import annotations

from rt_drake.retiming.grasp_constraint import (
    GRASP_ATTRIBUTES,
    MAX_GRASP_MARGIN,
    CupGrasp,
    GraspConstraint,
    ObjectSetGrasp,
    ToolGrasp,
)
from rt_drake.retiming.joint_limits import JointLimits

__all__ = [
    "GRASP_ATTRIBUTES",
    "MAX_GRASP_MARGIN",
    "CupGrasp",
    "GraspConstraint",
    "JointLimits",
    "ObjectSetGrasp",
    "ToolGrasp",
]
