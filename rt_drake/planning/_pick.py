"""The blended pick: retreat, APPROACH and REACH as one path without stops.

From q_start (home, or the place configuration of the object just released)
the cup

1. retreats vertically by ``RETREAT_HEIGHT`` when it rests on an object at
   q_start (the cup leaves the face along its normal: no scraping);
2. travels to the approach pose (the grasp raised by ``approach_offset``,
   :meth:`~._cycle_planner.CyclePlanner.approach_goal`): directly, or, if
   that blend collides between the retreat's top and the approach pose,
   along the polyline :meth:`~._cycle_planner.CyclePlanner.plan_approach`
   finds from the retreat's top;
3. descends vertically along the IK line of
   :meth:`~._cycle_planner.CyclePlanner.descent_line` to the grasp.

One clamped chord-length spline (:class:`~rt_drake.types.path.GeometricPath`) runs
through all of it, so the motion retimed on it starts and ends at rest but
keeps moving through the approach pose. A cubic through the IK line's points
can bulge off the line, most where the transit turns into the descent, so
the spline is refined until, sampled densely (``LINE_SAMPLES`` per line),
the cup stays within ``LINE_TOLERANCE_M`` (horizontal distance from the
vertical line, m) and ``LINE_TOLERANCE_RAD`` (angle of R_WC from the line's
orientation) over the whole descent and retreat: a line segment that
violates it gets the IK solution of its Cartesian midpoint; a transit
segment where the dense collision check
(:func:`~.dense_check.check_path`) fails gets its joint-space midpoint. The
whole path is checked in the REACH scene from q_start (the grasped face and
the face under the cup at q_start moved in by the touch allowance); the
approach pose and the descent line are solved and checked in that scene too.

Only the blend is certified: the APPROACH and REACH paths are not splined
and checked on their own first (the blend replaces them; they cost as much
again), except the APPROACH's when the straight transit is blocked. Where
the straight APPROACH is collision-free the pick is the one planned with
those separate checks; where it is not but the blend without transit points
is, that blend (certified like any other) is kept.
"""

from __future__ import annotations

import dataclasses
import time
from typing import Protocol

import numpy as np
from pydrake.math import RigidTransform

from rt_drake.errors import RtDrakeError
from rt_drake.model.scenario import Scenario
from rt_drake.planning._connect import (
    PhaseEnds,
    ik_line,
)
from rt_drake.planning._ik import CupIk
from rt_drake.planning._planning_errors import (
    NoPathError,
    UnreachablePoseError,
)
from rt_drake.planning.dense_check import check_path
from rt_drake.planning.result import PlannedPath, PlanTiming
from rt_drake.planning.scene import PlanningScene
from rt_drake.types.path import GeometricPath
from rt_drake.types.phase import Phase


class PickPlanner(Protocol):
    """What :func:`plan_pick` needs of its planner (a ``CyclePlanner``)."""

    scene: PlanningScene
    ik: CupIk
    scenario: Scenario

    def grasps(self, name: str) -> list[RigidTransform]:
        """The grasp ``X_OC`` of object ``name`` and its flip."""
        ...

    def prepare(
        self,
        phase: Phase,
        name: str,
        q_start: np.ndarray,
        X_OC: RigidTransform | None = None,
    ) -> PlanningScene:
        """Set the scene's objects for ``phase`` of object ``name``."""
        ...

    def approach_goal(
        self, q_current: np.ndarray, name: str, prepared: bool = False
    ) -> PhaseEnds:
        """The APPROACH's ends: from ``q_current`` to above the grasp."""
        ...

    def descent_line(
        self, q_approach: np.ndarray, name: str, prepared: bool = False
    ) -> PhaseEnds:
        """The REACH's ends along the vertical line down to the grasp."""
        ...

    def plan_approach(self, q_current: np.ndarray, name: str) -> PlannedPath:
        """The APPROACH path from ``q_current`` to above object ``name``."""
        ...


#: m, how far the cup rises vertically from an object it rests on.
RETREAT_HEIGHT = 0.02
#: m, an extra IK point this far below the approach pose (and this far below
#: the retreat's top): where the spline turns, it keeps the cup on the line.
TURN_STEP = 0.01
#: m and rad, largest horizontal offset and tilt of the cup off a line.
LINE_TOLERANCE_M = 1e-3
LINE_TOLERANCE_RAD = np.radians(0.5)
#: samples of the spline per vertical line when its deviation is measured.
LINE_SAMPLES = 200
#: refinement rounds (a point inserted per round) before giving up.
MAX_ROUNDS = 12


@dataclasses.dataclass(frozen=True)
class PlannedPick:
    """A blended pick, ready for the retimer.

    Attributes:
        path: the whole path (phase APPROACH; ``descent`` holds the IK line
            from the approach pose to the grasp, which the MOVE lifts along).
        s_retreat: path parameter at the top of the retreat (0: none).
        s_approach: path parameter at the approach pose (APPROACH ends,
            REACH begins).
        reach_timing: wall time of the descent's IK line (the REACH's plan);
            ``path.timing`` holds the rest (retreat, transit, blend).
    """

    path: PlannedPath
    s_retreat: float
    s_approach: float
    reach_timing: PlanTiming


@dataclasses.dataclass(frozen=True)
class LineDeviation:
    """How far the cup strays from a vertical line over part of a path.

    Attributes:
        offset_m: largest horizontal distance of the cup origin from the line.
        tilt_rad: largest angle between R_WC and the line's orientation.
        s: path parameter of the worst sample.
    """

    offset_m: float
    tilt_rad: float
    s: float

    @property
    def ok(self) -> bool:
        """Within ``LINE_TOLERANCE_M`` and ``LINE_TOLERANCE_RAD``."""
        return self.offset_m <= LINE_TOLERANCE_M and self.tilt_rad <= LINE_TOLERANCE_RAD


def line_deviation(
    scene: PlanningScene,
    path: GeometricPath,
    s0: float,
    s1: float,
    X_line: RigidTransform,
    samples: int = LINE_SAMPLES,
) -> LineDeviation:
    """Deviation of the cup from the vertical line through X_line, s in [s0, s1]."""
    s = np.linspace(s0, s1, samples)
    R, p = scene.cup_frames(path.value(s))
    offset = np.linalg.norm((p - X_line.translation())[:, :2], axis=1)
    # angle of R_line^T R: arccos((trace - 1) / 2)
    trace = np.einsum("ij,nij->n", X_line.rotation().matrix(), R)
    tilt = np.arccos(np.clip(0.5 * (trace - 1.0), -1.0, 1.0))
    worst = int(
        np.argmax(np.maximum(offset / LINE_TOLERANCE_M, tilt / LINE_TOLERANCE_RAD))
    )
    return LineDeviation(float(offset.max()), float(tilt.max()), float(s[worst]))


def plan_pick(
    planner: PickPlanner, q_start: np.ndarray, name: str, retreat: bool
) -> PlannedPick:
    """Retreat (if ``retreat``), approach and reach object ``name`` in one path.

    Raises:
        UnreachablePoseError: the retreat's line leaves the arm's reach.
        PlanningError: from the approach or reach planning.
        NoPathError: the blended spline could not be made clean.
    """
    start = time.perf_counter()
    q_start = np.asarray(q_start, dtype=float)
    retreat_chain = np.array([q_start])
    if retreat:
        X_start = planner.scene.cup_pose(q_start)
        X_top = RigidTransform([0.0, 0.0, RETREAT_HEIGHT]) @ X_start
        X_turn = RigidTransform([0.0, 0.0, RETREAT_HEIGHT - TURN_STEP]) @ X_start
        chain = ik_line(planner.ik, q_start, X_start, X_turn).chain
        q_top = None if chain is None else planner.ik.solve(X_top, chain[-1], chain[-1])
        if chain is None or q_top is None:
            raise UnreachablePoseError(
                Phase.APPROACH, name, "retreat pose above the placed object unreachable"
            )
        retreat_chain = np.vstack([chain, q_top])
    retreat_s = time.perf_counter() - start
    # One scene for all of it: the REACH's from q_start (the grasped face's
    # allowance does not depend on the grasp's yaw flip, about z_C).
    start = time.perf_counter()
    planner.prepare(Phase.REACH, name, q_start, planner.grasps(name)[0])
    scene_s = time.perf_counter() - start
    goal = planner.approach_goal(retreat_chain[-1], name, prepared=True)
    reach = planner.descent_line(goal.q_goal, name, prepared=True)
    assert reach.chain is not None  # descent_line always returns its line
    start = time.perf_counter()
    descent = turned_descent(planner, reach.chain)
    blend_s = time.perf_counter() - start
    approach_timing, transit = goal.attempt.watch.timing(), None
    while True:
        start = time.perf_counter()
        planner.prepare(Phase.REACH, name, q_start, reach.X_OC)
        blend = _Blend(planner, retreat_chain, transit, descent)
        try:
            path, s_retreat, s_approach = blend.refine(name)
            blend_s += time.perf_counter() - start
            break
        except (_TransitBlocked, NoPathError):
            if transit is not None:
                raise
        # The straight transit is blocked: the APPROACH's own path from the
        # retreat's top (its spline, else its connected polyline) joins in.
        blend_s += time.perf_counter() - start
        approach = planner.plan_approach(retreat_chain[-1], name)
        approach_timing, transit = approach.timing, approach.polyline[1:-1]
    timing = dataclasses.replace(
        approach_timing,
        scene_s=approach_timing.scene_s + scene_s,
        ik_s=approach_timing.ik_s + retreat_s,
        check_s=approach_timing.check_s + blend_s,
    )
    planned = PlannedPath(
        Phase.APPROACH,
        name,
        path,
        path.waypoints,
        reach.X_OC,
        timing,
        descent=blend.descent(),
    )
    reach_timing = reach.attempt.watch.timing()
    return PlannedPick(planned, s_retreat, s_approach, reach_timing)


def turned_descent(planner: PickPlanner, chain: np.ndarray) -> np.ndarray:
    """The descent's IK line ``chain`` with a point ``TURN_STEP`` below its top.

    The IK solution (seeded by the top, ``chain[0]``) of the approach pose
    lowered by ``TURN_STEP`` along world z, inserted after the top: where
    the spline turns into the line, it keeps the cup on it. ``chain`` as it
    is if the line is not longer than ``TURN_STEP`` or that pose has no
    solution.
    """
    X_approach = planner.scene.cup_pose(chain[0])
    q_turn = planner.ik.solve(
        RigidTransform([0.0, 0.0, -TURN_STEP]) @ X_approach, chain[0], chain[0]
    )
    line = (
        X_approach.translation()[2] - planner.scene.cup_pose(chain[-1]).translation()[2]
    )
    if q_turn is not None and TURN_STEP < line:
        return np.vstack([chain[:1], [q_turn], chain[1:]])
    return chain


class _TransitBlocked(RtDrakeError):
    """The blend without transit points collides between retreat and descent.

    Caught inside :func:`plan_pick` (it then plans the APPROACH's own path);
    an :class:`~rt_drake.errors.RtDrakeError` like every error the package
    defines.
    """


class _Blend:
    """The waypoints of a blended pick and which segments lie on a line.

    ``transit`` None: no points between the retreat's top and the approach
    pose, and no path there certified yet; a collision there raises
    :class:`_TransitBlocked` instead of refining.
    """

    def __init__(
        self,
        planner: PickPlanner,
        retreat: np.ndarray,
        transit: np.ndarray | None,
        descent: np.ndarray,
    ) -> None:
        self._planner = planner
        self._straight = transit is None
        transit = np.empty((0, len(descent[0]))) if transit is None else transit
        self._points = [*retreat, *transit, *descent]
        # Per point: 0 on the retreat line, 2 on the descent line, 1 between.
        self._line = [0] * len(retreat) + [1] * len(transit) + [2] * len(descent)
        self._has_retreat = len(retreat) > 1
        scene = planner.scene
        self._X_retreat = scene.cup_pose(retreat[0])
        self._X_grasp = scene.cup_pose(descent[-1])

    def descent(self) -> np.ndarray:
        """The descent line's configurations (approach pose to grasp)."""
        return np.array(
            [q for q, k in zip(self._points, self._line, strict=True) if k == 2]
        )

    def _index(self, line: int, last: bool) -> int:
        indices = [i for i, k in enumerate(self._line) if k == line]
        return indices[-1] if last else indices[0]

    def refine(self, name: str) -> tuple[GeometricPath, float, float]:
        """The clean spline, s at the retreat's top and s at the approach pose."""
        scene = self._planner.scene
        for _ in range(MAX_ROUNDS + 1):
            path = GeometricPath.from_waypoints(np.array(self._points))
            s_top = float(path.knots[self._index(0, last=True)])
            s_approach = float(path.knots[self._index(2, last=False)])
            lines = [(s_approach, 1.0, self._X_grasp)]
            if self._has_retreat:
                lines.append((0.0, s_top, self._X_retreat))
            bad = [line_deviation(scene, path, *line) for line in lines]
            bad = [d for d in bad if not d.ok]
            if bad:
                self._insert(path, bad[0].s)
                continue
            check = check_path(scene, path)
            if check.ok:
                return path, s_top if self._has_retreat else 0.0, s_approach
            assert check.s is not None
            between = s_top < check.s < s_approach
            if self._straight and check.reason == "collision" and between:
                raise _TransitBlocked
            self._insert(path, check.s)
        raise NoPathError(
            Phase.APPROACH,
            name,
            f"the blended approach and reach could not be made clean in {MAX_ROUNDS} "
            "refinements",
        )

    def _insert(self, path: GeometricPath, s: float) -> None:
        """Add a point in the segment holding s: on the line, or its joint midpoint."""
        k = int(np.clip(np.searchsorted(path.knots, s, side="right") - 1, 0, None))
        k = min(k, len(self._points) - 2)
        q_a, q_b = self._points[k], self._points[k + 1]
        line = self._line[k] if self._line[k] == self._line[k + 1] else 1
        q_mid = 0.5 * (q_a + q_b)
        if line != 1:
            scene = self._planner.scene
            X_a, X_b = scene.cup_pose(q_a), scene.cup_pose(q_b)
            X_mid = RigidTransform(
                X_a.rotation(), 0.5 * (X_a.translation() + X_b.translation())
            )
            solved = self._planner.ik.solve(X_mid, q_a, q_mid)
            q_mid = q_mid if solved is None else solved
        self._points.insert(k + 1, q_mid)
        self._line.insert(k + 1, line)


__all__ = [
    "LINE_SAMPLES",
    "LINE_TOLERANCE_M",
    "LINE_TOLERANCE_RAD",
    "LineDeviation",
    "PlannedPick",
    "RETREAT_HEIGHT",
    "TURN_STEP",
    "line_deviation",
    "plan_pick",
    "turned_descent",
]
