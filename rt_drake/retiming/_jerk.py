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
jerk rows at :data:`JOINT_SCREEN` on an LP's profile (kept once in), and
every row where step 3 finds a limit exceeded. Units: s, rad, 1/s^2 for x
and u.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

import numpy as np
from scipy import sparse
from scipy.optimize import linprog

from rt_drake.retiming._check import DEFAULT_TOLERANCE, Margin
from rt_drake.retiming._jerk_points import (
    DENSE,
    JERK_DENSE,
    DensePoints,
    GraspRows,
    JerkPoints,
    Keep,
    rest_bounds,
)
from rt_drake.retiming._jerk_rows import PointMaps, affine_rows, jerk_rows
from rt_drake.retiming._jerk_timed_path import JerkTimedPath, Piece
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
    sd_start: float
    sd_end: float


@dataclasses.dataclass
class _Selection:
    """Which points and rows the next LP takes (grows between rounds)."""

    active: np.ndarray
    rows: np.ndarray | None
    keep: Keep
    jerk_active: np.ndarray
    jerk_keep: np.ndarray | None = None


def jerk_limited(
    spline: JointPath,
    sample: Callable[[np.ndarray], PathSamples],
    s_topp: np.ndarray,
    x_topp: np.ndarray,
    limits: JointLimits,
    F: np.ndarray | None,
    g: np.ndarray | None,
    sd_start: float,
    sd_end: float,
    start_time: float,
    tolerance: float,
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
        sd_start: Path velocity at the start, 1/s.
        sd_end: Path velocity at the end, 1/s.
        start_time: s.
        tolerance: Relative excess that adds a point (``BETWEEN_TOLERANCE``).

    Raises:
        PathNotControllableError: an LP has no solution.
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
    problem = _Problem(
        s, kinds, dense, points, limits, rest_bounds(spline, s, kinds, limits.jerk),
        sd_start, sd_end,
    )  # fmt: skip
    x_ref = np.interp(dense.s, s_topp, x_topp)
    u_ref = _topp_u(s_topp, x_topp, dense.s)
    active = np.isin(dense.k, (0, len(DENSE) - 1))
    rows = None
    if grasp is not None:
        rows = (dense.grasp_ratio(x_ref, u_ref) >= SCREEN) & active[:, None]
    chosen = _Selection(
        active=active,
        rows=rows,
        keep=dense.joint_ratios(x_ref, u_ref, limits).at_least(JOINT_SCREEN),
        jerk_active=np.isin(points.k, (0, len(JERK_DENSE) - 1)),
    )
    x_bar = np.maximum(np.interp(s, s_topp, x_topp), 0.0)
    x_dense = np.interp(dense.s, s, x_bar)
    x_jerk = np.interp(points.s, s, x_bar)
    lps = rounds = 0
    best: tuple[float, np.ndarray] | None = None
    while True:
        rounds += 1
        previous = np.inf
        for _ in range(MAX_LPS):
            z = _solve(problem, chosen, x_bar, x_dense, x_jerk)
            lps += 1
            x, u = _split(z, len(s))
            try:
                duration = JerkTimedPath(spline, s, x, u).duration
            except RetimeInputError:  # s' = 0 between the LP's points
                duration = np.inf
                chosen.active |= dense.maps.X @ z <= 0.0
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
        if best is None:  # every LP's profile stopped (s' = 0) short of the end
            raise PathNotControllableError(
                "jerk-limited retiming: every profile found stops on the path "
                "(s' = 0 between grid points)"
            )
        z = best[1]
        over = dense.excess(z, limits) > tolerance
        jerk_over = _point_excess(problem, z) > tolerance
        if not (over.any() or jerk_over.any()) or rounds == MAX_ROUNDS:
            break
        chosen.active |= over
        chosen.keep = chosen.keep.with_full(over)
        chosen.jerk_active |= jerk_over
        if chosen.rows is not None:
            chosen.rows |= dense.grasp_excess(z) > tolerance
        best = None  # the rows changed: the old optimum may break them
    _refuse(problem, z)
    x, u = _split(z, len(s))
    margins = dense.margins(z, limits)
    margins[Margin.JERK] = points.margins(z, limits, problem.bounds)
    return JerkProfile(
        trajectory=JerkTimedPath(spline, s, x, u, start_time),
        s=s,
        x=x,
        u=u,
        margins=margins,
        lps=lps,
        rounds=rounds,
        grasp_rows=0 if chosen.rows is None else int(chosen.rows[chosen.active].sum()),
    )


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
    for order in (1, 2):
        # Each side extrapolated to the break by its own next derivative, so
        # that a steep but continuous q'' (a short spline piece) is no jump.
        right = spline(inner + step, order) - step * spline(inner + step, order + 1)
        left = spline(inner - step, order) + step * spline(inner - step, order + 1)
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


def _refuse(problem: _Problem, z: np.ndarray) -> None:
    """Raise if a limit is exceeded beyond the contract at any point."""
    dense, points = problem.dense, problem.jerk
    excess = dense.excess(z, problem.limits)
    jerk = _point_excess(problem, z)
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


def _split(z: np.ndarray, size: int) -> tuple[np.ndarray, np.ndarray]:
    """X and u from the LP variables (x clipped at 0 against rounding)."""
    return np.maximum(z[:size], 0.0), z[size:].copy()


def _solve(
    problem: _Problem,
    chosen: _Selection,
    x_bar: np.ndarray,
    x_dense: np.ndarray,
    x_jerk: np.ndarray,
) -> np.ndarray:
    """One LP (module docstring, step 2): z = [x, u].

    ``x_bar``, ``x_dense``, ``x_jerk``: the previous profile at the grid,
    dense and jerk points. The rows other than the jerk's are taken once
    per point: at the end of a segment only where it is not the next one's
    start (or where a limit was exceeded).
    """
    limits, dense, points = problem.limits, problem.dense, problem.jerk
    assert limits.jerk is not None
    s, size = problem.s, len(problem.s)
    last = len(DENSE) - 1
    repeated = (dense.k == last) & (np.arange(len(dense.s)) < len(dense.s) - 1)
    once = np.flatnonzero(chosen.active & (~repeated | chosen.keep.full))
    maps = PointMaps(*(m[once] for m in dense.maps))
    smp = dense.samples
    dq, ddq = smp.dq[once], smp.ddq[once]
    blocks, rhs = [], []

    def add(alpha: np.ndarray, beta: np.ndarray, bound: np.ndarray) -> None:
        A, b = affine_rows(maps, alpha, beta, bound)
        blocks.append(A)
        rhs.append(b)

    zeros = np.zeros((len(once), 1))
    add(zeros, np.ones_like(zeros), smp.x_cap[once][:, None])  # velocity
    inside = ((dense.k[once] > 0) & (dense.k[once] < last))[:, None]
    add(zeros, -np.ones_like(zeros), np.where(inside, 0.0, np.inf))  # x >= 0
    keep = chosen.keep
    acceleration = np.where(keep.acceleration[once], limits.acceleration, np.inf)
    for sign in (1.0, -1.0):
        add(sign * dq, sign * ddq, acceleration)
        if smp.torque is not None and limits.torque is not None:
            assert keep.torque is not None
            a, b, c = (v[once] for v in smp.torque)
            bound = np.where(keep.torque[once], limits.torque - sign * c, np.inf)
            add(sign * a, sign * b, bound)
    if chosen.rows is not None and dense.grasp is not None and smp.wrench is not None:
        mask = chosen.rows[once]
        rows = np.flatnonzero(mask.any(axis=0))
        a, b, c = (v[once] for v in smp.wrench)
        F, g = dense.grasp.F[rows], dense.grasp.g[rows]
        bound = np.where(mask[:, rows], g - c @ F.T, np.inf)
        add(a @ F.T, b @ F.T, bound)
    index = np.flatnonzero(chosen.jerk_active)
    floor = 1e-6 * max(float(np.max(x_jerk)), 1e-12)
    jerk_keep = chosen.jerk_keep
    if jerk_keep is not None:  # rows near the limit, and wherever it was exceeded
        jerk_keep = jerk_keep | ~np.isin(points.k, (0, len(JERK_DENSE) - 1))[:, None]
    A, b = jerk_rows(
        PointMaps(*(m[index] for m in points.maps)), points.inner[index],
        points.dq[index], points.ddq[index], points.dddq[index],
        np.maximum(x_jerk, floor)[index], limits.jerk,
        None if jerk_keep is None else jerk_keep[index],
    )  # fmt: skip
    blocks.append(A)
    rhs.append(b)
    added = index[~np.isin(points.k[index], (0, len(JERK_DENSE) - 1))]
    if added.size:  # where a limit was exceeded: velocity, acceleration too
        extra = PointMaps(*(m[added] for m in points.maps))
        for sign in (1.0, -1.0):
            A, b = affine_rows(
                extra, sign * points.dq[added], sign * points.ddq[added],
                np.broadcast_to(limits.acceleration, points.dq[added].shape),
            )  # fmt: skip
            blocks.append(A)
            rhs.append(b)
        zeros = np.zeros((added.size, 1))
        A, b = affine_rows(extra, zeros, zeros + 1.0, points.x_cap[added][:, None])
        blocks.append(A)
        rhs.append(b)
    ds = np.diff(s)
    # Simpson's rule on each segment: T = sum ds / sqrt(x) at its ends and
    # middle, linearised at the previous profile (d/dx x^-1/2 = -x^-1.5 / 2).
    middle = np.flatnonzero(dense.k == len(DENSE) // 2)
    scale = max(float(np.max(x_bar)), 1e-12)
    x_middle = np.maximum(x_dense[middle], 1e-3 * scale)
    width = (np.append(ds, 0.0) + np.insert(ds, 0, 0.0)) / 6.0
    weight = -dense.maps.X[middle].T @ (4.0 / 6.0 * ds / (2.0 * x_middle**1.5))
    weight[:size] -= width / (2.0 * np.maximum(x_bar, 1e-3 * scale) ** 1.5)
    blocks.append(-dense.maps.X[middle])  # x >= 0 in the middle of each segment
    rhs.append(np.zeros(len(middle)))
    blocks.append(_bernstein(s, problem.kinds))  # x >= 0 all along each segment
    rhs.append(np.zeros(int(np.sum(problem.kinds == Piece.INTERIOR))))
    A_eq, b_eq = _continuity(s, problem.kinds)
    result = linprog(
        weight / np.max(np.abs(weight)),
        A_ub=sparse.vstack(blocks).tocsr(),
        b_ub=np.concatenate(rhs),
        A_eq=A_eq,
        b_eq=b_eq,
        bounds=_bounds(problem),
        method="highs",
    )
    if result.status != 0 or result.x is None:
        raise PathNotControllableError(
            f"jerk-limited retiming: no admissible profile ({result.message})", s=0.0
        )
    return np.asarray(result.x)


def _bernstein(s: np.ndarray, kinds: np.ndarray) -> sparse.csr_matrix:
    """Rows ``-(x_i + ds_i u_i) <= 0`` of the interior segments.

    ``x(sigma)`` on segment i is the quadratic with Bernstein coefficients
    ``x_i``, ``x_i + ds_i u_i``, ``x_{i+1}``: the middle one >= 0 (and the
    ends >= 0, > 0 in the interior of the path) keeps x > 0 all along it,
    so the motion never stops inside a segment.
    """
    size = len(s)
    inner = np.flatnonzero(kinds == Piece.INTERIOR)
    rows = np.repeat(np.arange(len(inner)), 2)
    cols = np.column_stack([inner, size + inner]).ravel()
    values = np.column_stack([-np.ones(len(inner)), -np.diff(s)[inner]]).ravel()
    return sparse.csr_matrix((values, (rows, cols)), shape=(len(inner), 2 * size))


def _bounds(problem: _Problem) -> np.ndarray:
    """Bounds of z: x >= 0, the ends' x, and the start and stop pieces' u."""
    size = len(problem.s)
    lower = np.full(2 * size, -np.inf)
    upper = np.full(2 * size, np.inf)
    lower[:size] = 0.0
    lower[0] = upper[0] = float(problem.sd_start) ** 2
    lower[size - 1] = upper[size - 1] = float(problem.sd_end) ** 2
    for segment, (variable, most) in problem.bounds.items():
        if problem.kinds[segment] == Piece.START:  # u_0 = 0, 0 <= u_1 <= most
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
    r, c, v = [], [], []
    for i, kind in enumerate(kinds):
        if kind == Piece.START:  # x_1 = 1.5 ds u_1
            entries = [(i + 1, 1.0), (size + i + 1, -1.5 * ds[i])]
        elif kind == Piece.STOP:  # x_{N-1} = -1.5 ds u_{N-1}
            entries = [(i, 1.0), (size + i, 1.5 * ds[i])]
        else:
            entries = [
                (i + 1, 1.0), (i, -1.0), (size + i, -ds[i]), (size + i + 1, -ds[i])
            ]  # fmt: skip
        for col, val in entries:
            r.append(i)
            c.append(col)
            v.append(val)
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
