"""Dense collision and joint-limit check of a spline, certified by clearance.

The path q(s) is sampled on a grid where no point of any robot body (tool
and carried load included) moves more than ``GRID_STEP`` between
neighbours: the motion of body b from sample k to k+1 is bounded by
``m_bk = |p_WB(k+1) - p_WB(k)| + theta_k rho_b`` (origin displacement plus
rotation angle times the body's bounding radius;
:mod:`rt_drake.dynamics.body_kinematics`). The cup is a point of the tool,
so the grid is at most ``GRID_STEP`` of cup travel.

Walking the grid, each visited sample i gets its clearance rows (signed
distance d of each pair of bodies closer than ``INFLUENCE``). A pair cannot
touch while the bound on its relative motion since sample i stays below
``SAFETY * d``, so every sample up to the first that could break a pair is
collision-free without a query (conservative advancement). Bounds:

- body a against the environment: ``sum_k m_ak``;
- robot bodies a, o (every pair the checker does not filter): the smaller
  of ``sum_k (m_ak + m_ok)`` and ``sum_j R_ao[j] |dq_j|`` (lever arms of
  the joints that move exactly one of them,
  :meth:`~rt_drake.planning._bounds.MotionBounds.pair_levers`);
- a pair not reported is at least ``INFLUENCE`` apart.

Where the clearance is smaller than a grid step the walk just visits the
next sample, so the worst case is a query at every sample.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from rt_drake.dynamics.body_kinematics import step_motion
from rt_drake.planning.scene import PlanningScene
from rt_drake.types.path import GeometricPath

#: m, largest motion of any robot point between two grid samples.
GRID_STEP = 1e-3
#: m, clearance rows are requested up to this distance.
INFLUENCE = 0.1
#: fraction of a pair's clearance a certified step may use.
SAFETY = 0.9
#: samples of the first pass that sizes the grid, per knot interval.
_PASS1_PER_INTERVAL = 40


@dataclasses.dataclass(frozen=True)
class DenseCheck:
    """Outcome of :func:`check_path`.

    Attributes:
        ok: collision-free and within the joint limits.
        s: path parameter of the first bad sample (None if ok).
        reason: ``"collision"`` or ``"joint limit"`` (None if ok).
        q: configuration at ``s`` (None if ok).
        num_samples: grid samples; num_queries: clearance queries made.
    """

    ok: bool
    s: float | None
    reason: str | None
    q: np.ndarray | None
    num_samples: int
    num_queries: int


def grid(scene: PlanningScene, path: GeometricPath, step: float = GRID_STEP):
    """Samples of ``path`` with every robot point moving at most ~``step`` (m).

    Returns:
        ``(s, q, motion)``: (N,) parameters, (N, n) configurations and the
        (N - 1, B) per-body motion bounds between neighbours.
    """
    return _grid(scene, path, step)[:3]


def _first_outside(scene: PlanningScene, q: np.ndarray) -> int | None:
    outside = np.flatnonzero(
        np.any((q < scene.lower - 1e-9) | (q > scene.upper + 1e-9), axis=1)
    )
    return int(outside[0]) if outside.size else None


def _grid(scene: PlanningScene, path: GeometricPath, step: float):
    """:func:`grid`, stopping early (s, q, None, index) if pass 1 leaves the limits."""
    m = max(200, _PASS1_PER_INTERVAL * (len(path.knots) - 1))
    s1 = np.linspace(0.0, 1.0, m)
    q1 = path.value(s1)
    outside = _first_outside(scene, q1)
    if outside is not None:
        return s1, q1, None, outside
    R, p = scene.bounds.kinematics.poses(q1)
    w1 = np.concatenate(
        [[0.0], np.cumsum(step_motion(R, p, scene.bounds.body_radius).max(axis=1))]
    )
    n = max(2, int(np.ceil(w1[-1] / step)) + 1)
    s = np.interp(np.linspace(0.0, w1[-1], n), w1, s1)
    s[0], s[-1] = 0.0, 1.0
    q = path.value(s)
    R, p = scene.bounds.kinematics.poses(q)
    return s, q, step_motion(R, p, scene.bounds.body_radius), _first_outside(scene, q)


def check_path(scene: PlanningScene, path: GeometricPath) -> DenseCheck:
    """Check ``path`` for collisions and joint limits in ``scene``'s current state."""
    s, q, motion, outside = _grid(scene, path, GRID_STEP)
    if outside is not None:
        return DenseCheck(False, s[outside], "joint limit", q[outside], len(s), 0)
    # Cumulative bounds, each row nondecreasing along the N samples: body
    # motion (B, N); per robot pair, lever-weighted joint travel and summed
    # body motion (P, N).
    moved = np.hstack([np.zeros((motion.shape[1], 1)), np.cumsum(motion, axis=0).T])
    travel = np.hstack(
        [np.zeros((q.shape[1], 1)), np.cumsum(np.abs(np.diff(q, axis=0)), axis=0).T]
    )
    first, second = np.array(scene.bounds.self_pairs, dtype=int).reshape(-1, 2).T
    body_bound = _Rows(moved)
    lever_bound = _Rows(scene.bounds.pair_levers() @ travel)
    summed_bound = _Rows(moved[first] + moved[second])
    tables = _Tables(scene)
    last = len(s) - 1
    queries = 0
    i = 0
    while True:
        clearance = scene.clearance(q[i], INFLUENCE)
        queries += 1
        distances = np.asarray(clearance.distances())
        if distances.size and distances.min() <= 0.0:
            return DenseCheck(False, s[i], "collision", q[i], len(s), queries)
        body_budget, pair_budget = tables.budgets(clearance, distances)
        pair_reach = np.maximum(
            lever_bound.last_within(i, pair_budget),
            summed_bound.last_within(i, pair_budget),
        )  # a pair holds while either of its bounds does
        reach = min(
            body_bound.last_within(i, body_budget).min(), pair_reach.min(initial=last)
        )
        if reach >= last:
            return DenseCheck(True, None, None, None, len(s), queries)
        i = max(int(reach), i + 1)


class _Rows:
    """Rows of nondecreasing bounds, searched all at once."""

    def __init__(self, rows: np.ndarray) -> None:
        self._n = rows.shape[1]
        span = float((rows[:, -1] - rows[:, 0]).max(initial=0.0)) + 1.0
        self._offsets = span * np.arange(rows.shape[0]) - rows[:, 0]
        self._flat = (rows + self._offsets[:, None]).ravel()
        self._start = self._n * np.arange(rows.shape[0])

    def last_within(self, i: int, budgets: np.ndarray) -> np.ndarray:
        """Per row, last sample k >= i with ``row[k] - row[i] <= SAFETY * budget``."""
        targets = self._flat[self._start + i] + SAFETY * budgets
        return self._flat.searchsorted(targets, side="right") - 1 - self._start


class _Tables:
    """Column and pair lookups of a scene's clearance rows (Python lists).

    A query reports ten to twenty rows: a loop over Python objects reduces
    them faster than NumPy's per-call overhead would.
    """

    def __init__(self, scene: PlanningScene) -> None:
        bounds = scene.bounds
        #: Per plant body index, its column, or -1 (not part of the robot).
        self.column = list(bounds.column_lookup)
        columns = len(bounds.bodies)
        #: ``pair[a][o]`` (either order): the index in ``self_pairs``, or -1.
        self.pair = [[-1] * columns for _ in range(columns)]
        for k, (a, o) in enumerate(bounds.self_pairs):
            self.pair[a][o] = self.pair[o][a] = k
        self.pairs = len(bounds.self_pairs)

    def budgets(self, clearance, distances: np.ndarray):
        """Distances the bounds must stay below: per body (environment), per pair.

        The smallest distance of each body's environment rows and of each
        robot pair's rows; unreported ones are at least ``INFLUENCE`` apart.
        """
        column, table = self.column, self.pair
        body = [INFLUENCE] * len(table)
        pair = [INFLUENCE] * self.pairs
        for a, o, d in zip(
            clearance.robot_indices(),
            clearance.other_indices(),
            distances.tolist(),
            strict=True,
        ):
            column_a, column_o = column[int(a)], column[int(o)]
            if column_o < 0:
                if d < body[column_a]:
                    body[column_a] = d
                continue
            k = table[column_a][column_o]
            if k < 0:
                raise ValueError("clearance row of a filtered robot pair")
            if d < pair[k]:
                pair[k] = d
        return np.array(body), np.array(pair)


__all__ = ["DenseCheck", "GRID_STEP", "INFLUENCE", "check_path", "grid"]
