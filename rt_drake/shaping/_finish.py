"""The final retime on an adaptive grid, and the vertical-end check.

TOPP-RA's interpolation scheme constrains the grid points (and, in
:func:`rt_drake.retime`, the limits between them) with one path
acceleration per segment: it loses time where the profile ``x = s'^2``
changes much within a segment (near the ends of a rest-to-rest move, and
where the path turns sharply, e.g. at the top of a vertical end segment). On
100 uniform points that leaves about 6 % of a MOVE's duration unused against
1000 points. :func:`retime_adaptive` spends the points where the profile
moves: the profile of the coarse retimer (:mod:`._surrogate`, batched
kinematics, at the grid points only; 100 uniform points) gives ``t(s)`` and
``x(s)``; a grid of 200 points at equal steps of the measure

    mu(s) = w t(s) / T + (1 - w) V(s) / V(1),   V(s) = int_0^s |dx|

(time, and the total variation of x) gets the coarse retimer's profile
again, which places the final grid of N points, and :func:`rt_drake.retime`
retimes the path once on it (adding the path's knots and what it needs
between grid points). Measured against 1000 uniform points with the current
``retime`` (BENCHMARKS.md), N = 400, w = 0.3:

- 24 spline and randomly perturbed MOVE paths of random_transport: at most
  +0.16 %; 19 spline and optimised paths of random_transport_paper: at most
  -0.16 % (shorter), for 30-35 ms of CPU;
- one coarse pass (100 uniform points, then 500 points) lost up to +1.96 %
  on two optimised paper paths (their sharp turns fall between the coarse
  points); 600 uniform points up to +1.23 %; the two-pass scheme by
  ``retime`` itself (100, 200, 400 points) was within +0.17 % for 60 % more
  CPU, and failed numerically once.
"""

from __future__ import annotations

import numpy as np
from numba import njit
from pydrake.multibody.plant import MultibodyPlant

from rt_drake.dynamics.cup_frame import CupFrame
from rt_drake.retiming import (
    GraspConstraint,
    JointLimits,
    RetimeError,
    RetimeResult,
    retime,
)
from rt_drake.shaping._surrogate import CoarseRetimer
from rt_drake.shaping.cup_chain import CupChain

#: Points of the coarse uniform profile, and of the grid it places.
COARSE_POINTS = 100
MIDDLE_POINTS = 200
#: Points of the final grid.
FINAL_POINTS = 400
#: Uniform points if the adaptive retime fails numerically.
FALLBACK_POINTS = 1000
#: w of the measure: the share of time in it (module docstring).
ADAPTIVE_WEIGHT = 0.3


def adaptive_grid(
    s: np.ndarray, sd: np.ndarray, points: int, weight: float
) -> np.ndarray:
    """Grid of ``points`` parameters at equal steps of ``mu(s)`` (module doc).

    Args:
        s: (M,) grid of a profile.
        sd: (M,) its path velocity s' (1/s).
        points: Size of the new grid.
        weight: w, the share of time in the measure.
    """
    dt = 2.0 * np.diff(s) / np.maximum(sd[:-1] + sd[1:], 1e-12)
    t = np.concatenate([[0.0], np.cumsum(dt)])
    variation = np.concatenate([[0.0], np.cumsum(np.abs(np.diff(sd**2)))])
    measure = weight * t / t[-1] + (1.0 - weight) * variation / max(
        variation[-1], 1e-12
    )
    grid = np.interp(np.linspace(0.0, 1.0, points), measure, s)
    # At most ten times finer than the uniform grid: TOPP-RA's safeguards
    # can fail on much finer steps at the end of a MOVE (as on a 4000-point
    # uniform grid); retime_adaptive falls back then.
    return _thin(grid, 0.1 / points)


@njit(cache=True)
def _thin(grid: np.ndarray, step: float) -> np.ndarray:
    """0, each inner point of ``grid`` ``step`` past the last kept and before 1, 1."""
    kept = np.empty(len(grid))
    kept[0] = 0.0
    count = 1
    for value in grid[1:-1]:
        if value - kept[count - 1] >= step and 1.0 - value >= step:
            kept[count] = value
            count += 1
    kept[count] = 1.0
    return kept[: count + 1].copy()


def coarse_profile(
    chain: CupChain,
    limits: JointLimits,
    grasp: GraspConstraint,
    waypoints: np.ndarray,
    grid: int | np.ndarray = COARSE_POINTS,
) -> tuple[np.ndarray, np.ndarray] | None:
    """``(s, s')`` of the coarse retimer's profile of a path, or None if rejected.

    On ``grid`` (a number of uniform points, or the points).
    """
    s, sd, _ = _profile(chain, limits, grasp, waypoints, grid)
    return None if s is None or sd is None else (s, sd)


def _profile(
    chain: CupChain,
    limits: JointLimits,
    grasp: GraspConstraint,
    waypoints: np.ndarray,
    grid: int | np.ndarray,
    rows: np.ndarray | None = None,
) -> tuple[np.ndarray | None, np.ndarray | None, np.ndarray]:
    """:func:`coarse_profile`'s ``(s, s')`` (Nones if rejected), and its rows.

    The rows start as ``rows`` if given (the exactness check adds any row
    the profile violates, so the profile is TOPP-RA's with every row
    either way), else as those ray shooting picks on the path.
    """
    surrogate = CoarseRetimer(chain, limits, grasp, grid, rows)
    if rows is None:
        surrogate.select_rows(np.asarray(waypoints)[None])
    duration, x = surrogate.profile(waypoints)
    used = np.flatnonzero(surrogate.rows)
    if not np.isfinite(duration):
        return None, None, used
    return surrogate.s, np.sqrt(np.maximum(x, 0.0)), used


def retime_adaptive(
    plant: MultibodyPlant,
    path,
    limits: JointLimits,
    grasp: GraspConstraint | None,
    points: int = FINAL_POINTS,
    weight: float = ADAPTIVE_WEIGHT,
    context=None,
    cup: CupFrame | None = None,
    chain: CupChain | None = None,
) -> RetimeResult:
    """Retime ``path`` (:func:`rt_drake.retime`) on an adaptive grid.

    The grid is placed by the coarse retimer's profile, in two passes (with
    a grasp; without one, by a 100-point ``retime``). If the profile or the
    adaptive retime fails numerically, the path is retimed on
    :data:`FALLBACK_POINTS`
    uniform points (the discretization target's reference). Raises the
    retimer's errors if the path cannot be retimed at all.

    Args:
        plant: The retimer's arm plant.
        path: The path (``GeometricPath``).
        limits: Joint limits.
        grasp: Grasp constraint, or None.
        points: Size of the adaptive grid (before ``retime`` adds the knots
            and the points of :mod:`rt_drake.retiming.grid`).
        weight: w of the measure (module docstring).
        context: Scratch context of ``plant``.
        cup: The cup frame C of ``plant``.
        chain: The batched kinematics of ``plant`` (made if None).
    """
    cup = cup or CupFrame.of(plant)

    def timed(grid: int | np.ndarray) -> RetimeResult:
        return retime(plant, path, limits, grasp, grid, context=context, cup=cup)

    if grasp is None:
        coarse = timed(COARSE_POINTS)
        profile: tuple[np.ndarray, np.ndarray] | None = (coarse.gridpoints, coarse.sd)
    else:
        chain = chain or CupChain(plant, cup)
        waypoints = np.asarray(getattr(path, "waypoints", path), dtype=float)
        s, sd, rows = _profile(chain, limits, grasp, waypoints, COARSE_POINTS)
        profile = None
        if s is not None and sd is not None:
            # The second pass starts from the first's rows (no ray shooting).
            middle = adaptive_grid(s, sd, MIDDLE_POINTS, weight)
            s, sd, _ = _profile(chain, limits, grasp, waypoints, middle, rows)
            profile = None if s is None or sd is None else (s, sd)
    if profile is not None:
        try:
            return timed(adaptive_grid(*profile, points, weight))
        except RetimeError:
            pass
    return timed(FALLBACK_POINTS)


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
    "ADAPTIVE_WEIGHT",
    "COARSE_POINTS",
    "FALLBACK_POINTS",
    "FINAL_POINTS",
    "MIDDLE_POINTS",
    "adaptive_grid",
    "coarse_profile",
    "retime_adaptive",
    "vertical_drift",
]
