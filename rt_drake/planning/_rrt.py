"""Joint-space RRT-Connect (OMPL) and shortcutting, on a :class:`PlanningScene`.

OMPL 2.0.1's nanobind bindings: states are ``space.allocState()`` indexed
``st[i]``; a Python callable is the state validity checker; a Python
``MotionValidator`` subclass checks edges. Edges go to the Drake checker's
``CheckEdgeCollisionFree`` (C++ loop at the scene's weighted edge step, about
2 cm of motion of the farthest robot point), so OMPL's own validity
resolution is unused. ``ompl.util.RNG.setSeed`` before the planner is built
makes a query repeatable (OMPL logs an error that sampling "already
started": its seed generator is re-seeded anyway, silenced here).
"""

from __future__ import annotations

import numpy as np
from ompl import base as ob
from ompl import geometric as og
from ompl import util as ou

from rt_drake.planning.scene import PlanningScene


class _EdgeValidator(ob.MotionValidator):
    """OMPL motion validator calling the Drake checker's edge check."""

    def __init__(self, si: ob.SpaceInformation, scene: PlanningScene, n: int) -> None:
        super().__init__(si)
        self._scene = scene
        self._n = n

    def checkMotion(self, s1, s2) -> bool:  # noqa: N802 (OMPL's name)
        return self._scene.edge_free(_to_array(s1, self._n), _to_array(s2, self._n))


def _to_array(state, n: int) -> np.ndarray:
    return np.array([state[i] for i in range(n)])


def rrt_connect(
    scene: PlanningScene,
    q_start: np.ndarray,
    q_goal: np.ndarray,
    budget_s: float,
    seed: int,
) -> np.ndarray | None:
    """Collision-free joint-space polyline from q_start to q_goal, or None.

    Tries the straight edge first; otherwise OMPL RRT-Connect in the box of
    joint limits for at most ``budget_s`` seconds. Both ends must be valid.

    Returns:
        (N, n) waypoints (rad), first q_start, last q_goal; None if RRT-Connect
        found no path within the budget.
    """
    if scene.edge_free(q_start, q_goal):
        return np.array([q_start, q_goal])
    n = len(q_start)
    level = ou.getLogLevel()
    ou.setLogLevel(ou.LOG_NONE)
    try:
        ou.RNG.setSeed(int(seed) % 2_147_483_646 + 1)
        space = ob.RealVectorStateSpace(n)
        bounds = ob.RealVectorBounds(n)
        for i in range(n):
            bounds.setLow(i, float(scene.lower[i]))
            bounds.setHigh(i, float(scene.upper[i]))
        space.setBounds(bounds)
        si = ob.SpaceInformation(space)
        si.setStateValidityChecker(lambda state: scene.is_free(_to_array(state, n)))
        validator = _EdgeValidator(si, scene, n)
        si.setMotionValidator(validator)
        si.setup()
        start, goal = space.allocState(), space.allocState()
        for i in range(n):
            start[i], goal[i] = float(q_start[i]), float(q_goal[i])
        problem = ob.ProblemDefinition(si)
        problem.setStartAndGoalStates(start, goal)
        planner = og.RRTConnect(si)
        planner.setProblemDefinition(problem)
        planner.setup()
        planner.solve(max(budget_s, 1e-3))
        if not problem.hasExactSolution():
            return None
        path = problem.getSolutionPath()
        waypoints = np.array(
            [_to_array(path.getState(k), n) for k in range(path.getStateCount())]
        )
    finally:
        ou.setLogLevel(level)
    waypoints[0], waypoints[-1] = q_start, q_goal
    return waypoints


def shortcut(
    scene: PlanningScene,
    waypoints: np.ndarray,
    rng: np.random.Generator,
    attempts: int = 20,
) -> np.ndarray:
    """Shorten a collision-free polyline, keeping its ends.

    1. Vertex reduction: from each kept vertex, jump to the farthest later
       vertex joined by a free straight edge.
    2. ``attempts`` random shortcuts: two points at random fractions of the
       polyline's length, joined if the straight edge is free.
    3. Vertex reduction again.

    Deterministic for a given ``rng`` state.
    """
    path = _reduce_vertices(scene, [np.asarray(q, float) for q in waypoints])
    for _ in range(attempts):
        if len(path) < 3:
            break
        lengths = np.concatenate(
            [[0.0], np.cumsum(np.linalg.norm(np.diff(path, axis=0), axis=1))]
        )
        a, b = np.sort(rng.uniform(0.0, lengths[-1], 2))
        ia, ib = np.searchsorted(lengths, [a, b], side="right") - 1
        if ib <= ia:
            continue
        qa = _point_on(path, lengths, ia, a)
        qb = _point_on(path, lengths, ib, b)
        if scene.edge_free(qa, qb):
            path = path[: ia + 1] + [qa, qb] + path[ib + 1 :]
    return np.array(_reduce_vertices(scene, path))


def _reduce_vertices(scene: PlanningScene, path: list[np.ndarray]) -> list[np.ndarray]:
    """Keep a vertex only if the next kept one cannot be reached directly."""
    kept = [path[0]]
    i = 0
    while i < len(path) - 1:
        j = len(path) - 1
        while j > i + 1 and not scene.edge_free(path[i], path[j]):
            j -= 1
        kept.append(path[j])
        i = j
    return kept


def _point_on(path, lengths, index, length) -> np.ndarray:
    """Point at arc length ``length`` on segment ``index`` of the polyline."""
    if index >= len(path) - 1:
        return path[-1]
    span = lengths[index + 1] - lengths[index]
    t = 0.0 if span <= 0.0 else (length - lengths[index]) / span
    return path[index] + t * (path[index + 1] - path[index])


__all__ = ["rrt_connect", "shortcut"]
