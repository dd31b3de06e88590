"""The geometric path: one type, shared by the planner, the optimiser and the retimer.

A path is a C2 cubic spline ``q(s)`` in joint space (rad), ``s`` in [0, 1],
through joint-space waypoints ``q_0 .. q_{N-1}``. Convention, shared with
the retimer, which rebuilds the same spline as toppra's
``SplineInterpolator(knots, waypoints, bc_type="clamped")``:

- knots ``s_i = L_i / L_{N-1}`` with ``L_i = sum_{k<i} ||q_{k+1} - q_k||_2``,
  the cumulative Euclidean joint-space chord length (rad);
- a scipy ``CubicSpline`` with clamped ends: ``q'(0) = q'(1) = 0``, so the
  path starts and ends at rest whatever the retiming.

``q'(s)`` is in rad per unit s and ``q''(s)`` in rad per unit s squared.
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np
import toppra
from pydrake.trajectories import PiecewisePolynomial
from scipy.interpolate import CubicSpline

from rt_drake import arguments
from rt_drake.errors import InputError

#: Largest |q| of a waypoint (rad, or m for a prismatic joint): 16 turns, far
#: beyond any arm's range; a larger value is a unit or typing error, and
#: would make the trajectory (sampled every 1 ms) arbitrarily long.
MAX_ABS_POSITION = 100.0
#: Most waypoints accepted.
MAX_WAYPOINTS = 100_000


def chord_knots(waypoints: np.ndarray) -> np.ndarray:
    """Return the normalised cumulative chord-length knots of ``waypoints``.

    ``s_i = L_i / L_{N-1}`` with ``L_i = sum_{k<i} ||q_{k+1} - q_k||_2`` (rad):
    the convention the planner and the retimer share.

    Args:
        waypoints: (N, n) joint positions (rad), N >= 2, no two consecutive
            waypoints equal.

    Returns:
        (N,) knots, ``s_0 = 0``, ``s_{N-1} = 1``, strictly increasing.

    Raises:
        InputError (a ValueError): fewer than two waypoints, or two
            consecutive ones equal (zero chord: the knots would not increase).
    """
    waypoints = arguments.array(
        waypoints,
        "waypoints",
        ("N", "n"),
        where="chord_knots",
        finite=False,
    )
    if waypoints.ndim != 2 or waypoints.shape[0] < 2:
        raise InputError(f"need (N >= 2, n) waypoints, got {waypoints.shape=}")
    chords = np.linalg.norm(np.diff(waypoints, axis=0), axis=1)
    if np.any(chords <= 0.0):
        index = int(np.flatnonzero(chords <= 0.0)[0])
        raise InputError(f"waypoints {index} and {index + 1} are equal: zero chord")
    knots = np.concatenate([[0.0], np.cumsum(chords)]) / chords.sum()
    knots[-1] = 1.0
    return knots


def path_waypoints_and_knots(path: Any) -> tuple[np.ndarray, np.ndarray]:
    """Return ``(waypoints (K, n), knots (K,))`` of a path or raw waypoints.

    ``path`` is either an object with ``.waypoints`` and ``.knots`` (the
    planner's ``GeometricPath``) or a (K, n) array of waypoints, whose knots
    are then the normalised chord lengths.

    Raises:
        InputError: fewer than 2 or more than :data:`MAX_WAYPOINTS`
            waypoints, NaN or inf, a value beyond :data:`MAX_ABS_POSITION`,
            equal consecutive waypoints, or knots not strictly increasing from
            0 to 1.
    """
    caller = "path"  # the argument of retime and of path_waypoints_and_knots
    if hasattr(path, "waypoints") and hasattr(path, "knots"):
        waypoints = arguments.array(
            path.waypoints,
            "waypoints",
            ("K", "n"),
            where=caller,
            finite=False,
        )
        knots = arguments.array(path.knots, "knots", ("K",), where=caller)
    else:
        waypoints = arguments.array(
            path,
            "waypoints",
            ("K", "n"),
            where=caller,
            finite=False,
        )
        knots = None
    if (
        waypoints.ndim != 2
        or not 2 <= waypoints.shape[0] <= MAX_WAYPOINTS
        or waypoints.shape[1] < 1
    ):
        raise InputError(
            f"need (K >= 2, n) waypoints, K <= {MAX_WAYPOINTS}, got {waypoints.shape=}"
        )
    if not np.all(np.isfinite(waypoints)):
        row = int(np.flatnonzero(~np.all(np.isfinite(waypoints), axis=1))[0])
        raise InputError(f"waypoint {row} is not finite: {waypoints[row]}")
    if np.abs(waypoints).max() > MAX_ABS_POSITION:
        where = np.unravel_index(np.argmax(np.abs(waypoints)), waypoints.shape)
        index, joint = int(where[0]), int(where[1])
        raise InputError(
            f"waypoint {index}, joint {joint}: {waypoints[index, joint]:g} is beyond "
            f"+-{MAX_ABS_POSITION:g} (rad or m)"
        )
    if knots is None:
        knots = chord_knots(waypoints)
    if (
        knots.shape != (waypoints.shape[0],)
        or not np.all(np.isfinite(knots))
        or not np.all(np.diff(knots) > 0.0)
    ):
        raise InputError(f"knots must increase strictly, got {knots}")
    if knots[0] != 0.0 or knots[-1] != 1.0:
        raise InputError(f"knots must run from 0 to 1, got {knots[[0, -1]]}")
    return waypoints, knots


def path_spline(path: Any) -> CubicSpline:
    """Return the path's clamped ``CubicSpline`` q(s) (what toppra wraps).

    A ``GeometricPath``'s own ``spline`` is reused when it is that spline
    (a ``CubicSpline`` on the path's knots); otherwise it is built.
    """
    waypoints, knots = path_waypoints_and_knots(path)
    spline = getattr(path, "spline", None)
    if (
        isinstance(spline, CubicSpline)
        and np.array_equal(spline.x, knots)
        and spline.c.shape[2:] == waypoints.shape[1:]
    ):
        return spline
    return CubicSpline(knots, waypoints, bc_type="clamped")


def toppra_path(path: Any) -> toppra.SplineInterpolator:
    """Return toppra's clamped spline through the path's waypoints."""
    waypoints, knots = path_waypoints_and_knots(path)
    return toppra.SplineInterpolator(knots, waypoints, bc_type="clamped")


def drake_path(path: Any) -> PiecewisePolynomial:
    """Return the same spline as a Drake ``PiecewisePolynomial`` q(s).

    ``CubicHermite`` through the waypoints with the spline's slopes there
    reproduces the C2 spline exactly (for Drake's own ``Toppra``).
    """
    waypoints, knots = path_waypoints_and_knots(path)
    spline = toppra.SplineInterpolator(knots, waypoints, bc_type="clamped")
    return PiecewisePolynomial.CubicHermite(knots, waypoints.T, spline(knots, 1).T)


def drop_repeated(waypoints: np.ndarray, tolerance: float = 1e-9) -> np.ndarray:
    """Remove waypoints closer than ``tolerance`` (rad, 2-norm) to the previous.

    The last waypoint is always kept (it replaces its near-duplicate).
    """
    waypoints = np.asarray(waypoints, dtype=float)
    kept = [waypoints[0]]
    for q in waypoints[1:]:
        if np.linalg.norm(q - kept[-1]) > tolerance:
            kept.append(q)
    if len(kept) > 1 and np.linalg.norm(waypoints[-1] - kept[-1]) > 0.0:
        kept[-1] = waypoints[-1]
    return np.array(kept)


@dataclasses.dataclass(frozen=True)
class GeometricPath:
    """A clamped cubic spline ``q(s)``, ``s`` in [0, 1], through waypoints.

    Build it with :meth:`from_waypoints`. Evaluation is vectorised: ``s`` a
    scalar gives (n,), an array of shape (M,) gives (M, n).

    Attributes:
        waypoints: (N, n) joint positions (rad) the spline passes through;
            ``waypoints[0]`` and ``waypoints[-1]`` are the start and goal.
        knots: (N,) normalised chord-length parameters of the waypoints.
        spline: ``CubicSpline(knots, waypoints, bc_type="clamped")``.
    """

    waypoints: np.ndarray
    knots: np.ndarray
    spline: CubicSpline

    def __post_init__(self) -> None:
        where = "GeometricPath"
        arguments.array(self.waypoints, "waypoints", ("N", "n"), where=where)
        arguments.array(self.knots, "knots", ("N",), where=where)
        arguments.instance(self.spline, "spline", CubicSpline, where=where)

    @classmethod
    def from_waypoints(cls, waypoints: np.ndarray) -> GeometricPath:
        """Fit the clamped chord-length spline through ``waypoints`` (N, n)."""
        waypoints = np.array(
            arguments.array(
                waypoints, "waypoints", ("N", "n"), where="GeometricPath.from_waypoints"
            )
        )
        knots = chord_knots(waypoints)
        spline = CubicSpline(knots, waypoints, bc_type="clamped")
        waypoints.setflags(write=False)
        knots.setflags(write=False)
        return cls(waypoints=waypoints, knots=knots, spline=spline)

    @property
    def num_positions(self) -> int:
        """Number of joints n."""
        return int(self.waypoints.shape[1])

    def value(self, s: float | np.ndarray) -> np.ndarray:
        """Joint positions q(s) (rad)."""
        return self.spline(s)

    def deriv(self, s: float | np.ndarray) -> np.ndarray:
        """Path tangent q'(s) (rad per unit s); zero at s = 0 and s = 1."""
        return self.spline(s, 1)

    def deriv2(self, s: float | np.ndarray) -> np.ndarray:
        """Path curvature term q''(s) (rad per unit s^2), continuous in s."""
        return self.spline(s, 2)

    def joint_length(self) -> float:
        """Length of the waypoint polyline in joint space (rad, 2-norm)."""
        return float(np.linalg.norm(np.diff(self.waypoints, axis=0), axis=1).sum())


__all__ = [
    "MAX_ABS_POSITION",
    "MAX_WAYPOINTS",
    "GeometricPath",
    "chord_knots",
    "drake_path",
    "drop_repeated",
    "path_spline",
    "path_waypoints_and_knots",
    "toppra_path",
]
