"""Jerk-limited retiming: TOPP-RA first, then a sequence of LPs (totp3's scheme).

Given TOPP-RA's profile (the acceleration-limited optimum, an upper bound
on the path speed), :func:`jerk_limited` finds a profile whose path
acceleration ``u = s''`` is continuous (:mod:`._jerk_timed_path`) and whose
joint jerk stays within ``limits.jerk``, with every other limit and the
grasp rows exact at its points (:mod:`._jerk_rows`):

1. the grid is TOPP-RA's, with six points halving towards each end at rest
   (the jerk ramps up there, ``u ~ s^(1/3)``);
2. each LP maximises the first-order decrease of the duration ``T = sum
   ds / sqrt(x)`` (Simpson's rule on each segment, linearised at the
   previous profile ``xbar``: weights ``x^-1.5 / 2``), under the rows at the
   grid points (both sides for the jerk), the jerk rows linearised at
   ``xbar`` (tangent of a convex bound: every iterate keeps the jerk at
   those points), until the duration changes by less than
   :data:`CONVERGED`;
3. every limit and all grasp rows are then evaluated exactly at 9 points
   per segment, the jerk at 33 (:mod:`._jerk_points`; the grasp skipped at
   points an earlier round's check bounds under the limit,
   :mod:`._jerk_screen`); points over a limit
   by more than ``BETWEEN_TOLERANCE`` join the LPs (with every row there,
   and the violated grasp rows), and the LPs run again, at most
   :data:`MAX_ROUNDS` times; an excess still beyond the 1e-3 contract
   raises :class:`._retime_errors.LimitsBetweenGridPointsError`.

Rows screened into the LPs: grasp rows where TOPP-RA's profile used at
least :data:`SCREEN` of them (ratio ``F_r w / g_r``), acceleration and
torque rows at :data:`JOINT_SCREEN` of their limit on TOPP-RA's profile
(with a set of objects: each joint's and sign's worst object, as triples of
:mod:`._jerk_set`, and at a point over a limit those at
:data:`JOINT_SCREEN` for the profile's worst object there),
jerk rows at :data:`JOINT_SCREEN` on an LP's profile (kept once in), every
row at a dense point where step 3 finds a limit exceeded, and at a jerk
point where it does, the velocity row and the acceleration rows at
:data:`JOINT_SCREEN` there. Units: s, rad, 1/s^2 for x and u.

Each LP is made and solved by :func:`._jerk_problem.solve_lp`; the path's
continuity check is :func:`._jerk_smooth.check_smooth`. The LPs are
HiGHS's dual simplex (:mod:`._jerk_lp`): the first starts from
a basis read off TOPP-RA's profile, each next one from the last optimum's
(rows matched by key), and each takes its rows as cutting planes (those
tight at the start and those its optimum breaks). Same optima as solving
each LP whole, at a fraction of the cost.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from typing import NoReturn

import numpy as np

from rt_drake.retiming._check import DEFAULT_TOLERANCE, Margin
from rt_drake.retiming._jerk_lp import WarmLP
from rt_drake.retiming._jerk_points import (
    DENSE,
    JERK_DENSE,
    DensePoints,
    GraspRows,
    JerkPoints,
    largest_excess,
    rest_bounds,
)
from rt_drake.retiming._jerk_problem import (
    Problem,
    Selection,
    bernstein_rows,
    continuity,
    grid_caps,
    middle_rows,
    solve_lp,
    variable_bounds,
)
from rt_drake.retiming._jerk_screen import grasp_check
from rt_drake.retiming._jerk_set import SetGrasp, SetPairs
from rt_drake.retiming._jerk_smooth import check_smooth
from rt_drake.retiming._jerk_timed_path import JerkTimedPath, Piece, quadrature_duration
from rt_drake.retiming._joint_path import JointPath
from rt_drake.retiming._retime_errors import (
    LimitsBetweenGridPointsError,
    PathNotControllableError,
)
from rt_drake.retiming._samples import PathSamples
from rt_drake.retiming._set_tables import torque_columns
from rt_drake.retiming.limits import JointLimits

#: Grasp rows with at least this ratio on TOPP-RA's profile enter the LPs.
SCREEN = 0.9
#: Joint rows (acceleration, torque: on TOPP-RA's profile; jerk: on the
#: previous LP's) with at least this ratio enter the LPs.
JOINT_SCREEN = 0.5
#: Relative change of the duration that ends a sequence of LPs.
CONVERGED = 1e-3
#: LPs per sequence, at most.
MAX_LPS = 12
#: Sequences of LPs (rounds of added points), at most.
MAX_ROUNDS = 6
#: Points halving towards each end at rest.
END_POINTS = 6
#: The dense points (:data:`._jerk_points.DENSE` indices) and jerk points
#: (:data:`._jerk_points.JERK_DENSE` indices) of each segment in the first
#: round's LPs: its ends. (Taking every point there from the start saves
#: rounds but costs more than they do: ``benchmarks/bench_jerk_stopping.py``.)
FIRST_DENSE = (0, len(DENSE) - 1)
FIRST_JERK = (0, len(JERK_DENSE) - 1)


@dataclasses.dataclass(frozen=True, eq=False)
class JerkProfile:
    """A jerk-limited profile and its margins at the grid points.

    Attributes:
        trajectory: The motion (:class:`._jerk_timed_path.JerkTimedPath`).
        s: (N+1,) the grid.
        x: (N+1,) ``s'^2`` there.
        u: (N+1,) ``s''`` there.
        margins: Per limit, (N+1,) smallest relative slack at the grid
            points (the segment starting there; the last point, the end).
        lps: LPs solved.
        rounds: Sequences of LPs.
        grasp_rows: (point, row) pairs of the grasp in the last LP.
    """

    trajectory: JerkTimedPath
    s: np.ndarray
    x: np.ndarray
    u: np.ndarray
    margins: dict[Margin, np.ndarray]
    lps: int
    rounds: int
    grasp_rows: int


def jerk_limited(
    spline: JointPath,
    sample: Callable[[np.ndarray], PathSamples],
    s_topp: np.ndarray,
    x_topp: np.ndarray,
    limits: JointLimits,
    F: np.ndarray | None,
    g: np.ndarray | None,
    objects: SetGrasp | None,
    sd_start: float,
    sd_end: float,
    start_time: float,
    tolerance: float,
    *,
    sdd_start: float | None = None,
) -> JerkProfile:
    """The jerk-limited profile near TOPP-RA's ``x_topp`` (module docstring).

    Args:
        spline: The path q(s).
        sample: Path coefficients at given s (the retimer's ``sample_path``).
        s_topp: TOPP-RA's grid.
        x_topp: TOPP-RA's ``s'^2`` there (x linear in s between grid points).
        limits: Joint limits with ``jerk`` set.
        F: The grasp rows' normals (R, 6), or None.
        g: Their offsets (R,), or None.
        objects: The grasp of a set of objects (:mod:`._jerk_set`), or None
            (then F and g are None).
        sd_start: Path velocity at the start, 1/s.
        sd_end: Path velocity at the end, 1/s.
        start_time: s.
        tolerance: Relative excess that adds a point (``BETWEEN_TOLERANCE``).
        sdd_start: Path acceleration ``s''`` at the start (1/s^2), fixed
            (a stop continuing a motion); None: free.

    Raises:
        PathNotControllableError: an LP has no solution, or every LP of a
            round leaves ``s' = 0`` inside the path (naming where).
        LimitsBetweenGridPointsError: a limit still exceeded beyond the
            contract after :data:`MAX_ROUNDS` rounds.
    """
    assert limits.jerk is not None
    s = _grid(s_topp, sd_start, sd_end)
    kinds = np.full(len(s) - 1, Piece.INTERIOR, dtype=int)
    if sd_start == 0.0:
        kinds[0] = Piece.START
    if sd_end == 0.0:
        kinds[-1] = Piece.STOP
    grasp = None if F is None or g is None else GraspRows(F, g)
    dense = DensePoints.of(sample, s, kinds, grasp)
    points = JerkPoints.of(spline, s, kinds, limits.velocity)
    rest = rest_bounds(spline, s, kinds, limits.jerk)
    middle = np.flatnonzero(dense.k == len(DENSE) // 2)
    problem = Problem(
        s, kinds, dense, points, limits, rest, middle,
        middle_rows(dense.band, middle, len(s)), bernstein_rows(s, kinds),
        continuity(s, kinds),
        variable_bounds(
            s, kinds, grid_caps(dense, kinds), rest, sd_start, sd_end, sdd_start
        ),
    )  # fmt: skip
    solver = WarmLP()
    x_ref = np.interp(dense.s, s_topp, x_topp)
    u_ref = _topp_u(s_topp, x_topp, dense.s)
    active = _one_of(dense.k, FIRST_DENSE)
    rows = None
    if grasp is not None:
        # Only the active points' rows enter the LPs: screened there alone.
        rows = dense.grasp_screen(x_ref, u_ref, SCREEN, np.flatnonzero(active))[0]
    pairs = torques = None
    if objects is not None:
        assert dense.samples.wrench_set is not None
        pairs = SetPairs(dense.samples.wrench_set, objects.normals, objects.layout)
        worst = pairs.worst(x_ref, u_ref)
        assert worst.ranked is not None
        pairs.add(worst, (worst.ranked[0] >= SCREEN) & active[:, None])
        torques = _torque_pairs(dense, objects)
    if torques is not None:
        worst = torques.worst(x_ref, u_ref)
        assert worst.ranked is not None
        torques.add(worst, (worst.ranked[0] >= JOINT_SCREEN) & active[:, None])
    chosen = Selection(
        active=active,
        rows=rows,
        keep=dense.joint_ratios(x_ref, u_ref, limits).at_least(JOINT_SCREEN),
        jerk_active=_one_of(points.k, FIRST_JERK),
        pairs=pairs,
        torque_pairs=torques,
    )
    x_bar = np.maximum(np.interp(s, s_topp, x_topp), 0.0)
    x_dense = np.interp(dense.s, s, x_bar)
    x_jerk = np.interp(points.s, s, x_bar)
    solver.guess(_topp_start(s, x_bar, problem.variable_bounds))
    lps = rounds = 0
    best: tuple[float, np.ndarray, np.ndarray] | None = None  # duration, z, per joint
    # The duration of the profile the next LP is linearised at (a new round
    # starts from the last LP's: if its first LP changes it by less than
    # CONVERGED, the round is done).
    previous = np.inf
    screened = None  # the grasp check's last wrenches (_jerk_screen)
    while True:
        rounds += 1
        for _ in range(MAX_LPS):
            z = solve_lp(problem, chosen, solver, x_bar, x_dense, x_jerk)
            lps += 1
            x, u = _split(z, len(s))
            duration = quadrature_duration(s, x, u)
            if not np.isfinite(duration):  # s' = 0 between the LP's points
                chosen.active |= dense.maps.x(z) <= 0.0
                chosen.fixed = None
            per_joint = points.per_joint(z, limits)
            if np.isfinite(duration) and (best is None or duration < best[0]):
                best = (duration, z, per_joint)
            x_bar = x
            x_dense = np.maximum(dense.maps.x(z), 0.0)
            x_jerk = np.maximum(points.maps.x(z), 0.0)
            near = per_joint >= JOINT_SCREEN
            # Once in, a row stays in (dropping it again made LPs alternate).
            keep = chosen.jerk_keep
            chosen.jerk_keep = near if keep is None else keep | near
            if abs(previous - duration) <= CONVERGED * duration:
                break
            previous = duration
        if best is None:  # every LP of the round stops the motion somewhere
            _refuse_stop(dense, z)
        z = best[1]
        jerk_ratio = points.ratio(z, problem.bounds, best[2])
        x_z, u_z = dense.maps.x(z), dense.maps.u(z)
        grasp_over, grasp_max = None, None
        if grasp is not None:  # the pairs over the contract, each point's worst
            grasp_over, grasp_max, screened = grasp_check(
                dense, x_z, u_z, 1.0 + tolerance, screened
            )
        set_worst = None
        if pairs is not None:  # the set's worst object at every dense point
            set_worst = pairs.worst(x_z, u_z)
            grasp_max = set_worst.ratio
        torque_worst = None
        if torques is not None:  # every joint's worst object at every dense point
            torque_worst = torques.worst(x_z, u_z)
        ratios = dense.ratios(
            z, limits, grasp_max, None if torque_worst is None else torque_worst.ratio
        )
        excess = largest_excess(ratios)
        jerk_excess = _point_excess(problem, z, jerk_ratio)
        over, jerk_over = excess > tolerance, jerk_excess > tolerance
        if not (over.any() or jerk_over.any()) or rounds == MAX_ROUNDS:
            break
        chosen.active |= over
        chosen.keep = chosen.keep.with_full(over)
        chosen.jerk_active |= jerk_over
        # There the acceleration rows near their limit (once in, kept).
        at = np.flatnonzero(jerk_over)
        near = np.zeros(points.dq.shape, dtype=bool)
        near[at] = points.acceleration_ratio(z, limits, at) >= JOINT_SCREEN
        previous_near = chosen.jerk_acceleration
        chosen.jerk_acceleration = (
            near if previous_near is None else previous_near | near
        )
        if chosen.rows is not None and grasp_over is not None:
            chosen.rows |= grasp_over
        if pairs is not None and set_worst is not None:
            assert set_worst.ranked is not None
            pairs.add(set_worst, set_worst.ranked[0] - 1.0 > tolerance)
        if torques is not None and torque_worst is not None:
            # Where a limit was exceeded: the joints near theirs, each its
            # worst object (as one object's every torque row there).
            assert torque_worst.ranked is not None
            near = torque_worst.ranked[0] >= JOINT_SCREEN
            torques.add(torque_worst, near & over[:, None])
        chosen.fixed = None
        best = None  # the rows changed: the old optimum may break them
    _refuse(problem, excess, jerk_excess)
    x, u = _split(z, len(s))
    margins = dense.margins(ratios)
    margins[Margin.JERK] = points.margins(jerk_ratio)
    return JerkProfile(
        trajectory=JerkTimedPath(spline, s, x, u, start_time),
        s=s,
        x=x,
        u=u,
        margins=margins,
        lps=lps,
        rounds=rounds,
        grasp_rows=_grasp_rows(chosen),
    )


def _torque_pairs(dense: DensePoints, objects: SetGrasp) -> SetPairs | None:
    """The torque triples of a set of objects (None without torque limits).

    The set's torque columns at the dense points with the arm's torque on
    every box's centre (:func:`._set_tables.torque_columns`); every row
    (joint and sign) ranked at each point.
    """
    smp = dense.samples
    if objects.torque is None:
        return None
    assert smp.torque is not None and smp.torque_set is not None
    table = torque_columns(smp.torque, smp.torque_set, objects.layout)
    return SetPairs(table, objects.torque, objects.layout, objects.torque.shape[1])


def _one_of(k: np.ndarray, pair: tuple[int, int]) -> np.ndarray:
    """``np.isin(k, pair)`` for two values, without its sort."""
    return (k == pair[0]) | (k == pair[1])


def _point_excess(problem: Problem, z: np.ndarray, jerk: np.ndarray) -> np.ndarray:
    """Excess of the jerk, velocity or acceleration at the jerk points, (P,).

    ``jerk``: (P,) the largest jerk ratio there (:meth:`JerkPoints.ratio`).
    """
    return np.maximum(jerk, problem.jerk.joint_ratio(z, problem.limits)) - 1.0


def _grasp_rows(chosen: Selection) -> int:
    """(point, row) pairs of the grasp (or (point, row, vertex) of a set) in the LPs."""
    if chosen.pairs is not None:
        return len(chosen.pairs)
    if chosen.rows is None:
        return 0
    return int(np.count_nonzero(chosen.rows[chosen.active]))


def _refuse_stop(dense: DensePoints, z: np.ndarray) -> NoReturn:
    """Raise: the LPs keep ``s' = 0`` at a point inside the path.

    Every LP of a round maximises the path speed; when each of them still
    leaves ``x = s'^2 = 0`` at some point inside the path (where the limits,
    linearised at the previous profile, allow no speed), the motion would
    stop there for good: no finite-time profile was found.
    """
    x = dense.maps.x(z)
    inside = np.zeros(len(x), dtype=bool)
    inside[1:-1] = True
    stopped = inside & (x <= 1e-9 * max(float(np.max(x)), 1e-12))
    if not stopped.any():  # none exactly 0: the slowest point
        stopped = inside & (x == np.min(x[inside]))
    first, last = (float(v) for v in dense.s[stopped][[0, -1]])
    raise PathNotControllableError(
        f"jerk-limited retiming: every LP stops the motion (s' = 0) for s in "
        f"[{first:.4f}, {last:.4f}]: the limits there, with a continuous s'', "
        "leave no path speed",
        s=first,
    )


def _refuse(problem: Problem, excess: np.ndarray, jerk: np.ndarray) -> None:
    """Raise if a limit is exceeded beyond the contract at any point.

    ``excess``: (P,) the largest relative excess at the dense points;
    ``jerk``: at the jerk points (:func:`_point_excess`).
    """
    dense, points = problem.dense, problem.jerk
    worst, at = float(excess.max()), float(dense.s[int(np.argmax(excess))])
    if float(jerk.max()) > worst:
        worst, at = float(jerk.max()), float(points.s[int(np.argmax(jerk))])
    if worst > DEFAULT_TOLERANCE:
        raise LimitsBetweenGridPointsError(
            f"with jerk limits, a limit is exceeded by {100.0 * worst:.2f} % "
            f"between grid points near s = {at:.4f} after {MAX_ROUNDS} rounds "
            "of LPs",
            at,
        )


def _grid(s: np.ndarray, sd_start: float, sd_end: float) -> np.ndarray:
    """TOPP-RA's grid, at least 4 segments, with points halving towards rest ends."""
    s = np.asarray(s, dtype=float)
    while len(s) < 5:
        s = np.union1d(s, 0.5 * (s[:-1] + s[1:]))
    extra = []
    halves = 0.5 ** np.arange(1, END_POINTS + 1)
    if sd_start == 0.0:
        extra.append(s[1] * halves)
    if sd_end == 0.0:
        extra.append(1.0 - (1.0 - s[-2]) * halves)
    return np.union1d(s, np.concatenate([np.zeros(0), *extra]))


def _topp_u(s_topp: np.ndarray, x_topp: np.ndarray, at: np.ndarray) -> np.ndarray:
    """TOPP-RA's constant path acceleration on the segment holding each point."""
    u = np.diff(x_topp) / (2.0 * np.diff(s_topp))
    i = np.clip(np.searchsorted(s_topp, at, side="right") - 1, 0, len(u) - 1)
    return u[i]


def _topp_start(s: np.ndarray, x: np.ndarray, bounds: np.ndarray) -> np.ndarray:
    """TOPP-RA's profile as z: x, and u at each point the mean of its segments'."""
    u_segment = np.diff(x) / (2.0 * np.diff(s))
    u = np.concatenate(
        [[u_segment[0]], 0.5 * (u_segment[1:] + u_segment[:-1]), [u_segment[-1]]]
    )
    return np.clip(np.concatenate([x, u]), bounds[:, 0], bounds[:, 1])


def _split(z: np.ndarray, size: int) -> tuple[np.ndarray, np.ndarray]:
    """X and u from the LP variables (x clipped at 0 against rounding)."""
    return np.maximum(z[:size], 0.0), z[size:].copy()


__all__ = [
    "check_smooth",
    "CONVERGED",
    "MAX_LPS",
    "MAX_ROUNDS",
    "JerkProfile",
    "jerk_limited",
]
