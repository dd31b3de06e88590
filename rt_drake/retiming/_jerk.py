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
   per segment, the jerk at 33 (:mod:`._jerk_points`); points over a limit
   by more than ``BETWEEN_TOLERANCE`` join the LPs (with every row there,
   and the violated grasp rows), and the LPs run again, at most
   :data:`MAX_ROUNDS` times; an excess still beyond the 1e-3 contract
   raises :class:`._retime_errors.LimitsBetweenGridPointsError`.

Rows screened into the LPs: grasp rows where TOPP-RA's profile used at
least :data:`SCREEN` of them (ratio ``F_r w / g_r``), acceleration and
torque rows at :data:`JOINT_SCREEN` of their limit on TOPP-RA's profile,
jerk rows at :data:`JOINT_SCREEN` on an LP's profile (kept once in), every
row at a dense point where step 3 finds a limit exceeded, and at a jerk
point where it does, the velocity row and the acceleration rows at
:data:`JOINT_SCREEN` there. Units: s, rad, 1/s^2 for x and u.

The LPs are HiGHS's dual simplex (:mod:`._jerk_lp`): the first starts from
a basis read off TOPP-RA's profile, each next one from the last optimum's
(rows matched by key), and each takes its rows as cutting planes (those
tight at the start and those its optimum breaks). Same optima as solving
each LP whole, at a fraction of the cost.
"""

from __future__ import annotations

import dataclasses
import enum
from collections.abc import Callable
from typing import NoReturn

import numpy as np
from scipy import sparse

from rt_drake.retiming._check import DEFAULT_TOLERANCE, Margin
from rt_drake.retiming._jerk_lp import WarmLP
from rt_drake.retiming._jerk_points import (
    DENSE,
    JERK_DENSE,
    DensePoints,
    GraspRows,
    JerkPoints,
    Keep,
    largest_excess,
    rest_bounds,
)
from rt_drake.retiming._jerk_rows import (
    KIND_SHIFT,
    Rows,
    affine_rows,
    jerk_rows,
    key,
    stacked,
)
from rt_drake.retiming._jerk_set import SetGrasp, SetPairs
from rt_drake.retiming._jerk_timed_path import JerkTimedPath, Piece, quadrature_duration
from rt_drake.retiming._joint_path import JointPath
from rt_drake.retiming._retime_errors import (
    LimitsBetweenGridPointsError,
    PathNotControllableError,
    RetimeInputError,
)
from rt_drake.retiming._samples import PathSamples
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


class _Kind(enum.IntEnum):
    """The kinds of LP rows, for their keys (a sign's rows: kind and kind + 1)."""

    VELOCITY = 0
    POSITIVE = 1
    ACCELERATION = 2
    TORQUE = 4
    GRASP = 6
    JERK = 7
    JERK_POINT_ACCELERATION = 9
    JERK_POINT_VELOCITY = 11
    MIDDLE = 12
    BERNSTEIN = 13


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


@dataclasses.dataclass(frozen=True, eq=False)
class _Problem:
    """What the LPs are built from (fixed for one retime)."""

    s: np.ndarray
    kinds: np.ndarray
    dense: DensePoints
    jerk: JerkPoints
    limits: JointLimits
    bounds: dict[int, tuple[int, float]]
    middle: np.ndarray
    X_middle: sparse.csr_matrix
    bernstein: Rows
    equalities: tuple[sparse.csr_matrix, np.ndarray]
    variable_bounds: np.ndarray


@dataclasses.dataclass
class _Selection:
    """Which points and rows the next LP takes (grows between rounds)."""

    active: np.ndarray
    rows: np.ndarray | None
    keep: Keep
    jerk_active: np.ndarray
    jerk_keep: np.ndarray | None = None
    jerk_acceleration: np.ndarray | None = None
    pairs: SetPairs | None = None
    #: The LP rows other than the jerk's (:func:`_fixed_rows`), while the
    #: selection is unchanged; None: to be made.
    fixed: tuple[list[Rows], list[Rows]] | None = None


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
    problem = _Problem(
        s, kinds, dense, points, limits, rest, middle, dense.maps.X[middle],
        _bernstein(s, kinds), _continuity(s, kinds),
        _bounds(s, kinds, rest, sd_start, sd_end, sdd_start),
    )  # fmt: skip
    solver = WarmLP()
    x_ref = np.interp(dense.s, s_topp, x_topp)
    u_ref = _topp_u(s_topp, x_topp, dense.s)
    active = np.isin(dense.k, (0, len(DENSE) - 1))
    rows = None
    if grasp is not None:
        # Only the active points' rows enter the LPs: screened there alone.
        rows = dense.grasp_screen(x_ref, u_ref, SCREEN, np.flatnonzero(active))[0]
    pairs = None
    if objects is not None:
        assert dense.samples.wrench_set is not None
        pairs = SetPairs(dense.samples.wrench_set, objects.normals, objects.layout)
        worst = pairs.worst(x_ref, u_ref)
        assert worst.ranked is not None
        pairs.add(worst, (worst.ranked[0] >= SCREEN) & active[:, None])
    chosen = _Selection(
        active=active,
        rows=rows,
        keep=dense.joint_ratios(x_ref, u_ref, limits).at_least(JOINT_SCREEN),
        jerk_active=np.isin(points.k, (0, len(JERK_DENSE) - 1)),
        pairs=pairs,
    )
    x_bar = np.maximum(np.interp(s, s_topp, x_topp), 0.0)
    x_dense = np.interp(dense.s, s, x_bar)
    x_jerk = np.interp(points.s, s, x_bar)
    solver.guess(_topp_start(s, x_bar, problem.variable_bounds))
    lps = rounds = 0
    best: tuple[float, np.ndarray] | None = None
    # The duration of the profile the next LP is linearised at (a new round
    # starts from the last LP's: if its first LP changes it by less than
    # CONVERGED, the round is done).
    previous = np.inf
    while True:
        rounds += 1
        for _ in range(MAX_LPS):
            z = _solve(problem, chosen, solver, x_bar, x_dense, x_jerk)
            lps += 1
            x, u = _split(z, len(s))
            duration = quadrature_duration(s, x, u)
            if not np.isfinite(duration):  # s' = 0 between the LP's points
                chosen.active |= dense.maps.X @ z <= 0.0
                chosen.fixed = None
            if np.isfinite(duration) and (best is None or duration < best[0]):
                best = (duration, z)
            x_bar = x
            x_dense = np.maximum(dense.maps.X @ z, 0.0)
            x_jerk = np.maximum(points.maps.X @ z, 0.0)
            near = points.per_joint(z, limits) >= JOINT_SCREEN
            # Once in, a row stays in (dropping it again made LPs alternate).
            keep = chosen.jerk_keep
            chosen.jerk_keep = near if keep is None else keep | near
            if abs(previous - duration) <= CONVERGED * duration:
                break
            previous = duration
        if best is None:  # every LP of the round stops the motion somewhere
            _refuse_stop(dense, z)
        z = best[1]
        x_z, u_z = dense.maps.X @ z, dense.maps.U @ z
        grasp_over, grasp_max = None, None
        if grasp is not None:  # the pairs over the contract, each point's worst
            grasp_over, grasp_max = dense.grasp_screen(x_z, u_z, 1.0 + tolerance)
        set_worst = None
        if pairs is not None:  # the set's worst object at every dense point
            set_worst = pairs.worst(x_z, u_z)
            grasp_max = set_worst.ratio
        ratios = dense.ratios(z, limits, grasp_max)
        excess, jerk_excess = largest_excess(ratios), _point_excess(problem, z)
        over, jerk_over = excess > tolerance, jerk_excess > tolerance
        if not (over.any() or jerk_over.any()) or rounds == MAX_ROUNDS:
            break
        chosen.active |= over
        chosen.keep = chosen.keep.with_full(over)
        chosen.jerk_active |= jerk_over
        # There the acceleration rows near their limit (once in, kept).
        near = points.acceleration_ratio(z, limits) >= JOINT_SCREEN
        near &= jerk_over[:, None]
        previous_near = chosen.jerk_acceleration
        chosen.jerk_acceleration = (
            near if previous_near is None else previous_near | near
        )
        if chosen.rows is not None and grasp_over is not None:
            chosen.rows |= grasp_over
        if pairs is not None and set_worst is not None:
            assert set_worst.ranked is not None
            pairs.add(set_worst, set_worst.ranked[0] - 1.0 > tolerance)
        chosen.fixed = None
        best = None  # the rows changed: the old optimum may break them
    _refuse(problem, excess, jerk_excess)
    x, u = _split(z, len(s))
    margins = dense.margins(ratios)
    margins[Margin.JERK] = points.margins(z, limits, problem.bounds)
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


def _taylor(
    spline: JointPath, s: np.ndarray, order: int, h: float, third: np.ndarray
) -> np.ndarray:
    """``q^(order)(s + h)`` by Taylor's series at ``s`` up to ``third`` = q'''(s).

    ``q'(s) + h q''(s) + h^2 / 2 q'''(s)`` for order 1, ``q''(s) + h
    q'''(s)`` for order 2: exact inside a cubic piece.
    """
    value = spline(s, order)
    if order == 1:
        return value + h * spline(s, 2) + 0.5 * h * h * third
    return value + h * third


def check_smooth(spline: JointPath) -> None:
    """Refuse a path whose q' or q'' jumps at a break.

    There the joint acceleration ``q' s'' + q'' s'^2`` jumps unless the
    motion stops, so no jerk limit can hold; the motion's pieces
    (:mod:`._jerk_timed_path`) stop only at the ends.

    Raises:
        RetimeInputError: naming the joint, the jump and s.
    """
    inner = spline.breaks[1:-1]
    if not inner.size:
        return
    step = 1e-9
    third = {side: spline(inner + side * step, 3) for side in (-1.0, 1.0)}
    for order in (1, 2):
        # Each side extrapolated to the break by its Taylor series up to the
        # third derivative (exact inside a cubic piece), so that a steep but
        # continuous q' or q'' (a short spline piece) is no jump: with the
        # next derivative alone, a last piece 3e-7 of the path long made q'
        # "jump" by 6e-6 (the step^2 / 2 q''' term left out).
        right, left = (
            _taylor(spline, inner + side * step, order, -side * step, third[side])
            for side in (1.0, -1.0)
        )
        jump = right - left
        scale = max(1.0, float(np.max(np.abs(spline(spline.breaks, order)))))
        if np.max(np.abs(jump)) > 1e-6 * scale:
            i, j = np.unravel_index(int(np.argmax(np.abs(jump))), jump.shape)
            name = "q'" if order == 1 else "q''"
            raise RetimeInputError(
                f"jerk limits need a path with continuous q' and q'': {name} of "
                f"joint {j + 1} jumps by {jump[i, j]:.4g} at s = {inner[i]:.4f} "
                "(a break of the path), where the joint acceleration would jump; "
                "give waypoints (the clamped cubic spline) or retime without "
                "jerk limits",
                s=float(inner[i]),
            )


def _point_excess(problem: _Problem, z: np.ndarray) -> np.ndarray:
    """Excess of the jerk, velocity or acceleration at the jerk points, (P,)."""
    points = problem.jerk
    ratio = points.ratio(z, problem.limits, problem.bounds)
    return np.maximum(ratio, points.joint_ratio(z, problem.limits)) - 1.0


def _grasp_rows(chosen: _Selection) -> int:
    """(point, row) pairs of the grasp (or (point, row, vertex) of a set) in the LPs."""
    if chosen.pairs is not None:
        return len(chosen.pairs)
    return 0 if chosen.rows is None else int(chosen.rows[chosen.active].sum())


def _refuse_stop(dense: DensePoints, z: np.ndarray) -> NoReturn:
    """Raise: the LPs keep ``s' = 0`` at a point inside the path.

    Every LP of a round maximises the path speed; when each of them still
    leaves ``x = s'^2 = 0`` at some point inside the path (where the limits,
    linearised at the previous profile, allow no speed), the motion would
    stop there for good: no finite-time profile was found.
    """
    x = dense.maps.X @ z
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


def _refuse(problem: _Problem, excess: np.ndarray, jerk: np.ndarray) -> None:
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


def _solve(
    problem: _Problem,
    chosen: _Selection,
    solver: WarmLP,
    x_bar: np.ndarray,
    x_dense: np.ndarray,
    x_jerk: np.ndarray,
) -> np.ndarray:
    """One LP (module docstring, step 2): z = [x, u].

    ``x_bar``, ``x_dense``, ``x_jerk``: the previous profile at the grid,
    dense and jerk points. Only the jerk rows and the objective change from
    one LP of a round to the next: the other rows (:func:`_fixed_rows`) are
    kept in ``chosen.fixed`` until the selection changes.
    """
    limits, points = problem.limits, problem.jerk
    assert limits.jerk is not None
    s, size = problem.s, len(problem.s)
    if chosen.fixed is None:
        chosen.fixed = _fixed_rows(problem, chosen)
    before, after = chosen.fixed
    index = np.flatnonzero(chosen.jerk_active & points.inner)
    floor = 1e-6 * max(float(np.max(x_jerk)), 1e-12)
    jerk_keep = np.ones((len(index), len(limits.jerk)), dtype=bool)
    if chosen.jerk_keep is not None:  # rows near the limit (where exceeded too)
        jerk_keep = chosen.jerk_keep[index]
    jerk = jerk_rows(
        points.band.take(index), index, _Kind.JERK, points.dq[index],
        points.ddq[index], points.dddq[index],
        np.maximum(x_jerk, floor)[index], limits.jerk, jerk_keep,
    )  # fmt: skip
    ds = np.diff(s)
    # Simpson's rule on each segment: T = sum ds / sqrt(x) at its ends and
    # middle, linearised at the previous profile (d/dx x^-1/2 = -x^-1.5 / 2).
    middle = problem.middle
    scale = max(float(np.max(x_bar)), 1e-12)
    x_middle = np.maximum(x_dense[middle], 1e-3 * scale)
    width = (np.append(ds, 0.0) + np.insert(ds, 0, 0.0)) / 6.0
    weight = -problem.X_middle.T @ (4.0 / 6.0 * ds / (2.0 * x_middle**1.5))
    weight[:size] -= width / (2.0 * np.maximum(x_bar, 1e-3 * scale) ** 1.5)
    A_ub, b_ub, keys = stacked([*before, jerk, *after], 2 * size)
    kind = keys >> KIND_SHIFT
    always = (kind == _Kind.VELOCITY) | (kind == _Kind.POSITIVE)
    always |= (kind == _Kind.MIDDLE) | (kind == _Kind.BERNSTEIN)
    z, status = solver.solve(
        weight / np.max(np.abs(weight)), A_ub, b_ub, keys, *problem.equalities,
        problem.variable_bounds, always,
    )  # fmt: skip
    if z is None:
        raise PathNotControllableError(
            f"jerk-limited retiming: no admissible profile ({status})", s=0.0
        )
    return z


def _fixed_rows(problem: _Problem, chosen: _Selection) -> tuple[list[Rows], list[Rows]]:
    """The LP rows other than the jerk's: those before them, those after.

    They depend on the selection alone, not on the previous profile. The
    rows at the dense points are taken once per point: at the end of a
    segment only where it is not the next one's start (or where a limit was
    exceeded). After the jerk rows: the velocity and acceleration rows at
    jerk points where a limit was exceeded, ``x >= 0`` in the middle of
    each segment and all along it.
    """
    limits, dense, points = problem.limits, problem.dense, problem.jerk
    last = len(DENSE) - 1
    repeated = (dense.k == last) & (np.arange(len(dense.s)) < len(dense.s) - 1)
    once = np.flatnonzero(chosen.active & (~repeated | chosen.keep.full))
    band = dense.band.take(once)
    smp = dense.samples
    dq, ddq = smp.dq[once], smp.ddq[once]
    blocks: list[Rows] = []

    def add(kind: int, alpha: np.ndarray, beta: np.ndarray, bound: np.ndarray) -> None:
        blocks.append(affine_rows(band, once, kind, alpha, beta, bound))

    zeros = np.zeros((len(once), 1))
    add(_Kind.VELOCITY, zeros, zeros + 1.0, smp.x_cap[once][:, None])
    inside = ((dense.k[once] > 0) & (dense.k[once] < last))[:, None]
    add(_Kind.POSITIVE, zeros, zeros - 1.0, np.where(inside, 0.0, np.inf))  # x >= 0
    keep = chosen.keep
    acceleration = np.where(keep.acceleration[once], limits.acceleration, np.inf)
    for sign, offset in ((1.0, 0), (-1.0, 1)):
        add(_Kind.ACCELERATION + offset, sign * dq, sign * ddq, acceleration)
        if smp.torque is not None and limits.torque is not None:
            assert keep.torque is not None
            a, b, c = (v[once] for v in smp.torque)
            bound = np.where(keep.torque[once], limits.torque - sign * c, np.inf)
            add(_Kind.TORQUE + offset, sign * a, sign * b, bound)
    if chosen.rows is not None and dense.grasp is not None and smp.wrench is not None:
        blocks.append(_grasp_rows_at(dense, once, chosen.rows[once]))
    if chosen.pairs is not None and len(chosen.pairs):
        blocks.append(chosen.pairs.rows(dense.band, once, _Kind.GRASP))
    after: list[Rows] = []
    added = np.flatnonzero(chosen.jerk_active)
    near = chosen.jerk_acceleration
    if near is None:
        near = np.zeros(points.dq.shape, dtype=bool)
    added = added[~np.isin(points.k[added], (0, len(JERK_DENSE) - 1))]
    if added.size:  # where a limit was exceeded: velocity, acceleration too
        extra = points.band.take(added)
        for sign, offset in ((1.0, 0), (-1.0, 1)):
            after.append(
                affine_rows(
                    extra, added, _Kind.JERK_POINT_ACCELERATION + offset,
                    sign * points.dq[added], sign * points.ddq[added],
                    np.where(near[added], limits.acceleration, np.inf),
                )
            )  # fmt: skip
        zeros = np.zeros((added.size, 1))
        after.append(
            affine_rows(
                extra, added, _Kind.JERK_POINT_VELOCITY, zeros, zeros + 1.0,
                points.x_cap[added][:, None],
            )
        )  # fmt: skip
    middle = problem.middle
    zeros = np.zeros((len(middle), 1))
    after.append(  # x >= 0 in the middle of each segment
        affine_rows(
            dense.band.take(middle), middle, _Kind.MIDDLE, zeros, zeros - 1.0, zeros
        )
    )
    after.append(problem.bernstein)  # x >= 0 all along each segment
    return blocks, after


def _grasp_rows_at(dense: DensePoints, once: np.ndarray, mask: np.ndarray) -> Rows:
    """Grasp rows ``F_r (a u + b x) <= g_r - F_r c`` of the (point, row) pairs ``mask``.

    ``once``: (P,) dense points; ``mask``: (P, R). Only the pairs asked for
    are made (an LP takes a few percent of them); in the order of
    :func:`._jerk_rows.affine_rows` (point-major).
    """
    assert dense.grasp is not None and dense.samples.wrench is not None
    p, r = np.nonzero(mask)
    at = once[p]
    a, b, c = (v[at] for v in dense.samples.wrench)
    F = dense.grasp.F[r]
    alpha = np.einsum("ij,ij->i", a, F)[:, None]
    beta = np.einsum("ij,ij->i", b, F)[:, None]
    band = dense.band
    return Rows(
        band.cols[at],
        alpha * band.U[at] + beta * band.X[at],
        dense.grasp.g[r] - np.einsum("ij,ij->i", c, F),
        key(_Kind.GRASP, at, r),
    )


def _bernstein(s: np.ndarray, kinds: np.ndarray) -> Rows:
    """Rows ``-(x_i + ds_i u_i) <= 0`` of the interior segments.

    ``x(sigma)`` on segment i is the quadratic with Bernstein coefficients
    ``x_i``, ``x_i + ds_i u_i``, ``x_{i+1}``: the middle one >= 0 (and the
    ends >= 0, > 0 in the interior of the path) keeps x > 0 all along it,
    so the motion never stops inside a segment.
    """
    size = len(s)
    inner = np.flatnonzero(kinds == Piece.INTERIOR)
    values = np.zeros((len(inner), 3))
    values[:, 0], values[:, 1] = -1.0, -np.diff(s)[inner]
    return Rows(
        np.column_stack([inner, size + inner, size + inner + 1]),
        values,
        np.zeros(len(inner)),
        key(_Kind.BERNSTEIN, inner, np.zeros(len(inner), dtype=int)),
    )


def _bounds(
    s: np.ndarray,
    kinds: np.ndarray,
    rest: dict[int, tuple[int, float]],
    sd_start: float,
    sd_end: float,
    sdd_start: float | None = None,
) -> np.ndarray:
    """Bounds of z: x >= 0, the ends' x, ``u_0`` if given, the end pieces' u."""
    size = len(s)
    lower = np.full(2 * size, -np.inf)
    upper = np.full(2 * size, np.inf)
    lower[:size] = 0.0
    lower[0] = upper[0] = float(sd_start) ** 2
    lower[size - 1] = upper[size - 1] = float(sd_end) ** 2
    if sdd_start is not None:  # u_0 given (sd_start > 0: no START piece)
        lower[size] = upper[size] = float(sdd_start)
    for segment, (variable, most) in rest.items():
        if kinds[segment] == Piece.START:  # u_0 = 0, 0 <= u_1 <= most
            lower[size] = upper[size] = 0.0
            lower[variable], upper[variable] = 0.0, most
        else:  # u_N = 0, -most <= u_{N-1} <= 0
            lower[2 * size - 1] = upper[2 * size - 1] = 0.0
            lower[variable], upper[variable] = -most, 0.0
    return np.column_stack([lower, upper])


def _continuity(
    s: np.ndarray, kinds: np.ndarray
) -> tuple[sparse.csr_matrix, np.ndarray]:
    """``x_{i+1} - x_i - ds_i (u_i + u_{i+1}) = 0`` (and the rest pieces' relations)."""
    size = len(s)
    ds = np.diff(s)
    i = np.arange(len(kinds))
    # Interior: x_{i+1}, x_i, u_i, u_{i+1}; the rest pieces use two of them.
    c = np.column_stack([i + 1, i, size + i, size + i + 1])
    v = np.column_stack([np.ones_like(ds), -np.ones_like(ds), -ds, -ds])
    start, stop = kinds == Piece.START, kinds == Piece.STOP
    v[start] = np.column_stack(
        [np.ones(start.sum()), 0 * ds[start], 0 * ds[start], -1.5 * ds[start]]
    )  # x_1 = 1.5 ds u_1
    v[stop] = np.column_stack(
        [0 * ds[stop], np.ones(stop.sum()), 1.5 * ds[stop], 0 * ds[stop]]
    )  # x_{N-1} = -1.5 ds u_{N-1}
    r = np.repeat(i, 4)
    c, v = c.ravel(), v.ravel()
    A = sparse.csr_matrix((v, (r, c)), shape=(len(kinds), 2 * size))
    return A, np.zeros(len(kinds))


__all__ = [
    "check_smooth",
    "CONVERGED",
    "MAX_LPS",
    "MAX_ROUNDS",
    "JerkProfile",
    "jerk_limited",
]
