"""Any joint path the retimer takes, as ``q(s)`` with s in [0, 1].

:func:`as_joint_path` accepts

- waypoints, (K, n) rad, or an object with ``.waypoints`` and ``.knots``
  (the planner's ``GeometricPath``): the clamped cubic spline through them
  with chord-length knots (:mod:`rt_drake.types.path`);
- a Drake ``Trajectory`` with derivatives (``PiecewisePolynomial``,
  ``BsplineTrajectory``, ``CompositeTrajectory``, ...), on [t0, t1];
- a toppra interpolator (``SplineInterpolator`` and any
  ``AbstractGeometricPath``: ``path(ss, order)`` on ``path_interval``).

The path itself is used, never resampled: with the path's own parameter
``t = t0 + s T`` (``T = t1 - t0``), ``d^k q / ds^k = T^k d^k q / dt^k``.

:class:`JointPath` also says where the path's derivatives may jump
(``breaks``: the knots of a spline, the segment times of a piecewise
polynomial, the knots of a B-spline) and whether it is a cubic polynomial
between them (``cubic``): the retimer puts the breaks into its grid and, for
cubic paths, uses exact formulas between grid points (q'' is linear there);
for others it evaluates the path at the points it needs.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Protocol, TypeAlias

import numpy as np
import toppra
from numpy.typing import ArrayLike
from pydrake.trajectories import (
    BsplineTrajectory,
    PiecewisePolynomial,
    PiecewiseTrajectory,
    Trajectory,
)
from scipy.interpolate import CubicSpline

from rt_drake.errors import InputError
from rt_drake.retiming._retime_errors import RetimeInputError
from rt_drake.types.path import path_waypoints_and_knots

#: Derivatives the retimer evaluates: q, q', q'' (q''' for the jerk).
MAX_ORDER = 3


class JointPath:
    """``q(s)``, s in [0, 1], of n joints (see the module docstring).

    Call it like a scipy spline: ``path(s, order)`` gives (n,) for a scalar
    s and (M, n) for (M,) values (and (..., n) for any shape).

    Attributes:
        breaks: (K,) s where derivatives may jump, from 0 to 1.
        cubic: Whether q is a cubic polynomial between breaks.
        num_joints: n.
    """

    def __init__(
        self,
        evaluate: Callable[[np.ndarray, int], np.ndarray],
        breaks: np.ndarray,
        cubic: bool,
        num_joints: int,
    ) -> None:
        self._evaluate = evaluate
        self.breaks = np.asarray(breaks, dtype=float)
        self.cubic = cubic
        self.num_joints = num_joints

    @property
    def x(self) -> np.ndarray:
        """The breaks (scipy's name for a spline's knots)."""
        return self.breaks

    def __call__(self, s: float | np.ndarray, order: int = 0) -> np.ndarray:
        """``d^order q / ds^order`` at s (rad per unit s^order)."""
        if not 0 <= order <= MAX_ORDER:
            raise RetimeInputError(f"path derivative order must be 0..{MAX_ORDER}")
        s = np.asarray(s, dtype=float)
        flat = np.clip(s.reshape(-1), 0.0, 1.0)
        values = self._evaluate(flat, order)
        return values.reshape(*s.shape, self.num_joints)


class WaypointPath(Protocol):
    """A path given by waypoints and knots, as the planner's ``GeometricPath``.

    The retimer joins the waypoints by the clamped cubic spline through them
    at the knots (:mod:`rt_drake.types.path`).
    """

    @property
    def waypoints(self) -> np.ndarray:
        """(K, n) rad."""

    @property
    def knots(self) -> np.ndarray:
        """(K,) s of the waypoints, strictly increasing from 0 to 1."""


#: What :func:`as_joint_path` (and so ``retime``) takes: a :class:`JointPath`,
#: a Drake ``Trajectory`` with derivatives, a toppra interpolator, a
#: :class:`WaypointPath`, or (K, n) waypoints (chord-length knots).
PathLike: TypeAlias = (
    JointPath
    | Trajectory
    | toppra.interpolator.AbstractGeometricPath
    | WaypointPath
    | ArrayLike
)


def as_joint_path(path: PathLike) -> JointPath:
    """The retimer's view of ``path`` (see the module docstring).

    Raises:
        RetimeInputError: an unsupported type, a trajectory without
            derivatives or of zero duration, or malformed waypoints.
    """
    if isinstance(path, JointPath):
        return path
    if isinstance(path, Trajectory):
        return _from_drake(path)
    if hasattr(path, "path_interval") and callable(path):
        return _from_toppra(path)
    if hasattr(path, "waypoints") and hasattr(path, "knots") or _array_like(path):
        return _from_waypoints(path)
    raise RetimeInputError(
        f"unsupported path of type {type(path).__name__}: give (K, n) waypoints, "
        "a GeometricPath, a Drake Trajectory with derivatives or a toppra "
        "interpolator"
    )


def _array_like(path: Any) -> bool:
    try:
        return np.asarray(path, dtype=float).ndim >= 1
    except (TypeError, ValueError):
        return False


def _from_waypoints(path: Any) -> JointPath:
    try:
        waypoints, knots = path_waypoints_and_knots(path)
    except InputError as error:  # the path type's refusal, as the retimer's
        raise RetimeInputError(str(error)) from None
    spline = getattr(path, "spline", None)
    if not (
        isinstance(spline, CubicSpline)
        and np.array_equal(spline.x, knots)
        and spline.c.shape[2:] == waypoints.shape[1:]
    ):
        spline = CubicSpline(knots, waypoints, bc_type="clamped")

    def evaluate(s: np.ndarray, order: int) -> np.ndarray:
        return spline(s, order)

    return JointPath(evaluate, knots, cubic=True, num_joints=waypoints.shape[1])


def _from_toppra(path: Any) -> JointPath:
    start, end = (float(v) for v in path.path_interval)
    if not end > start:
        raise RetimeInputError(f"toppra path interval [{start}, {end}] is empty")
    span = end - start
    probe = np.atleast_1d(np.asarray(path(np.array([start])), dtype=float))
    n = probe.shape[-1]
    knots = getattr(path, "ss_waypoints", None)
    breaks = (
        np.array([0.0, 1.0])
        if knots is None
        else (np.asarray(knots, dtype=float) - start) / span
    )

    def evaluate(s: np.ndarray, order: int) -> np.ndarray:
        values = np.asarray(path(start + s * span, order), dtype=float)
        return values.reshape(len(s), n) * span**order

    cubic = isinstance(path, toppra.SplineInterpolator)
    return JointPath(evaluate, breaks, cubic=cubic, num_joints=n)


def _from_drake(trajectory: Trajectory) -> JointPath:
    if trajectory.cols() != 1:
        raise RetimeInputError(
            f"a path trajectory must be a column vector, got {trajectory.rows()} x "
            f"{trajectory.cols()}"
        )
    if not trajectory.has_derivative():
        raise RetimeInputError(
            f"{type(trajectory).__name__} has no derivatives: the retimer needs "
            "q', q'' (give a PiecewisePolynomial, BsplineTrajectory, ...)"
        )
    start, end = trajectory.start_time(), trajectory.end_time()
    if not end > start:
        raise RetimeInputError(f"path trajectory spans [{start}, {end}]: empty")
    span = end - start
    derivatives = [trajectory] + [
        trajectory.MakeDerivative(k) for k in range(1, MAX_ORDER + 1)
    ]

    def evaluate(s: np.ndarray, order: int) -> np.ndarray:
        values = derivatives[order].vector_values(list(start + s * span))
        return np.asarray(values, dtype=float).T * span**order

    times, cubic = _drake_breaks(trajectory)
    breaks = np.clip((np.asarray(times, dtype=float) - start) / span, 0.0, 1.0)
    breaks = np.unique(np.concatenate([[0.0], breaks, [1.0]]))
    return JointPath(evaluate, breaks, cubic=cubic, num_joints=trajectory.rows())


def _drake_breaks(trajectory: Trajectory) -> tuple[list[float], bool]:
    """Where a Drake trajectory's derivatives may jump, and if it is cubic."""
    if isinstance(trajectory, PiecewisePolynomial):
        degree = max(
            trajectory.getSegmentPolynomialDegree(i, row, 0)
            for i in range(trajectory.get_number_of_segments())
            for row in range(trajectory.rows())
        )
        return list(trajectory.get_segment_times()), degree <= 3
    if isinstance(trajectory, BsplineTrajectory):
        return list(trajectory.basis().knots()), trajectory.basis().order() <= 4
    if isinstance(trajectory, PiecewiseTrajectory):
        return list(trajectory.get_segment_times()), False
    return [], False


class ToppraPath(toppra.interpolator.AbstractGeometricPath):
    """A :class:`JointPath` as toppra's path interface (for ``engine="toppra"``)."""

    def __init__(self, path: JointPath) -> None:
        self._path = path

    def __call__(self, ss: Any, order: int = 0) -> np.ndarray:  # noqa: D102
        return self._path(ss, order)

    @property
    def dof(self) -> int:  # noqa: D102
        return self._path.num_joints

    @property
    def path_interval(self) -> np.ndarray:  # noqa: D102
        return np.array([0.0, 1.0])

    @property
    def waypoints(self) -> None:  # noqa: D102
        return None


__all__ = [
    "MAX_ORDER",
    "JointPath",
    "PathLike",
    "ToppraPath",
    "WaypointPath",
    "as_joint_path",
]
