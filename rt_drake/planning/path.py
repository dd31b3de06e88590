"""The geometric path handed from the planner to the retimer.

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

import numpy as np
from scipy.interpolate import CubicSpline

from rt_drake import arguments
from rt_drake.retiming.path import chord_knots


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


__all__ = ["GeometricPath", "chord_knots", "drop_repeated"]
