"""MOVE path optimisation under the grasp constraint (issue 13).

:func:`optimize_move` returns a MOVE path from the grasp configuration to
the place configuration whose time-optimal duration (TOPP-RA under the joint
limits and the exact grasp polytope ``F w <= g``) is as short as it finds
within a fixed number of candidate paths scored (no clock decides anything,
so the result does not depend on the machine's load). It starts from the
planner's spline path and never returns a slower one. Modules:

- :mod:`._optimizer`: :class:`MoveOptimizer` and :func:`optimize_move`;
  :mod:`._options`: their options and result;
- :mod:`._family`: the paths searched (vertical end segments, free via
  points in joint space starting at the spline path's corners);
- :mod:`._search`: CMA-ES within a number of evaluations; :mod:`._objective`:
  its objective;
- :mod:`._starts`: warm starts learned on other transports (package data
  ``data/warm_starts.npz``);
- :mod:`._surrogate`: batched TOPP-RA on a coarse grid (the duration part);
- :mod:`.cup_chain`, :mod:`._spline`: batched cup kinematics, object wrench
  coefficients and clamped splines (numba);
- :mod:`._clearance`: the search's cheap clearance estimate;
- :mod:`._finish`: the final retime on an adaptive grid, the vertical check;
- :mod:`._jerk_grid`: that grid refined for the jerk-limited retime;
- :mod:`._shape_task`: what one run of the stages shapes, their clock;
- :mod:`._pick_shaping`: :func:`shape_pick`, the pick's transit between
  its retreat and descent lines shaped by the same search (no grasp);
- :mod:`._compile_kernels`: compiles the numba kernels before anything is timed.
"""

from rt_drake.shaping._compile_kernels import warm_up
from rt_drake.shaping._family import FamilyError
from rt_drake.shaping._finish import (
    ADAPTIVE_WEIGHT,
    adaptive_grid,
    retime_adaptive,
    vertical_drift,
)
from rt_drake.shaping._jerk_grid import END_HALVINGS, JERK_GRID_STEP, jerk_grid
from rt_drake.shaping._optimizer import (
    MoveOptimizer,
    optimize_move,
)
from rt_drake.shaping._options import (
    MoveOptimizerError,
    MoveOptimizerOptions,
    MovePlanner,
    OptimizedMove,
)
from rt_drake.shaping._pick_shaping import ShapedPick, shape_pick

__all__ = [
    "ADAPTIVE_WEIGHT",
    "END_HALVINGS",
    "FamilyError",
    "JERK_GRID_STEP",
    "MoveOptimizer",
    "MoveOptimizerError",
    "MoveOptimizerOptions",
    "MovePlanner",
    "OptimizedMove",
    "ShapedPick",
    "adaptive_grid",
    "jerk_grid",
    "optimize_move",
    "retime_adaptive",
    "shape_pick",
    "vertical_drift",
    "warm_up",
]
