"""Time-optimal retiming under joint limits and grasp stability (paper III).

The public face of TOPP-RA in rt_drake; everything else in this package is
internal:

- :mod:`.solve`: :func:`retime` and :class:`RetimeResult` (its margins keyed
  by :class:`Margin`; the passes run by an :class:`Engine`).
- :mod:`.limits`: joint limits and the grasp constraint ``F w <= g``, one
  class per source of its rows (:class:`GraspConstraint` given by hand,
  :class:`CupGrasp`, :class:`ToolGrasp`, :class:`ObjectSetGrasp`).
- :mod:`.path`: the joint path ``q(s)`` in the planner's spline convention.
- :mod:`.at_rest`: the object and the arm must be holdable at rest.
- :mod:`.rows`: which grasp rows the stage LPs get, and the exactness check
  (compiled); :mod:`.grasp_rows` applies them for one object.
- :mod:`.robust_grasp`: the grasp of a set of objects (robust to what the
  robot does not know): (row, vertex) pairs built as they bind, with
  :mod:`.robust_rows` (the worst vertex of every row, compiled),
  :mod:`.set_tables` and :mod:`.set_pairs`.
- :mod:`.passes`: TOPP-RA's passes on precomputed constraints.
- :mod:`.seidel`: toppra's seidel LP and the passes, compiled with numba.
- :mod:`.warm`: compiles the kernels before anything is timed.
- :mod:`.timed_path`: the retimed trajectory as a Drake ``Trajectory``;
  :mod:`.time_scaled`: a trajectory played faster.
- :mod:`.check`: dense (1 kHz) verification of a timed trajectory.
- :mod:`.trajectory_file`: the ``.npz`` trajectory format.
- :mod:`.errors`: typed errors and statuses.
"""

from rt_drake.retiming.check import (
    DEFAULT_TOLERANCE,
    Excess,
    Margin,
    TrajectoryCheck,
    WorstMargin,
    check_trajectory,
)
from rt_drake.retiming.joint_path import PathLike, WaypointPath
from rt_drake.retiming.limits import (
    CupGrasp,
    GraspConstraint,
    JointLimits,
    ObjectSetGrasp,
    ToolGrasp,
)
from rt_drake.retiming.passes import Engine
from rt_drake.retiming.precompile import warm_up
from rt_drake.retiming.retime_errors import (
    GraspUnstableAtRestError,
    LimitsBetweenGridPointsError,
    PathNotControllableError,
    RetimeError,
    RetimeInputError,
    RetimeStatus,
    TorqueLimitAtRestError,
)
from rt_drake.retiming.solve import RetimeResult, retime
from rt_drake.retiming.time_scaled import TimeScaled
from rt_drake.retiming.timed_path import TimedPath
from rt_drake.retiming.trajectory_file import (
    SavedTrajectory,
    load_trajectory,
    sample_trajectory,
    save_trajectory,
)
from rt_drake.types.path import (
    chord_knots,
    path_waypoints_and_knots,
)

__all__ = [
    "DEFAULT_TOLERANCE",
    "CupGrasp",
    "Engine",
    "Excess",
    "GraspConstraint",
    "GraspUnstableAtRestError",
    "JointLimits",
    "LimitsBetweenGridPointsError",
    "Margin",
    "ObjectSetGrasp",
    "PathLike",
    "PathNotControllableError",
    "RetimeError",
    "RetimeInputError",
    "RetimeResult",
    "RetimeStatus",
    "SavedTrajectory",
    "TimeScaled",
    "TimedPath",
    "ToolGrasp",
    "TorqueLimitAtRestError",
    "TrajectoryCheck",
    "WaypointPath",
    "WorstMargin",
    "check_trajectory",
    "chord_knots",
    "load_trajectory",
    "path_waypoints_and_knots",
    "retime",
    "sample_trajectory",
    "save_trajectory",
    "warm_up",
]
