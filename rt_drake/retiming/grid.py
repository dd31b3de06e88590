"""The grid in s on which TOPP-RA constrains the path, and its refinement.

TOPP-RA enforces every constraint at the grid points only. Between two grid
points the motion is exact (constant path acceleration), but the constraint
functions vary with the path: how much depends on the path's smoothness
there. The path is a cubic spline in s whose third derivative jumps at the
knots, so a grid segment that straddles a knot can overshoot by several
percent whatever the grid size (9 % of an acceleration limit measured on a
planned MOVE at both 100 and 200 uniform points). Hence :func:`initial_grid`:

- the uniform grid of the requested size;
- every knot of the path, so that each segment lies inside one cubic piece
  (where the constraint functions are smooth);
- at least :data:`MIN_PIECE_SEGMENTS` segments in every piece, so that the
  values between grid points can be estimated from neighbours of the same
  piece (:mod:`._between`);
- no step longer than :data:`MAX_JOINT_STEP` in joint space
  (:func:`bound_steps`): those estimates interpolate the torque and wrench
  coefficients from the grid points, with an error of fourth order in the
  step, so a coarse grid (a small ``gridpoints``, or a long path) would let
  a limit be exceeded between grid points unseen.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from rt_drake.retiming._retime_errors import RetimeInputError

#: Segments per cubic piece of the path, at least.
MIN_PIECE_SEGMENTS = 3
#: Points closer than this in s are merged (a grid step below it is noise).
MIN_STEP = 1e-9
#: rad: longest step between grid points, ``|q(s_{i+1}) - q(s_i)|`` (2-norm).
#: Measured on the retimer's test paths (tests/retiming/test_solve.py, 3
#: paths and 12 random ones, 3 objects) before this bound: grids whose
#: longest step was 0.14-0.50 rad (8-20 uniform points) let the grasp exceed
#: its limit by up to 0.86 % and a joint velocity by up to 0.17 % at 1 kHz,
#: unseen by the retimer; every grid with steps up to 0.15 rad at 30 points
#: kept within 6e-4. The bound leaves a factor 3 in step (about 80 in the
#: interpolation error); grids of 100 points on paths up to 5 rad long are
#: unchanged by it.
MAX_JOINT_STEP = 0.05
#: A step in s shorter than this that still moves more than MAX_JOINT_STEP
#: (a joint speed |q'(s)| above 5e4 rad per unit of s) is a jump in q.
JUMP_STEP = 1e-6
#: Most grid points accepted (the dynamics and the passes are linear in
#: them: 100 000 take about 4 s and 0.6 GB with the grasp constraint).
MAX_GRIDPOINTS = 100_000


def initial_grid(gridpoints: int | np.ndarray, knots: np.ndarray) -> np.ndarray:
    """The grid: ``gridpoints`` uniform points (or the grid given) and the knots.

    Args:
        gridpoints: Number of uniform points (an integer >= 2), or an
            explicit grid (strictly increasing from 0 to 1).
        knots: (K,) the path's knots in s, 0 to 1.

    Returns:
        (G,) strictly increasing from 0 to 1: the uniform points (or the
        grid given), every knot, and :data:`MIN_PIECE_SEGMENTS` equal
        segments in pieces that got fewer.

    Raises:
        RetimeInputError: not an integer >= 2, or a grid that does not
            increase strictly from 0 to 1.
    """
    knots = np.asarray(knots, dtype=float)
    if np.ndim(gridpoints) != 0:
        s = np.asarray(gridpoints, dtype=float)
        if (
            s.ndim != 1
            or not 2 <= s.size <= MAX_GRIDPOINTS
            or s[0] != 0.0
            or s[-1] != 1.0
            or not np.all(np.diff(s) > 0)
        ):
            raise RetimeInputError(
                f"gridpoints must be 2 to {MAX_GRIDPOINTS} values increasing "
                f"strictly from 0 to 1, got {s.size} values"
            )
        return _fill_pieces(_merge(s, knots), knots)
    count = gridpoints
    if isinstance(count, bool) or not isinstance(count, (int, np.integer)):
        raise RetimeInputError(f"gridpoints must be an integer, got {count!r}")
    if not 2 <= count <= MAX_GRIDPOINTS:
        raise RetimeInputError(
            f"gridpoints must be an integer in [2, {MAX_GRIDPOINTS}], got {count!r}"
        )
    return _fill_pieces(_merge(np.linspace(0.0, 1.0, int(count)), knots), knots)


def _fill_pieces(s: np.ndarray, knots: np.ndarray) -> np.ndarray:
    """``s`` with :data:`MIN_PIECE_SEGMENTS` equal segments in pieces that got fewer.

    ``s`` holds every knot. A piece of one or two segments would leave the
    wrench and torque between its grid points to a linear or quadratic
    interpolation (:mod:`._between`), blind to the piece's curvature: on
    paths whose knots bunch at their ends (waypoints sampled at equal times
    of a rest-to-rest motion) a given grid of 101 points, or the adaptive
    grid, let the grasp exceed its limit by up to 4 % at 1 kHz, unseen
    (BENCHMARKS.md, "Retiming on paths whose knots bunch at their ends").
    """
    segments = np.diff(np.searchsorted(s, knots))  # per piece
    short = np.flatnonzero(segments < MIN_PIECE_SEGMENTS)
    if not short.size:
        return s
    fractions = np.arange(1, MIN_PIECE_SEGMENTS) / MIN_PIECE_SEGMENTS
    start, end = knots[short, None], knots[short + 1, None]
    return _merge(s, (start + fractions * (end - start)).ravel())


def bound_steps(s: np.ndarray, path: Callable[[np.ndarray], np.ndarray]) -> np.ndarray:
    """The grid ``s`` with every step longer than :data:`MAX_JOINT_STEP` split.

    A segment whose joint displacement ``|q(s_{i+1}) - q(s_i)|`` is d gets
    ``ceil(d / MAX_JOINT_STEP)`` equal parts in s, and again (the joint speed
    ``|q'(s)|`` varies inside a segment) until every step is within the bound.

    Args:
        s: (G,) grid, strictly increasing from 0 to 1.
        path: ``q(s)`` for an array of s, (G, n).

    Raises:
        RetimeInputError: the bounded grid would exceed
            :data:`MAX_GRIDPOINTS` (a path too long in joint space), or q
            jumps (a step shorter than :data:`JUMP_STEP` in s still moves
            more than the bound).
    """
    while True:
        step = np.linalg.norm(np.diff(path(s), axis=0), axis=1)
        parts = np.ceil(step / MAX_JOINT_STEP)
        long = np.flatnonzero(parts > 1)
        if not long.size:
            return s
        jumps = long[np.diff(s)[long] < JUMP_STEP]
        if jumps.size:
            i = int(jumps[np.argmax(step[jumps])])
            raise RetimeInputError(
                f"the path is not continuous: q jumps by {step[i]:.3g} rad "
                f"at s = {s[i]:.6f}"
            )
        if s.size + float(np.sum(parts[long] - 1)) > MAX_GRIDPOINTS:
            raise RetimeInputError(
                f"the path is {step.sum():.1f} rad long in joint space: steps "
                f"of {MAX_JOINT_STEP} rad need more than {MAX_GRIDPOINTS} grid "
                f"points"
            )
        added = [
            s[i] + (s[i + 1] - s[i]) * np.arange(1, k) / k
            for i, k in zip(long, parts[long].astype(int), strict=True)
        ]
        s = _merge(s, np.concatenate(added))


def _merge(*grids: np.ndarray) -> np.ndarray:
    """0, the interior points of ``grids`` at least MIN_STEP apart, then 1."""
    s = np.unique(np.concatenate(grids))
    inside = s[(s > MIN_STEP) & (s < 1.0 - MIN_STEP)]
    if inside.size:
        inside = inside[np.concatenate([[True], np.diff(inside) > MIN_STEP])]
    return np.concatenate([[0.0], inside, [1.0]])


__all__ = [
    "JUMP_STEP",
    "MAX_GRIDPOINTS",
    "MAX_JOINT_STEP",
    "MIN_PIECE_SEGMENTS",
    "MIN_STEP",
    "bound_steps",
    "initial_grid",
]
