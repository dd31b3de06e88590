"""Jerk-limited retiming: TOPP-RA first, then a sequence of LPs (totp3's scheme).

Given TOPP-RA's profile (the acceleration-limited optimum, an upper bound
on the path speed), :func:`jerk_limited` finds a profile whose path
acceleration ``u = s''`` is continuous (:mod:`._jerk_timed_path`) and whose
joint jerk stays within ``limits.jerk``, with every other limit and the
grasp rows exact at its points (:mod:`._jerk_rows`):

1. the grid is TOPP-RA's, with six points halving towards each end at rest
   (the jerk ramps up there, ``u ~ s^(1/3)``);
2. each LP maximises ``sum_i w_i x_i``, ``w_i = ds_i / (2 xbar_i^1.5)`` (the
   first-order decrease of the duration ``sum ds / sqrt(x)``), under the
   rows at the constraint points, the jerk rows linearised at the previous
   iterate ``xbar`` (tangent of a convex bound: every iterate keeps the
   jerk at those points), until the duration changes by less than
   :data:`CONVERGED`;
3. every limit, all grasp rows and the jerk are then evaluated exactly at
   nine points per segment; points over a limit by more than
   ``BETWEEN_TOLERANCE`` join the LP (and violated grasp rows with them),
   and the LPs run again, at most :data:`MAX_ROUNDS` times; an excess
   still beyond the 1e-3 contract raises
   :class:`._retime_errors.LimitsBetweenGridPointsError`.

Grasp rows enter the LPs where TOPP-RA's profile used at least
:data:`SCREEN` of them (ratio ``F_r w / g_r``), and wherever step 3 finds one
exceeded. Units: s, rad, 1/s^2 for x and u.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

import numpy as np
from scipy import sparse
from scipy.optimize import linprog

from rt_drake.retiming._check import DEFAULT_TOLERANCE, Margin
from rt_drake.retiming._jerk_rows import (
    PointMaps,
    affine_rows,
    jerk_rows,
    jerk_values,
    point_maps,
    rest_bound,
)
from rt_drake.retiming._jerk_timed_path import JerkTimedPath, Piece
from rt_drake.retiming._joint_path import JointPath
from rt_drake.retiming._retime_errors import (
    LimitsBetweenGridPointsError,
    PathNotControllableError,
    RetimeInputError,
)
from rt_drake.retiming._samples import PathSamples
from rt_drake.retiming.limits import JointLimits

#: Fractions of each segment evaluated exactly after each LP sequence.
DENSE = np.linspace(0.0, 1.0, 9)
#: Of :data:`DENSE`, the ones in the first LPs (indices): both sides of
#: every grid point (the jerk differs; the other rows are taken once).
FIRST = (0, 8)
#: Grasp rows with at least this ratio on TOPP-RA's profile enter the LPs.
SCREEN = 0.9
#: Joint rows (acceleration, torque: on TOPP-RA's profile; jerk: on the
#: previous LP's) with at least this ratio enter the LPs.
JOINT_SCREEN = 0.5
#: Relative change of the duration that ends a sequence of LPs.
CONVERGED = 1e-4
#: LPs per sequence, at most.
MAX_LPS = 12
#: Sequences of LPs (rounds of added points), at most.
MAX_ROUNDS = 6
#: Points halving towards each end at rest.
END_POINTS = 6
#: Fractions of a start or stop piece where its jerk bound is evaluated.
_REST = np.linspace(0.0, 1.0, 65)


@dataclasses.dataclass(frozen=True, eq=False)
class JerkProfile:
    """A jerk-limited profile and its margins at the grid points.

    Attributes:
        trajectory: The motion (:class:`._jerk_timed_path.JerkTimedPath`).
        s, x, u: (N+1,) the grid, ``s'^2`` and ``s''`` there.
        margins: Per constraint, (N+1,) smallest relative slack at the grid
            points (the segment starting there; the last point, the end).
        lps: LPs solved; rounds: sequences of LPs.
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
class _Grasp:
    """The grasp's rows ``F w <= g`` (or None)."""

    F: np.ndarray
    g: np.ndarray


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
    x_ref = np.interp(s, s_topp, x_topp)
    kinds = np.full(len(s) - 1, Piece.INTERIOR, dtype=int)
    if sd_start == 0.0:
        kinds[0] = Piece.START
    if sd_end == 0.0:
        kinds[-1] = Piece.STOP
    grasp = None if F is None or g is None else _Grasp(F, g)
    dense = _Dense.of(spline, sample, s, kinds, limits, grasp)
    u_ref = _topp_u(s_topp, x_topp, dense.s)
    active = np.zeros(len(dense.s), dtype=bool)
    active[np.isin(dense.k, FIRST)] = True
    x_topp_dense = np.interp(dense.s, s_topp, x_topp)
    rows = None
    if grasp is not None:
        ratio = dense.grasp_ratio(x_topp_dense, u_ref)
        rows = (ratio >= SCREEN) & active[:, None]
    keep = dense.joint_ratios(x_topp_dense, u_ref, limits).at_least(JOINT_SCREEN)
    jerk_keep = None
    bounds = _rest_bounds(spline, s, kinds, limits.jerk)
    x_bar = np.maximum(x_ref, 0.0)
    x_dense = np.interp(dense.s, s, x_bar)
    lps = rounds = 0
    best: tuple[float, np.ndarray] | None = None
    while True:
        rounds += 1
        previous = np.inf
        for _ in range(MAX_LPS):
            z = _solve(s, kinds, dense, active, rows, keep, jerk_keep, x_dense,
                       x_bar, limits, bounds, sd_start, sd_end)  # fmt: skip
            lps += 1
            x, u = _split(z, len(s))
            try:
                duration = JerkTimedPath(spline, s, x, u).duration
            except RetimeInputError:  # s' = 0 between the LP's points
                duration = np.inf
                active |= dense.maps.X @ z <= 0.0
            if np.isfinite(duration) and (best is None or duration < best[0]):
                best = (duration, z)
            x_bar = np.maximum(x, 0.0)
            x_dense = np.maximum(dense.maps.X @ z, 0.0)
            jerk_keep = dense.jerk_ratio(z, limits) >= JOINT_SCREEN
            jerk_keep |= keep.full[:, None]
            if abs(previous - duration) <= CONVERGED * duration:
                break
            previous = duration
        assert best is not None
        z = best[1]
        excess = dense.excess(z, limits, bounds)
        over = excess.max(axis=1) > tolerance
        if not over.any() or rounds == MAX_ROUNDS:
            break
        active |= over
        keep = keep.with_full(over)
        if rows is not None:
            rows |= dense.grasp_excess(z) > tolerance
        best = None  # the rows changed: the old optimum may break them
    worst = float(excess.max())
    if worst > DEFAULT_TOLERANCE:
        point = int(np.argmax(excess.max(axis=1)))
        raise LimitsBetweenGridPointsError(
            f"with jerk limits, a limit is exceeded by {100.0 * worst:.2f} % "
            f"between grid points near s = {dense.s[point]:.4f} after "
            f"{MAX_ROUNDS} rounds of LPs",
            float(dense.s[point]),
        )
    x, u = _split(z, len(s))
    trajectory = JerkTimedPath(spline, s, x, u, start_time)
    return JerkProfile(
        trajectory=trajectory,
        s=s,
        x=x,
        u=u,
        margins=dense.margins(z, limits, bounds),
        lps=lps,
        rounds=rounds,
        grasp_rows=0 if rows is None else int(rows[active].sum()),
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


def _rest_bounds(
    spline: JointPath, s: np.ndarray, kinds: np.ndarray, jerk: np.ndarray
) -> dict[int, tuple[int, float]]:
    """By start or stop piece: its far end's u (variable index) and largest |u|."""
    bounds = {}
    for i in np.flatnonzero(kinds != Piece.INTERIOR):
        ds = s[i + 1] - s[i]
        start = kinds[i] == Piece.START
        at = s[i] + ds * (_REST if start else 1.0 - _REST)
        at = np.clip(at, s[i] + 1e-9 * ds, s[i + 1] - 1e-9 * ds)
        sign = 1.0 if start else -1.0  # derivatives pointing away from rest
        variable = len(s) + int(i) + (1 if start else 0)
        bounds[int(i)] = (
            variable,
            rest_bound(
                ds,
                sign * spline(at, 1),
                spline(at, 2),
                sign * spline(at, 3),
                _REST,
                jerk,
            ),
        )
    return bounds


@dataclasses.dataclass(frozen=True, eq=False)
class _Keep:
    """Which joint rows enter the LPs: ratios, or booleans after :meth:`at_least`.

    ``full``: points where a limit was exceeded, which get every row.
    """

    acceleration: np.ndarray
    torque: np.ndarray | None
    full: np.ndarray

    def at_least(self, threshold: float) -> _Keep:
        """Rows whose ratio is at least ``threshold`` (every row of a full point)."""
        full = self.full[:, None]
        return _Keep(
            (self.acceleration >= threshold) | full,
            None if self.torque is None else (self.torque >= threshold) | full,
            self.full,
        )

    def with_full(self, over: np.ndarray) -> _Keep:
        """Every row at the points ``over`` too."""
        full = (self.full | over)[:, None]
        return _Keep(
            self.acceleration | full,
            None if self.torque is None else self.torque | full,
            self.full | over,
        )


@dataclasses.dataclass(frozen=True, eq=False)
class _Dense:
    """The path at :data:`DENSE` of every segment, and the maps of x, u, k there."""

    s: np.ndarray
    k: np.ndarray
    inner: np.ndarray
    samples: PathSamples
    dddq: np.ndarray
    maps: PointMaps
    grasp: _Grasp | None

    @staticmethod
    def of(
        spline: JointPath,
        sample: Callable[[np.ndarray], PathSamples],
        s: np.ndarray,
        kinds: np.ndarray,
        limits: JointLimits,
        grasp: _Grasp | None,
    ) -> _Dense:
        segments = np.repeat(np.arange(len(s) - 1), len(DENSE))
        k = np.tile(np.arange(len(DENSE)), len(s) - 1)
        sigma = DENSE[k]
        ds = np.diff(s)[segments]
        at = s[segments] + sigma * ds
        at[k == len(DENSE) - 1] = s[segments + 1][k == len(DENSE) - 1]
        own = np.clip(at, s[segments] + 1e-9 * ds, s[segments + 1] - 1e-9 * ds)
        maps = point_maps(s, kinds, segments, sigma)
        return _Dense(
            s=at,
            k=k,
            inner=kinds[segments] == Piece.INTERIOR,
            samples=sample(at),
            dddq=spline(own, 3),
            maps=maps,
            grasp=grasp,
        )

    def joint_ratios(self, x: np.ndarray, u: np.ndarray, limits: JointLimits) -> _Keep:
        """Acceleration and torque ratios per joint at (x, u), (P, n) each."""
        smp = self.samples
        acc = np.abs(smp.dq * u[:, None] + smp.ddq * x[:, None]) / limits.acceleration
        torque = None
        if smp.torque is not None and limits.torque is not None:
            a, b, c = smp.torque
            torque = np.abs(a * u[:, None] + b * x[:, None] + c) / limits.torque
        return _Keep(acc, torque, np.zeros(len(x), dtype=bool))

    def jerk_ratio(self, z: np.ndarray, limits: JointLimits) -> np.ndarray:
        """Jerk ratio per joint at the interior points, (P, n) (0 elsewhere)."""
        assert limits.jerk is not None
        x, u, k = self.maps.X @ z, self.maps.U @ z, self.maps.K @ z
        smp = self.samples
        jerk = jerk_values(x, u, k, smp.dq, smp.ddq, self.dddq) / limits.jerk
        return np.where(self.inner[:, None], np.abs(jerk), 0.0)

    def grasp_ratio(self, x: np.ndarray, u: np.ndarray) -> np.ndarray:
        """``F_r w / g_r`` at every point and row, (P, R)."""
        assert self.grasp is not None and self.samples.wrench is not None
        a, b, c = self.samples.wrench
        w = a * u[:, None] + b * x[:, None] + c
        return (w @ self.grasp.F.T) / self.grasp.g

    def grasp_excess(self, z: np.ndarray) -> np.ndarray:
        """Relative excess of every grasp row at every point, (P, R)."""
        return self.grasp_ratio(self.maps.X @ z, self.maps.U @ z) - 1.0

    def ratios(
        self, z: np.ndarray, limits: JointLimits, bounds: dict[int, tuple[int, float]]
    ) -> dict[Margin, np.ndarray]:
        """Each constraint's largest ratio ``value / limit`` at every point, (P,)."""
        x, u, k = self.maps.X @ z, self.maps.U @ z, self.maps.K @ z
        smp = self.samples
        x_cap = np.where(np.isfinite(smp.x_cap), smp.x_cap, np.inf)
        out = {
            Margin.VELOCITY: np.where(
                np.isfinite(x_cap), np.sqrt(np.maximum(x, 0.0) / x_cap), 0.0
            ),
            Margin.ACCELERATION: np.max(
                np.abs(smp.dq * u[:, None] + smp.ddq * x[:, None])
                / limits.acceleration,
                axis=1,
            ),
        }
        assert limits.jerk is not None
        jerk = np.abs(jerk_values(x, u, k, smp.dq, smp.ddq, self.dddq)) / limits.jerk
        jerk_ratio = np.where(self.inner, np.max(jerk, axis=1), 0.0)
        n_points = len(DENSE)
        for segment, (variable, bound) in bounds.items():
            part = slice(segment * n_points, (segment + 1) * n_points)
            jerk_ratio[part] = (abs(z[variable]) / bound) ** 1.5
        out[Margin.JERK] = jerk_ratio
        if smp.torque is not None and limits.torque is not None:
            a, b, c = smp.torque
            tau = a * u[:, None] + b * x[:, None] + c
            out[Margin.TORQUE] = np.max(np.abs(tau) / limits.torque, axis=1)
        if self.grasp is not None:
            out[Margin.GRASP] = np.max(self.grasp_excess(z), axis=1) + 1.0
        return out

    def excess(
        self, z: np.ndarray, limits: JointLimits, bounds: dict[int, tuple[int, float]]
    ) -> np.ndarray:
        """Relative excess over each limit at every point, (P, kinds)."""
        return np.column_stack(list(self.ratios(z, limits, bounds).values())) - 1.0

    def margins(
        self, z: np.ndarray, limits: JointLimits, bounds: dict[int, tuple[int, float]]
    ) -> dict[Margin, np.ndarray]:
        """``1 - ratio`` at the grid points (segment starts, and the end)."""
        grid = np.append(np.flatnonzero(self.k == 0), len(self.s) - 1)
        return {m: 1.0 - r[grid] for m, r in self.ratios(z, limits, bounds).items()}


def _solve(
    s: np.ndarray,
    kinds: np.ndarray,
    dense: _Dense,
    active: np.ndarray,
    rows: np.ndarray | None,
    keep: _Keep,
    jerk_keep: np.ndarray | None,
    x_dense: np.ndarray,
    x_bar: np.ndarray,
    limits: JointLimits,
    bounds: dict[int, tuple[int, float]],
    sd_start: float,
    sd_end: float,
) -> np.ndarray:
    """One LP (module docstring, step 2): z = [x, u].

    The rows other than the jerk's are taken once per point: at the end of
    a segment only where it is not the next one's start (or a full point).
    """
    assert limits.jerk is not None
    size = len(s)
    index = np.flatnonzero(active)
    last = len(DENSE) - 1
    repeated = (dense.k == last) & (np.arange(len(dense.s)) < len(dense.s) - 1)
    once = np.flatnonzero(active & (~repeated | keep.full))
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
    acceleration = np.where(keep.acceleration[once], limits.acceleration, np.inf)
    for sign in (1.0, -1.0):
        add(sign * dq, sign * ddq, acceleration)
        if smp.torque is not None and limits.torque is not None:
            assert keep.torque is not None
            a, b, c = (v[once] for v in smp.torque)
            bound = np.where(keep.torque[once], limits.torque - sign * c, np.inf)
            add(sign * a, sign * b, bound)
    if rows is not None and dense.grasp is not None and smp.wrench is not None:
        mask = rows[once]
        chosen = np.flatnonzero(mask.any(axis=0))
        a, b, c = (v[once] for v in smp.wrench)
        F, g = dense.grasp.F[chosen], dense.grasp.g[chosen]
        bound = np.where(mask[:, chosen], g - c @ F.T, np.inf)
        add(a @ F.T, b @ F.T, bound)
    floor = 1e-6 * max(float(np.max(x_dense)), 1e-12)
    jerk_maps = PointMaps(*(m[index] for m in dense.maps))
    A, b = jerk_rows(
        jerk_maps, dense.inner[index], dense.samples.dq[index],
        dense.samples.ddq[index], dense.dddq[index],
        np.maximum(x_dense, floor)[index], limits.jerk,
        None if jerk_keep is None else jerk_keep[index],
    )  # fmt: skip
    blocks.append(A)
    rhs.append(b)
    A_eq, b_eq = _continuity(s, kinds)
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
    lower = np.full(2 * size, -np.inf)
    upper = np.full(2 * size, np.inf)
    lower[:size] = 0.0
    lower[0] = upper[0] = float(sd_start) ** 2
    lower[size - 1] = upper[size - 1] = float(sd_end) ** 2
    for segment, (variable, most) in bounds.items():
        if kinds[segment] == Piece.START:  # u_0 = 0, 0 <= u_1 <= most
            lower[size] = upper[size] = 0.0
            lower[variable], upper[variable] = 0.0, most
        else:  # u_N = 0, -most <= u_{N-1} <= 0
            lower[2 * size - 1] = upper[2 * size - 1] = 0.0
            lower[variable], upper[variable] = -most, 0.0
    result = linprog(
        weight / np.max(np.abs(weight)),
        A_ub=sparse.vstack(blocks).tocsr(),
        b_ub=np.concatenate(rhs),
        A_eq=A_eq,
        b_eq=b_eq,
        bounds=np.column_stack([lower, upper]),
        method="highs",
    )
    if result.status != 0 or result.x is None:
        raise PathNotControllableError(
            f"jerk-limited retiming: no admissible profile ({result.message})", s=0.0
        )
    return np.asarray(result.x)


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


__all__ = ["CONVERGED", "DENSE", "MAX_LPS", "MAX_ROUNDS", "JerkProfile", "jerk_limited"]
