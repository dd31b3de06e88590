"""The jerk-limited motion ``q(t) = p(s(t))`` as a Drake ``Trajectory``.

The jerk-limited retimer (:mod:`._jerk`) gives the path acceleration
``u = s''`` at the grid points s_i, continuous along the path. On each
segment ``[s_i, s_{i+1}]`` (``ds_i``, ``sigma = (s - s_i) / ds_i``) it is

- linear in s (an *interior* segment): ``u(s) = u_i + k_i (s - s_i)``,
  ``k_i = (u_{i+1} - u_i) / ds_i``, so ``x = s'^2`` is quadratic in s,
  ``x(sigma) = x_i + ds_i ((2 sigma - sigma^2) u_i + sigma^2 u_{i+1})``.
  In time, ``s'' = u_i + k_i (s - s_i)`` is a linear ODE; with ``tau = t -
  t_i`` and ``z = k_i tau^2``::

      s   = s_i + s'_i tau C1(z) + u_i tau^2 C2(z)
      s'  = s'_i C0(z) + u_i tau C1(z),   s'' = u_i + k_i (s - s_i),
      s''' = k_i s'

  with ``C0 = cosh sqrt z``, ``C1 = sinh sqrt z / sqrt z``, ``C2 = (cosh
  sqrt z - 1) / z`` (their trigonometric forms for z < 0; series near 0);
- a *start from rest* (the first segment when ``x_0 = 0``): constant path
  jerk ``j`` from ``s' = s'' = 0``, ``s = s_0 + j tau^3 / 6``, reaching
  ``u_1`` at ``s_1``: ``T = sqrt(6 ds / u_1)``, ``j = u_1 / T``, so
  ``x(sigma) = 1.5 ds u_1 sigma^(4/3)`` and ``u(sigma) = u_1 sigma^(1/3)``;
- a *stop to rest* (the last segment when ``x_N = 0``): its mirror image,
  ``s = s_N - j rho^3 / 6`` with ``rho`` the time left, ``u_{N-1} < 0``.

Then ``q' = p' s'``, ``q'' = p' s'' + p'' s'^2`` and ``q''' = p' s''' + 3 p''
s' s'' + p''' s'^3``: the acceleration is continuous in time, the jerk
bounded (it jumps where ``k_i`` or ``p'''`` does). This is exactly the
motion whose ``(x, u, k)`` the retimer's LPs constrained. Before
``start_time()`` and after ``end_time()`` the trajectory holds its end points
at rest. Units: s, rad, rad/s, rad/s^2, rad/s^3.
"""

from __future__ import annotations

import enum

import numpy as np
from pydrake.trajectories import Trajectory

from rt_drake.retiming._jerk_kernels import interior_duration
from rt_drake.retiming._joint_path import JointPath
from rt_drake.retiming._retime_errors import RetimeInputError
from rt_drake.retiming._timed_path import PathTrajectory

#: Highest derivative order the trajectory evaluates (q''').
MAX_ORDER = 3
#: |z| below which C0, C1, C2 are summed as series (error < 1e-16).
_SERIES = 1e-3
#: 16-point Gauss-Legendre nodes and weights on [-1, 1].
_GAUSS = np.polynomial.legendre.leggauss(16)
#: Their ``2 sigma - sigma^2``, ``sigma^2`` (``sigma`` on [0, 1]) and weights.
_NODES = (
    2.0 * (0.5 * (_GAUSS[0] + 1.0)) - (0.5 * (_GAUSS[0] + 1.0)) ** 2,
    (0.5 * (_GAUSS[0] + 1.0)) ** 2,
    _GAUSS[1],
)


class Piece(enum.IntEnum):
    """How the path acceleration behaves on a segment (module docstring)."""

    INTERIOR = 0
    START = 1
    STOP = 2


def stumpff(z: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``C0, C1, C2`` of the module docstring at ``z = k tau^2`` (any sign).

    ``|z| < _SERIES``: their series to ``z^3``; else with ``r = sqrt|z|``,
    ``cosh r, sinh r / r, 2 sinh^2(r/2) / r^2`` for z > 0 and ``cos``,
    ``sin`` for z < 0 (each function evaluated only where it is taken).
    """
    z = np.asarray(z, dtype=float)
    c0, c1, c2 = (np.empty(z.shape) for _ in range(3))
    small = np.abs(z) < _SERIES
    for where, (even, odd) in (
        (~small & (z > 0.0), (np.cosh, np.sinh)),
        (~small & (z <= 0.0), (np.cos, np.sin)),
    ):
        r = np.sqrt(np.abs(z[where]))
        c0[where] = even(r)
        c1[where] = odd(r) / r
        c2[where] = 2.0 * odd(0.5 * r) ** 2 / r**2
    w = z[small]
    c0[small] = 1.0 + w / 2.0 + w**2 / 24.0 + w**3 / 720.0
    c1[small] = 1.0 + w / 6.0 + w**2 / 120.0 + w**3 / 5040.0
    c2[small] = 0.5 + w / 24.0 + w**2 / 720.0 + w**3 / 40320.0
    return c0, c1, c2


def _lowest_x(x: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Smallest ``x(sigma) = x + (2 sigma - sigma^2) a + sigma^2 b`` on [0, 1]."""
    curvature = b - a
    with np.errstate(divide="ignore", invalid="ignore"):
        vertex = np.where(curvature > 0.0, -a / curvature, -1.0)
    inside = (vertex > 0.0) & (vertex < 1.0)
    at_vertex = x + (2.0 * vertex - vertex**2) * a + vertex**2 * b
    ends = np.minimum(x, x + a + b)
    return np.where(inside, np.minimum(ends, at_vertex), ends)


def quadrature_duration(s: np.ndarray, x: np.ndarray, u: np.ndarray) -> float:
    """The motion's duration, ``sum ds / sqrt(x)``, by quadrature (inf if it stops).

    Start and stop pieces in closed form (``T = sqrt(6 ds / |u|)``), the
    interior segments by 16-point Gauss-Legendre quadrature of ``ds /
    sqrt(x(sigma))`` (what :class:`JerkTimedPath` starts its Newton steps
    from; close to its exact duration where x stays away from 0). Inf where
    x reaches 0 inside a segment or a rest piece has ``u = 0``.
    """
    x = np.maximum(np.asarray(x, dtype=float), 0.0)
    u = np.ascontiguousarray(u, dtype=float)
    ds = np.diff(s)
    # The pieces of piece_kinds (plain comparisons: enums cost microseconds).
    count = len(ds)
    stop = bool(x[-1] == 0.0)
    start = bool(x[0] == 0.0) and not (stop and count == 1)
    total = 0.0
    for rest, i, a in ((start, 0, u[1]), (stop, count - 1, u[count - 1])):
        if rest:
            if not abs(a) > 0.0:
                return np.inf
            total += float(np.sqrt(6.0 * ds[i] / abs(a)))
    first, last = int(start), count - int(stop)
    return total + interior_duration(
        ds[first:last], x[first:last], u[first:last], u[first + 1 : last + 1],
        *_NODES,
    )  # fmt: skip


def piece_kinds(x: np.ndarray) -> np.ndarray:
    """START for the first segment if ``x_0 = 0``, STOP for the last if ``x_N = 0``."""
    kinds = np.full(len(x) - 1, Piece.INTERIOR, dtype=int)
    if x[0] == 0.0:
        kinds[0] = Piece.START
    if x[-1] == 0.0:
        kinds[-1] = Piece.STOP
    return kinds


class JerkTimedPath(PathTrajectory):
    """Joint trajectory of a jerk-limited retime (see the module docstring).

    Args:
        spline: The path p(s), s in [0, 1].
        gridpoints: (N+1,) grid s_i, N >= 2.
        x: (N+1,) ``s'(s_i)^2`` (1/s^2); ``x > 0`` except possibly at the ends.
        u: (N+1,) ``s''(s_i)`` (1/s^2), with ``x_{i+1} - x_i = ds_i (u_i +
            u_{i+1})`` on interior segments, ``x_1 = 1.5 ds_0 u_1`` after a
            start from rest, ``x_{N-1} = -1.5 ds_{N-1} u_{N-1}`` before a stop.
        start_time: Time (s) at which s = 0.
        derivative_order: 0 for q(t); k for its k-th derivative (<= 3).
    """

    def __init__(
        self,
        spline: JointPath,
        gridpoints: np.ndarray,
        x: np.ndarray,
        u: np.ndarray,
        start_time: float = 0.0,
        derivative_order: int = 0,
    ) -> None:
        Trajectory.__init__(self)
        s = np.asarray(gridpoints, dtype=float)
        x = np.maximum(np.asarray(x, dtype=float), 0.0)
        u = np.asarray(u, dtype=float)
        if s.ndim != 1 or x.shape != s.shape or u.shape != s.shape or s.size < 3:
            raise RetimeInputError(
                f"{s.shape=}, {x.shape=} and {u.shape=} must be equal (N+1,), N >= 2"
            )
        if not 0 <= derivative_order <= MAX_ORDER:
            raise RetimeInputError(f"derivative order must be 0..{MAX_ORDER}")
        self._spline = spline
        self._s, self._x, self._u = s, x, u
        self._ds = np.diff(s)
        self._kind = piece_kinds(x)
        self._k = np.diff(u) / self._ds
        self._jerk = np.zeros(len(self._ds))  # path jerk of START / STOP pieces
        durations = np.empty(len(self._ds))
        for i in np.flatnonzero(self._kind != Piece.INTERIOR):
            a = abs(u[i + 1] if self._kind[i] == Piece.START else u[i])
            if not a > 0.0:
                raise RetimeInputError(f"segment {i} never leaves or reaches rest")
            durations[i] = np.sqrt(6.0 * self._ds[i] / a)
            self._jerk[i] = a / durations[i]
        inner = self._kind == Piece.INTERIOR
        durations[inner] = self._interior_durations(np.flatnonzero(inner))
        self._t = float(start_time) + np.concatenate([[0.0], np.cumsum(durations)])
        self._order = int(derivative_order)

    def _interior_durations(self, index: np.ndarray) -> np.ndarray:
        """Time to cross each interior segment: ``s(tau) = s_{i+1}``.

        Newton from 16-point Gauss-Legendre quadrature of ``ds / sqrt(x)``;
        where it has not converged (x nearly 0 inside the segment makes s(t)
        stiff), bisection on ``s(tau)``, which increases while ``s' > 0``,
        between 0 and ``ds / sqrt(min x)``.

        Raises:
            RetimeInputError: x reaches 0 inside a segment (never ends).
        """
        if not index.size:
            return np.zeros(0)
        ds, x, u = self._ds[index], self._x[index], self._u[index]
        u1 = self._u[index + 1]
        lowest = _lowest_x(x, ds * u, ds * u1)
        if np.any(lowest <= 0.0):
            i = int(index[np.flatnonzero(lowest <= 0.0)[0]])
            raise RetimeInputError(f"s' reaches 0 inside segment {i}: never ends")
        nodes, weights = _GAUSS
        sigma = 0.5 * (nodes + 1.0)
        xs = x[:, None] + ds[:, None] * (
            (2.0 * sigma - sigma**2) * u[:, None] + sigma**2 * u1[:, None]
        )
        tau = 0.5 * ds * np.sum(weights / np.sqrt(xs), axis=1)
        sd, k = np.sqrt(x), self._k[index]

        def reached(t: np.ndarray) -> np.ndarray:
            _, c1, c2 = stumpff(k * t**2)
            return sd * t * c1 + u * t**2 * c2

        with np.errstate(over="ignore", invalid="ignore"):
            for _ in range(8):
                c0, c1, c2 = stumpff(k * tau**2)  # reached(tau)'s, taken once
                at = sd * tau * c1 + u * tau**2 * c2
                tau = tau - (at - ds) / (sd * c0 + u * tau * c1)
            bad = ~(np.abs(reached(tau) - ds) <= 1e-12 * (1.0 + ds))
            if np.any(bad):
                low = np.zeros(int(bad.sum()))
                high = ds[bad] / np.sqrt(lowest[bad])
                sub = np.flatnonzero(bad)
                for _ in range(200):
                    middle = 0.5 * (low + high)
                    _, c1, c2 = stumpff(k[sub] * middle**2)
                    below = sd[sub] * middle * c1 + u[sub] * middle**2 * c2 < ds[sub]
                    low, high = (
                        np.where(below, middle, low),
                        np.where(below, high, middle),
                    )
                tau[sub] = 0.5 * (low + high)
        return tau

    @property
    def times(self) -> np.ndarray:
        """Times (s) at which the motion passes the grid points, (N+1,)."""
        return self._t.copy()

    @property
    def duration(self) -> float:
        """``end_time() - start_time()``, s."""
        return float(self._t[-1] - self._t[0])

    def time_at(self, s: float) -> float:
        """Time (s) at which the motion reaches path parameter ``s`` (in [0, 1]).

        Start and stop pieces in closed form (``s = j tau^3 / 6``); interior
        ones by bisection on ``s(tau)``, which increases on the segment.
        """
        s = float(np.clip(s, self._s[0], self._s[-1]))
        i = int(
            np.clip(np.searchsorted(self._s, s, side="right") - 1, 0, len(self._ds) - 1)
        )
        t0, t1 = self._t[i], self._t[i + 1]
        if self._kind[i] == Piece.START:
            return float(t0 + np.cbrt(6.0 * (s - self._s[i]) / self._jerk[i]))
        if self._kind[i] == Piece.STOP:
            return float(t1 - np.cbrt(6.0 * (self._s[i + 1] - s) / self._jerk[i]))
        low, high = t0, t1
        for _ in range(60):
            middle = 0.5 * (low + high)
            if self.path_state(middle)[0][0] < s:
                low = middle
            else:
                high = middle
        return float(0.5 * (low + high))

    def path_state(self, times: float | np.ndarray) -> list[np.ndarray]:
        """``s, s', s'', s'''`` at each time, each (M,) (rest outside the span)."""
        times = np.atleast_1d(np.asarray(times, dtype=float))
        t0, t1 = self._t[0], self._t[-1]
        inside = (times >= t0) & (times <= t1)
        t = np.clip(times, t0, t1)
        i = np.clip(np.searchsorted(self._t, t, side="right") - 1, 0, len(self._ds) - 1)
        tau = t - self._t[i]
        kind, k, u = self._kind[i], self._k[i], self._u[i]
        sd0 = np.sqrt(self._x[i])
        with np.errstate(over="ignore", invalid="ignore"):  # start/stop: unused
            c0, c1, c2 = stumpff(k * tau**2)
            s = self._s[i] + sd0 * tau * c1 + u * tau**2 * c2
            sd = sd0 * c0 + u * tau * c1
            sdd = u + k * (s - self._s[i])
            sddd = k * sd
        j = self._jerk[i]
        start, stop = kind == Piece.START, kind == Piece.STOP
        rho = self._t[i + 1] - t
        s = np.where(start, self._s[i] + j * tau**3 / 6.0, s)
        s = np.where(stop, self._s[i + 1] - j * rho**3 / 6.0, s)
        sd = np.where(start, 0.5 * j * tau**2, np.where(stop, 0.5 * j * rho**2, sd))
        sdd = np.where(start, j * tau, np.where(stop, -j * rho, sdd))
        sddd = np.where(start | stop, j, sddd)
        s = np.clip(s, 0.0, 1.0)
        rest = ~inside
        return [
            s,
            np.where(rest, 0.0, sd),
            np.where(rest, 0.0, sdd),
            np.where(rest, 0.0, sddd),
        ]

    def sample(self, times: float | np.ndarray, order: int = 2) -> list[np.ndarray]:
        """Return ``[q, q', ..., q^(order)]`` at each time, each (M, n).

        Vectorised; ``order`` counts from this trajectory's own order.
        """
        total = self._order + order
        if total > MAX_ORDER:
            raise RetimeInputError(f"derivatives above order {MAX_ORDER} not provided")
        s, sd, sdd, sddd = (v[:, None] for v in self.path_state(times))
        p = [self._spline(s[:, 0], nu) for nu in range(total + 1)]
        series = [p[0]]
        if total >= 1:
            series.append(p[1] * sd)
        if total >= 2:
            series.append(p[1] * sdd + p[2] * sd**2)
        if total >= 3:
            series.append(p[1] * sddd + 3.0 * p[2] * sd * sdd + p[3] * sd**3)
        return series[self._order :]


__all__ = [
    "JerkTimedPath",
    "Piece",
    "piece_kinds",
    "quadrature_duration",
    "stumpff",
]
