"""The points where the jerk-limited retimer evaluates its limits.

:class:`DensePoints`: :data:`DENSE` fractions of every segment, with the
path's coefficients (velocity cap, torques, object wrench) from the
retimer's ``sample_path``; there the velocity, acceleration, torque and
grasp are evaluated exactly after each sequence of LPs, and the points over
a limit join the LPs. :class:`JerkPoints`: :data:`JERK_DENSE` fractions,
for the jerk alone. :func:`rest_bounds`: the jerk of the start and stop
pieces as a bound on their path acceleration (:mod:`._jerk_rows`).
:class:`Keep`: which joint rows enter the LPs.
"""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Callable

import numpy as np

from rt_drake.retiming._check import Margin
from rt_drake.retiming._jerk_kernels import (
    acceleration_ratios,
    grasp_screen,
    jerk_ratios,
    joint_ratios,
    row_max,
)
from rt_drake.retiming._jerk_rows import (
    Band,
    PointMaps,
    rest_bound,
)
from rt_drake.retiming._jerk_timed_path import Piece
from rt_drake.retiming._joint_path import JointPath
from rt_drake.retiming._samples import PathSamples
from rt_drake.retiming.limits import JointLimits

#: Fractions of each segment where every limit but the jerk is evaluated.
DENSE = np.linspace(0.0, 1.0, 9)
#: Fractions of each segment where the jerk is evaluated.
JERK_DENSE = np.linspace(0.0, 1.0, 33)
#: Fractions of a start or stop piece where its jerk bound is evaluated.
REST = np.linspace(0.0, 1.0, 65)


@dataclasses.dataclass(frozen=True, eq=False)
class GraspRows:
    """The grasp's rows ``F w <= g`` (or None)."""

    F: np.ndarray
    g: np.ndarray

    @property
    def scaled(self) -> np.ndarray:
        """``F_r / g_r``, (R, 6): ``F_r w / g_r = scaled_r w``."""
        return self.F / self.g[:, None]

    @functools.cached_property
    def largest_norm(self) -> float:
        """``max_r |F_r / g_r|_2``: the largest change of a ratio per unit of wrench."""
        return float(np.max(np.linalg.norm(self.scaled, axis=1)))

    @functools.cached_property
    def scaled_t(self) -> np.ndarray:
        """:attr:`scaled` transposed, (6, R), C-contiguous (the compiled screen's)."""
        return np.ascontiguousarray(self.scaled.T, dtype=float)


def rest_bounds(
    spline: JointPath, s: np.ndarray, kinds: np.ndarray, jerk: np.ndarray
) -> dict[int, tuple[int, float]]:
    """By start or stop piece: its far end's u (variable index) and largest |u|."""
    bounds = {}
    for i in np.flatnonzero(kinds != Piece.INTERIOR):
        ds = s[i + 1] - s[i]
        start = kinds[i] == Piece.START
        at = s[i] + ds * (REST if start else 1.0 - REST)
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
                REST,
                jerk,
            ),
        )
    return bounds


@dataclasses.dataclass(frozen=True, eq=False)
class Keep:
    """Which joint rows enter the LPs: ratios, or booleans after :meth:`at_least`.

    ``full``: points where a limit was exceeded, which get every row.
    """

    acceleration: np.ndarray
    torque: np.ndarray | None
    full: np.ndarray

    def at_least(self, threshold: float) -> Keep:
        """Rows whose ratio is at least ``threshold`` (every row of a full point)."""
        full = self.full[:, None]
        return Keep(
            (self.acceleration >= threshold) | full,
            None if self.torque is None else (self.torque >= threshold) | full,
            self.full,
        )

    def with_full(self, over: np.ndarray) -> Keep:
        """Every row at the points ``over`` too."""
        full = (self.full | over)[:, None]
        return Keep(
            self.acceleration | full,
            None if self.torque is None else self.torque | full,
            self.full | over,
        )


@dataclasses.dataclass(frozen=True, eq=False)
class DensePoints:
    """The path at :data:`DENSE` of every segment, and the maps of x, u, k there."""

    s: np.ndarray
    k: np.ndarray
    samples: PathSamples
    maps: PointMaps
    band: Band
    grasp: GraspRows | None

    @staticmethod
    def of(
        sample: Callable[[np.ndarray], PathSamples],
        s: np.ndarray,
        kinds: np.ndarray,
        grasp: GraspRows | None,
    ) -> DensePoints:
        """The points of every segment and the path's coefficients there."""
        segments = np.repeat(np.arange(len(s) - 1), len(DENSE))
        k = np.tile(np.arange(len(DENSE)), len(s) - 1)
        sigma = DENSE[k]
        ds = np.diff(s)[segments]
        at = s[segments] + sigma * ds
        at[k == len(DENSE) - 1] = s[segments + 1][k == len(DENSE) - 1]
        band = Band.of(s, kinds, segments, sigma)
        return DensePoints(
            s=at,
            k=k,
            samples=sample(at),
            maps=band.maps(len(s)),
            band=band,
            grasp=grasp,
        )

    def joint_ratios(self, x: np.ndarray, u: np.ndarray, limits: JointLimits) -> Keep:
        """Acceleration and torque ratios per joint at (x, u), (P, n) each.

        No torque ratios with a set of objects (its torques are pairs,
        :mod:`._jerk_set`).
        """
        smp = self.samples
        acc = np.abs(smp.dq * u[:, None] + smp.ddq * x[:, None]) / limits.acceleration
        torque = None
        if self.one_torque and limits.torque is not None:
            assert smp.torque is not None
            a, b, c = smp.torque
            torque = np.abs(a * u[:, None] + b * x[:, None] + c) / limits.torque
        return Keep(acc, torque, np.zeros(len(x), dtype=bool))

    @property
    def one_torque(self) -> bool:
        """Torque coefficients of the whole robot: the arm and (one) object.

        False with a set of objects: ``samples.torque`` is then the arm's
        alone, the object's share in ``samples.torque_set``.
        """
        smp = self.samples
        return smp.torque is not None and smp.torque_set is None

    def grasp_screen(
        self,
        x: np.ndarray,
        u: np.ndarray,
        threshold: float,
        at: np.ndarray | None = None,
    ) -> tuple[np.ndarray, np.ndarray]:
        """Pairs with ``F_r w / g_r >= threshold``, (P, R), and each point's largest.

        ``w = a u + b x + c`` at every point (:func:`._jerk_kernels.grasp_screen`,
        one compiled pass: the (P, R) ratios are not stored). ``at``: the
        points to evaluate (the others: no pair, largest -inf); None: all.
        """
        assert self.grasp is not None and self.samples.wrench is not None
        index = np.arange(len(x)) if at is None else np.asarray(at, dtype=np.int64)
        a, b, c = (np.ascontiguousarray(v, dtype=float) for v in self.samples.wrench)
        x, u = (np.ascontiguousarray(v, dtype=float) for v in (x, u))
        over = np.zeros((len(x), len(self.grasp.g)), dtype=bool)
        largest = np.full(len(x), -np.inf)
        grasp_screen(
            a, b, c, x, u, self.grasp.scaled_t, float(threshold), index, over, largest
        )
        return over, largest

    def ratios(
        self,
        z: np.ndarray,
        limits: JointLimits,
        grasp: np.ndarray | None = None,
        torque: np.ndarray | None = None,
    ) -> dict[Margin, np.ndarray]:
        """Each limit's largest ratio ``value / limit`` at every point, (P,).

        ``grasp``: (P,) the grasp's largest ratio at z, if already known (a
        set of objects: its worst object's); else the grasp rows' (if any).
        ``torque``: (P,) with a set of objects, its worst object's largest
        torque ratio at z; else the one object's torques (if limited).
        """
        x, u = self.maps.x(z), self.maps.u(z)
        smp = self.samples
        x_cap = np.where(np.isfinite(smp.x_cap), smp.x_cap, np.inf)
        out = {
            Margin.VELOCITY: np.where(
                np.isfinite(x_cap), np.sqrt(_divide(np.maximum(x, 0.0), x_cap)), 0.0
            ),
            Margin.ACCELERATION: _row_max(
                np.abs(smp.dq * u[:, None] + smp.ddq * x[:, None]) / limits.acceleration
            ),
        }
        if self.one_torque and limits.torque is not None:
            assert smp.torque is not None
            a, b, c = smp.torque
            tau = a * u[:, None] + b * x[:, None] + c
            out[Margin.TORQUE] = _row_max(np.abs(tau) / limits.torque)
        if torque is not None:
            out[Margin.TORQUE] = torque
        if grasp is None and self.grasp is not None:
            grasp = self.grasp_screen(x, u, np.inf)[1]
        if grasp is not None:
            out[Margin.GRASP] = grasp
        return out

    def margins(self, ratios: dict[Margin, np.ndarray]) -> dict[Margin, np.ndarray]:
        """``1 - ratio`` at the grid points (segment starts, and the end)."""
        grid = np.append(np.flatnonzero(self.k == 0), len(self.s) - 1)
        return {m: 1.0 - r[grid] for m, r in ratios.items()}


def largest_excess(ratios: dict[Margin, np.ndarray]) -> np.ndarray:
    """Largest relative excess over a limit at every point, (P,)."""
    values = list(ratios.values())
    largest = values[0]
    for more in values[1:]:  # (np.max over a stacked copy costs more)
        largest = np.maximum(largest, more)
    return largest - 1.0


def _row_max(a: np.ndarray) -> np.ndarray:
    """``np.max(a, axis=1)`` of a (P, n) array (:func:`._jerk_kernels.row_max`)."""
    out = np.empty(len(a))
    row_max(np.ascontiguousarray(a, dtype=float), out)
    return out


def _divide(x: np.ndarray, cap: np.ndarray) -> np.ndarray:
    """``x / cap``, with ``0 / 0 = 0`` and ``x / 0 = inf`` (a cap of 0: a stop)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(x > 0.0, x / cap, 0.0)


@dataclasses.dataclass(frozen=True, eq=False)
class JerkPoints:
    """The path at :data:`JERK_DENSE` of every segment, for the jerk rows.

    The jerk varies most inside a segment (it holds ``k = du/ds``), so it is
    evaluated at more points than the other limits; it needs only the
    spline's derivatives, not Drake. So do the velocity and acceleration,
    checked here too (on a coarse grid they can peak between the 9 points of
    :class:`DensePoints`).
    """

    s: np.ndarray
    k: np.ndarray
    inner: np.ndarray
    x_cap: np.ndarray
    dq: np.ndarray
    ddq: np.ndarray
    dddq: np.ndarray
    maps: PointMaps
    band: Band
    segment: np.ndarray

    @staticmethod
    def of(
        spline: JointPath, s: np.ndarray, kinds: np.ndarray, velocity: np.ndarray
    ) -> JerkPoints:
        """The points of every segment (q''' on the segment side of a knot)."""
        count = len(JERK_DENSE)
        segments = np.repeat(np.arange(len(s) - 1), count)
        k = np.tile(np.arange(count), len(s) - 1)
        sigma = JERK_DENSE[k]
        ds = np.diff(s)[segments]
        at = s[segments] + sigma * ds
        at[k == count - 1] = s[segments + 1][k == count - 1]
        own = np.clip(at, s[segments] + 1e-9 * ds, s[segments + 1] - 1e-9 * ds)
        dq = spline(at, 1)
        band = Band.of(s, kinds, segments, sigma)
        with np.errstate(divide="ignore", over="ignore"):  # q' = 0: no cap
            x_cap = np.min(velocity**2 / dq**2, axis=1)
        return JerkPoints(
            s=at,
            k=k,
            inner=kinds[segments] == Piece.INTERIOR,
            x_cap=x_cap,
            dq=np.ascontiguousarray(dq, dtype=float),
            ddq=np.ascontiguousarray(spline(at, 2), dtype=float),
            dddq=np.ascontiguousarray(spline(own, 3), dtype=float),
            maps=band.maps(len(s)),
            band=band,
            segment=segments,
        )

    def per_joint(self, z: np.ndarray, limits: JointLimits) -> np.ndarray:
        """``|jerk_j| / J_j`` at the interior points, (P, n) (0 elsewhere).

        :func:`._jerk_kernels.jerk_ratios`: :func:`._jerk_rows.jerk_values`
        with x, u, k from the band, in one compiled pass.
        """
        assert limits.jerk is not None
        out = np.empty(self.dq.shape)
        band = self.band
        jerk_ratios(
            band.cols, band.X, band.U, band.K, np.ascontiguousarray(z, dtype=float),
            self.dq, self.ddq, self.dddq, np.array(limits.jerk, dtype=float),
            self.inner, out,
        )  # fmt: skip
        return out

    def ratio(
        self,
        z: np.ndarray,
        bounds: dict[int, tuple[int, float]],
        per_joint: np.ndarray,
    ) -> np.ndarray:
        """The largest jerk ratio at every point, (P,).

        ``per_joint``: (P, n) :meth:`per_joint` at z. Start and stop pieces
        in closed form, ``(|u| / bound)^1.5``.
        """
        out = _row_max(per_joint)
        for segment, (variable, bound) in bounds.items():
            out[self.segment == segment] = (abs(z[variable]) / bound) ** 1.5
        return out

    def acceleration_ratio(
        self, z: np.ndarray, limits: JointLimits, at: np.ndarray
    ) -> np.ndarray:
        """``|q'_j u + q''_j x| / a_j`` at the points ``at``, (A, n).

        :func:`._jerk_kernels.acceleration_ratios` (x clipped at 0).
        """
        band = self.band
        out = np.empty((len(at), self.dq.shape[1]))
        acceleration_ratios(
            band.cols, band.X, band.U, np.ascontiguousarray(z, dtype=float),
            self.dq, self.ddq, np.array(limits.acceleration, dtype=float),
            np.asarray(at, dtype=np.int64), out,
        )  # fmt: skip
        return out

    def joint_ratio(self, z: np.ndarray, limits: JointLimits) -> np.ndarray:
        """The largest velocity or acceleration ratio at every point, (P,).

        :func:`._jerk_kernels.joint_ratios`: ``max(sqrt(x / x_cap), max_j
        |q'_j u + q''_j x| / a_j)``, x clipped at 0.
        """
        band = self.band
        out = np.empty(len(self.s))
        joint_ratios(
            band.cols, band.X, band.U, np.ascontiguousarray(z, dtype=float),
            self.dq, self.ddq, self.x_cap, np.array(limits.acceleration, dtype=float),
            out,
        )  # fmt: skip
        return out

    def margins(self, ratio: np.ndarray) -> np.ndarray:
        """``1 - ratio`` at the grid points (segment starts, and the end).

        ``ratio``: (P,) the largest jerk ratio at every point (:meth:`ratio`).
        """
        grid = np.append(np.flatnonzero(self.k == 0), len(self.s) - 1)
        return 1.0 - ratio[grid]


__all__ = [
    "DENSE",
    "JERK_DENSE",
    "REST",
    "DensePoints",
    "GraspRows",
    "JerkPoints",
    "Keep",
    "largest_excess",
    "rest_bounds",
]
