"""Turning a phase's anchor configurations into a certified spline.

The steps every phase shares, in the order they are tried:

1. :func:`through`: the spline through the anchors alone (a few refinement
   rounds), certified by the dense check. Most MOVE and APPROACH queries stop
   here: no edge checks, no RRT.
2. :func:`connect`: otherwise join consecutive anchors by a straight
   joint-space edge if free, else by an IK line (cup on a straight line,
   :func:`ik_line`) where the phase asks for one, else by OMPL RRT-Connect
   plus shortcutting, within the attempt's deadline.
3. :func:`finish`: fit, refine and certify the spline through the polyline;
   a polyline segment the edge checks let through is re-planned at a finer
   edge step (``MAX_REPAIRS`` times).
"""

from __future__ import annotations

import dataclasses
import time

import numpy as np
from pydrake.math import RigidTransform, RotationMatrix

from rt_drake.planning._ik import CupIk
from rt_drake.planning._planning_errors import NoPathError
from rt_drake.planning._rrt import (
    rrt_connect,
    shortcut,
)
from rt_drake.planning._smooth import fit_spline
from rt_drake.planning.result import PlannedPath, Stopwatch
from rt_drake.planning.scene import PlanningScene
from rt_drake.types.phase import Phase

#: m, spacing of the IK waypoints along a straight cup line.
LINE_STEP = 0.05
#: refinement rounds of the optimistic spline through the anchors alone.
OPTIMISTIC_ROUNDS = 3
#: re-plans of polyline segments found colliding (edge step / 4 each time).
MAX_REPAIRS = 2


@dataclasses.dataclass
class Attempt:
    """One planning call: what it is for, its stopwatch, deadline and RNG.

    Attributes:
        phase, name: the phase and object (for messages, ``"MOVE notebook: ..."``).
        budget_s: the call's time budget (s); deadline: its end
            (``time.perf_counter()`` clock).
        seed: the planner's seed (for messages); rng: the call's generator.
        watch: stage timings.
    """

    phase: Phase
    name: str
    budget_s: float
    seed: int
    rng: np.random.Generator
    watch: Stopwatch = dataclasses.field(default_factory=Stopwatch)
    deadline: float = 0.0

    def __post_init__(self) -> None:
        self.deadline = time.perf_counter() + self.budget_s


def describe(scene: PlanningScene, q: np.ndarray, which: str) -> str:
    """``"goal configuration in collision (a with b, ...)"`` or the limits."""
    if not scene.within_limits(q):
        return f"{which} configuration outside the joint limits"
    pairs = ", ".join(scene.collisions(q)) or "closer than the checker allows"
    return f"{which} configuration in collision ({pairs})"


@dataclasses.dataclass(frozen=True)
class IkLine:
    """The outcome of :func:`ik_line`.

    Attributes:
        chain: (K + 1, n) configurations from q_start along the line (rad),
            or None if a pose on the line was unreachable.
        unreached_m: m left to the line's end at the first unreachable pose
            (0 when ``chain`` is complete).
    """

    chain: np.ndarray | None
    unreached_m: float = 0.0


def ik_line(
    ik: CupIk, q_start: np.ndarray, X_start: RigidTransform, X_goal: RigidTransform
) -> IkLine:
    """IK every ``LINE_STEP`` along the cup line X_start -> X_goal (slerped).

    Each solve is seeded and costed by the previous solution, so the chain
    stays on q_start's branch.
    """
    length = np.linalg.norm(X_goal.translation() - X_start.translation())
    steps = max(1, int(np.ceil(length / LINE_STEP)))
    quaternions = (X_start.rotation().ToQuaternion(), X_goal.rotation().ToQuaternion())
    chain = [np.asarray(q_start, float)]
    for k in range(1, steps + 1):
        t = k / steps
        R = RotationMatrix(quaternions[0].slerp(t, quaternions[1]))
        p = (1 - t) * X_start.translation() + t * X_goal.translation()
        q = ik.solve(RigidTransform(R, p), chain[-1], chain[-1])
        if q is None:
            return IkLine(None, float((1 - t) * length))
        chain.append(q)
    return IkLine(np.array(chain))


def connect(
    scene: PlanningScene,
    ik: CupIk,
    anchors: list[np.ndarray],
    attempt: Attempt,
    lines: list | None = None,
) -> np.ndarray:
    """Join consecutive anchors into a collision-free polyline.

    ``lines[k]``: (X_WC at anchor k, X_WC at anchor k + 1) for a segment the
    cup should travel in a straight line, or None.

    Raises:
        NoPathError: RRT-Connect found no path before the deadline.
    """
    watch = attempt.watch
    lines = lines or [None] * (len(anchors) - 1)
    polyline = [anchors[0]]
    for q_a, q_b, line in zip(anchors[:-1], anchors[1:], lines, strict=True):
        piece = None
        if line is not None and not scene.edge_free(q_a, q_b):
            with watch("ik"):
                chain = ik_line(ik, q_a, *line).chain
            if chain is not None:
                if np.linalg.norm(chain[-1] - q_b) < 1e-3:
                    chain[-1] = q_b
                else:
                    chain = np.vstack([chain, q_b])
                with watch("rrt"):
                    edges = zip(chain[:-1], chain[1:], strict=True)
                    if all(scene.edge_free(a, b) for a, b in edges):
                        piece = chain
        if piece is None:
            with watch("rrt"):
                seed = int(attempt.rng.integers(1, 2**31 - 1))
                budget = attempt.deadline - time.perf_counter()
                piece = rrt_connect(scene, q_a, q_b, budget, seed)
            if piece is None:
                raise NoPathError(
                    attempt.phase,
                    attempt.name,
                    f"no collision-free path found within the {attempt.budget_s:g} s "
                    f"budget (RRT-Connect, seed {attempt.seed})",
                )
            if len(piece) > 2:
                with watch("shortcut"):
                    piece = shortcut(scene, piece, attempt.rng)
        polyline.extend(piece[1:])
    return np.array(polyline)


def through(
    scene: PlanningScene,
    ik: CupIk,
    anchors: list[np.ndarray],
    X_OC: RigidTransform,
    attempt: Attempt,
    lines: list | None = None,
) -> PlannedPath:
    """The spline through the anchors if it is clean, else connect and finish."""
    fit = fit_spline(scene, np.array(anchors), OPTIMISTIC_ROUNDS)
    attempt.watch.add("spline", fit.fit_s)
    attempt.watch.add("check", fit.check_s)
    if fit.check.ok:
        return _planned(attempt, fit.path, np.array(anchors), X_OC)
    polyline = connect(scene, ik, anchors, attempt, lines)
    return finish(scene, ik, polyline, X_OC, attempt)


def finish(
    scene: PlanningScene,
    ik: CupIk,
    polyline: np.ndarray,
    X_OC: RigidTransform,
    attempt: Attempt,
) -> PlannedPath:
    """Fit the certified spline; re-plan segments the edge checks let through.

    Raises:
        NoPathError: refinement and repairs could not make the spline clean.
    """
    first = polyline
    for repair in range(MAX_REPAIRS + 1):
        fit = fit_spline(scene, polyline)
        attempt.watch.add("spline", fit.fit_s)
        attempt.watch.add("check", fit.check_s)
        if fit.check.ok:
            return _planned(attempt, fit.path, first, X_OC)
        if fit.bad_segment is None or repair == MAX_REPAIRS:
            break
        k = fit.bad_segment
        points = fit.path.waypoints
        step = scene.checker.edge_step_size()
        scene.checker.set_edge_step_size(step / 4 ** (repair + 1))
        try:
            piece = connect(scene, ik, list(points[k : k + 2]), attempt)
        finally:
            scene.checker.set_edge_step_size(step)
        polyline = np.vstack([points[:k], piece, points[k + 2 :]])
    assert fit.check.q is not None and fit.check.s is not None  # failed: where
    raise NoPathError(
        attempt.phase,
        attempt.name,
        f"the spline could not be made collision-free after {fit.rounds} "
        f"refinements ({fit.check.reason} at s = {fit.check.s:.3f}; "
        f"{describe(scene, fit.check.q, 'path')})",
    )


def _planned(attempt: Attempt, path, polyline, X_OC) -> PlannedPath:
    return PlannedPath(
        attempt.phase, attempt.name, path, polyline, X_OC, attempt.watch.timing()
    )


@dataclasses.dataclass(frozen=True)
class PhaseEnds:
    """Where a phase starts and ends, before any path joins them.

    Attributes:
        attempt: the phase's planning call (its stopwatch and RNG).
        q_start, q_goal: rad, the ends.
        X_OC: the grasp (or its flip) the phase is for.
        chain: the REACH's IK line from q_start to q_goal (None otherwise).
    """

    attempt: Attempt
    q_start: np.ndarray
    q_goal: np.ndarray
    X_OC: RigidTransform
    chain: np.ndarray | None = None


__all__ = [
    "PhaseEnds",
    "Attempt",
    "IkLine",
    "LINE_STEP",
    "MAX_REPAIRS",
    "OPTIMISTIC_ROUNDS",
    "connect",
    "describe",
    "finish",
    "ik_line",
    "through",
]
