"""The final retime on an adaptive grid, and the vertical-end check.

TOPP-RA's interpolation scheme constrains the grid points only, with one
path acceleration per segment: it loses time where the profile ``x = s'^2``
changes much within a segment (near the ends of a rest-to-rest move, and
where the path turns sharply, e.g. at the top of a vertical end segment). On
a uniform grid of 100 points that left about 6 % of the duration unused
against 1000 points on the planner's MOVE paths. :func:`retime_adaptive`
spends the points where the profile moves: a first retime on 100 uniform
points gives ``t(s)`` and ``x(s)``; the final grid puts its N points at equal
steps of the measure (in two passes, see :func:`retime_adaptive`)

    mu(s) = w t(s) / T + (1 - w) V(s) / V(1),   V(s) = int_0^s |dx|

(time, and the total variation of x). With N = 400 and w = 0.3 it was within
0.3 % of a 1000-point uniform retime (0.6 % shorter on average) on 80
spline and optimised MOVE paths (random_transport, seeds 0 and 1; 27 of
random_transport_paper: +0.07 % at most), for about 60 % of the cost;
one pass from the 100-point profile lost up to 0.54 %, and equal time steps
(w = 1, or 0.8 with 0.2 of uniform s) up to 5 % on paths that turn sharply
at the top of a vertical segment (see BENCHMARKS.md).
"""

from __future__ import annotations

import numpy as np
from pydrake.multibody.plant import MultibodyPlant

from rt_drake.cup_frame import CupFrame
from rt_drake.planning.shape.kinematics import CupChain
from rt_drake.retiming import (
    GraspConstraint,
    JointLimits,
    RetimeError,
    RetimeResult,
    retime,
)

#: Points of the coarse uniform retime that sizes the grid.
COARSE_POINTS = 100
#: Uniform points if an adaptive pass fails numerically.
FALLBACK_POINTS = 1000


def adaptive_grid(result: RetimeResult, points: int, weight: float) -> np.ndarray:
    """Grid of ``points`` parameters at equal steps of ``mu(s)`` (module doc)."""
    s, sd = result.gridpoints, result.sd
    dt = 2.0 * np.diff(s) / (sd[:-1] + sd[1:])
    t = np.concatenate([[0.0], np.cumsum(dt)])
    variation = np.concatenate([[0.0], np.cumsum(np.abs(np.diff(sd**2)))])
    measure = weight * t / t[-1] + (1.0 - weight) * variation / variation[-1]
    grid = np.interp(np.linspace(0.0, 1.0, points), measure, s)
    # At most ten times finer than the uniform grid (three times: the loss
    # against 1000 points grew from +0.30 % to +0.62 % at most). TOPP-RA's
    # safeguards can fail on such steps at the end of a MOVE (as on a
    # 4000-point uniform grid): retime_adaptive falls back then.
    step = 0.1 / points
    kept = [0.0]
    for value in grid[1:-1]:
        if value - kept[-1] >= step and 1.0 - value >= step:
            kept.append(float(value))
    kept.append(1.0)
    return np.array(kept)


def retime_adaptive(
    plant: MultibodyPlant,
    path,
    limits: JointLimits,
    grasp: GraspConstraint | None,
    points: int = 400,
    weight: float = 0.3,
    context=None,
    cup: CupFrame | None = None,
) -> RetimeResult:
    """Retime ``path`` on the adaptive grid of :func:`adaptive_grid`, in two passes.

    The profile of a 100-point uniform retime sizes a grid of ``points / 2``,
    whose profile sizes the final grid of ``points`` (the coarse profile
    misplaces sharp features). If an adaptive pass fails numerically, the
    path is retimed on :data:`FALLBACK_POINTS` uniform points instead (the
    discretization target's reference). Raises the retimer's errors if the
    path cannot be retimed at all.
    """
    cup = cup or CupFrame.of(plant)
    result = retime(plant, path, limits, grasp, COARSE_POINTS, context=context, cup=cup)
    try:
        for count in (points // 2, points):
            grid = adaptive_grid(result, count, weight)
            result = retime(plant, path, limits, grasp, grid, context=context, cup=cup)
    except RetimeError:
        result = retime(
            plant, path, limits, grasp, FALLBACK_POINTS, context=context, cup=cup
        )
    return result


def vertical_drift(chain: CupChain, path, s_start: float, s_end: float) -> float:
    """Horizontal drift (m) of the cup on ``s in [s_start, s_end]`` of ``path``.

    The largest horizontal distance of the cup origin from its position at
    whichever end of the interval is an end of the path (s = 0 or 1): for a
    vertical end segment, how far the cup strays from the vertical line
    through the grasp (or place). Sampled at 200 points.
    """
    s = np.linspace(s_start, s_end, 200)
    p = chain.cup_pose(path.value(s))[1]
    origin = p[0] if s_start == 0.0 else p[-1]
    up = chain.gravity_W / np.linalg.norm(chain.gravity_W)
    offset = p - origin
    horizontal = offset - np.outer(offset @ up, up)
    return float(np.linalg.norm(horizontal, axis=1).max())


__all__ = [
    "COARSE_POINTS",
    "FALLBACK_POINTS",
    "adaptive_grid",
    "retime_adaptive",
    "vertical_drift",
]
