"""Time-optimal retiming under joint limits and grasp stability (paper III).

The public face of TOPP-RA in rt_drake: import from here. Four modules are
public because the MOVE optimiser's surrogate (:mod:`rt_drake.shaping`)
reuses them on batches of paths:

- :mod:`.limits`: joint limits and the grasp constraint ``F w <= g``, one
  class per source of its rows (:class:`GraspConstraint` given by hand,
  :class:`CupGrasp`, :class:`ToolGrasp`, :class:`ObjectSetGrasp`), from
  :mod:`.joint_limits` and :mod:`.grasp_constraint` (``_grasp_sets`` builds
  the rows of the sets, ``_grasp_checks`` checks a cup or tool);
- :mod:`.stage_rows`: which grasp rows the stage LPs get, and the exactness
  check (compiled);
- :mod:`.passes` and :mod:`.seidel`: TOPP-RA's passes on precomputed
  constraints, and toppra's seidel LP compiled with numba;
- :mod:`.grid`: the grid of path parameters.

The rest is private (``_x.py``): ``_solve`` (:func:`retime`: its loop of
solves and refinements), ``_retime_inputs`` (its argument checks),
``_position_limits``, ``_exact_solve`` (one solve exact for every grasp
row), ``_retime_result`` (:class:`RetimeResult`), ``_at_rest``,
``_grasp_rows``, ``_robust_grasp``, ``_robust_rows``, ``_set_tables``,
``_set_pairs`` (the grasp of a set of objects), ``_between`` (limits held
between grid points: grasp rows at the midpoints, refinement; ``_segments``
the sub-points, ``_joint_cuts`` the joint limits' rows and cuts,
``_between_refusal`` the last word), ``_samples``, ``_joint_path`` (any path
as ``q(s)``; the path type itself is
:class:`rt_drake.types.path.GeometricPath`), ``_precompile`` (compiles the
kernels before anything is timed), ``_timed_path``, ``_time_scaled``,
``_check`` (dense 1 kHz verification; ``_check_report`` its margins),
``_floor`` (the least time the joint limits allow between two
configurations, :func:`segment_floor`; ``_floor_envelope`` its jerk-limited
bound between bounded end states), ``_stop`` and ``_stop_pass``
(protective stops along the path), ``_jerk_stop``, ``_stop_distance`` and
``_set_slack`` (jerk-limited stops: the search over the stop distance and
its first guess), ``_stop_table`` (stops computed ahead,
:func:`stop_table`), ``_jerk``, ``_jerk_problem`` (one LP of the jerk
pass), ``_jerk_smooth`` (the path's smoothness check), ``_jerk_rows``,
``_jerk_points`` and ``_jerk_timed_path`` (jerk limits: LPs after TOPP-RA,
and the motion they give), ``_trajectory_file`` (the ``.npz`` format) and
``_retime_errors`` (typed errors and statuses), ``_ring_margin`` (a MOVE's
grasp margin from the bellows cup's ring, :func:`retime_for_ring`).
"""

from rt_drake.retiming._check import check_trajectory
from rt_drake.retiming._check_report import (
    DEFAULT_TOLERANCE,
    Excess,
    Margin,
    TrajectoryCheck,
    WorstMargin,
)
from rt_drake.retiming._floor import (
    joint_floor,
    junction_accelerations,
    junction_speeds,
    rest_to_rest_jerk,
    segment_floor,
)
from rt_drake.retiming._jerk_timed_path import JerkTimedPath
from rt_drake.retiming._joint_path import (
    PathLike,
    WaypointPath,
)
from rt_drake.retiming._precompile import warm_up
from rt_drake.retiming._retime_errors import (
    GraspUnstableAtRestError,
    LimitsBetweenGridPointsError,
    PathNotControllableError,
    RetimeError,
    RetimeInputError,
    RetimeStatus,
    TorqueLimitAtRestError,
)
from rt_drake.retiming._ring_margin import (
    RingLoad,
    RingNotHeldError,
    RingRetime,
    retime_for_ring,
    ring_load,
)
from rt_drake.retiming._solve import (
    RetimeResult,
    retime,
)
from rt_drake.retiming._stop import (
    StopNotFoundError,
    StopResult,
    joint_brake_stop,
    protective_stop,
)
from rt_drake.retiming._stop_table import StopTable, stop_table
from rt_drake.retiming._time_scaled import TimeScaled
from rt_drake.retiming._timed_path import PathTrajectory, TimedPath
from rt_drake.retiming._trajectory_file import (
    SavedTrajectory,
    load_trajectory,
    sample_trajectory,
    save_trajectory,
)
from rt_drake.retiming.limits import (
    CupGrasp,
    GraspConstraint,
    JointLimits,
    ObjectSetGrasp,
    ToolGrasp,
)
from rt_drake.retiming.passes import Engine
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
    "JerkTimedPath",
    "JointLimits",
    "LimitsBetweenGridPointsError",
    "Margin",
    "ObjectSetGrasp",
    "PathLike",
    "PathNotControllableError",
    "PathTrajectory",
    "RetimeError",
    "RetimeInputError",
    "RetimeResult",
    "RetimeStatus",
    "RingLoad",
    "RingNotHeldError",
    "RingRetime",
    "SavedTrajectory",
    "StopNotFoundError",
    "StopResult",
    "StopTable",
    "TimeScaled",
    "TimedPath",
    "ToolGrasp",
    "TorqueLimitAtRestError",
    "TrajectoryCheck",
    "WaypointPath",
    "WorstMargin",
    "check_trajectory",
    "chord_knots",
    "joint_brake_stop",
    "joint_floor",
    "junction_accelerations",
    "junction_speeds",
    "load_trajectory",
    "path_waypoints_and_knots",
    "protective_stop",
    "stop_table",
    "rest_to_rest_jerk",
    "retime",
    "retime_for_ring",
    "ring_load",
    "sample_trajectory",
    "save_trajectory",
    "segment_floor",
    "warm_up",
]
