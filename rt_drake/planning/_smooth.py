"""From a collision-free polyline to a collision-free C2 spline.

The clamped chord-length cubic spline (:class:`GeometricPath`) through the
polyline's vertices cuts corners. :func:`fit_spline` checks it densely
(:func:`~rt_drake.planning.dense_check.check_path`) and, where it collides
or leaves the joint limits at s, inserts the midpoints of the polyline
segments around s (the knot interval holding s and its two neighbours) and
refits. The inserted points lie on the polyline, so the polyline does not
change while the spline is pulled onto it; a few rounds suffice in practice.

That converges only if the polyline itself is free. RRT edges are checked
at a step of about 2 cm, which can miss a graze, so when the spline collides
the polyline segment under it is certified too (a two-waypoint path is the
straight segment); if that segment collides, :func:`fit_spline` reports it
(``bad_segment``) for the caller to re-plan.
"""

from __future__ import annotations

import dataclasses
import time

import numpy as np

from rt_drake.planning.dense_check import DenseCheck, check_path
from rt_drake.planning.scene import PlanningScene
from rt_drake.types.path import (
    GeometricPath,
    drop_repeated,
)

#: refinement rounds before giving up.
MAX_ROUNDS = 12


@dataclasses.dataclass(frozen=True)
class SplineFit:
    """Outcome of :func:`fit_spline`.

    Attributes:
        path: the last spline fitted (collision-free iff ``check.ok``).
        check: its dense check.
        rounds: refinement rounds used (0: the first fit was clean).
        fit_s, check_s: wall time (s) spent fitting and checking.
        bad_segment: index k of a colliding straight segment
            ``path.waypoints[k] -> path.waypoints[k + 1]``, or None.
    """

    path: GeometricPath
    check: DenseCheck
    rounds: int
    fit_s: float
    check_s: float
    bad_segment: int | None = None


def fit_spline(
    scene: PlanningScene, waypoints: np.ndarray, max_rounds: int = MAX_ROUNDS
) -> SplineFit:
    """Fit and refine until the spline through ``waypoints`` is clean."""
    points = drop_repeated(waypoints)
    fit_s = check_s = 0.0
    for rounds in range(max_rounds + 1):
        start = time.perf_counter()
        path = GeometricPath.from_waypoints(points)
        middle = time.perf_counter()
        check = check_path(scene, path)
        fit_s += middle - start
        check_s += time.perf_counter() - middle
        if check.ok or rounds == max_rounds:
            break
        assert check.s is not None  # a failed check says where
        if check.reason == "collision":
            k = _interval(path.knots, check.s)
            middle = time.perf_counter()
            segment = check_path(scene, GeometricPath.from_waypoints(points[k : k + 2]))
            check_s += time.perf_counter() - middle
            if not segment.ok:
                return SplineFit(path, check, rounds, fit_s, check_s, bad_segment=k)
        points = _refine(points, path.knots, check.s)
    return SplineFit(path, check, rounds, fit_s, check_s)


def _interval(knots: np.ndarray, s: float) -> int:
    """Index of the knot interval holding s."""
    return int(np.clip(np.searchsorted(knots, s, side="right") - 1, 0, len(knots) - 2))


def _refine(points: np.ndarray, knots: np.ndarray, s: float) -> np.ndarray:
    """Insert midpoints of the segments around parameter ``s``."""
    interval = _interval(knots, s)
    segments = range(max(0, interval - 1), min(len(points) - 1, interval + 2))
    refined = []
    for k in range(len(points)):
        refined.append(points[k])
        if k in segments:
            refined.append(0.5 * (points[k] + points[k + 1]))
    return np.array(refined)


__all__ = ["MAX_ROUNDS", "SplineFit", "fit_spline"]
