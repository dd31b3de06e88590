"""The retimed motion ``q(t) = p(s(t))`` as a Drake ``Trajectory``.

TOPP-RA returns ``x_i = s'(s_i)^2`` at the grid points; between two grid
points the path acceleration is constant, ``u_i = (x_{i+1} - x_i) / (2 ds_i)``
(so ``x`` is linear in s), which takes ``dt_i = 2 ds_i / (s'_i + s'_{i+1})``.
Within segment i, with ``tau = t - t_i``::

    s = s_i + s'_i tau + u_i tau^2 / 2,   s' = s'_i + u_i tau,   s'' = u_i
    q = p(s),  q' = p'(s) s',  q'' = p'(s) s'' + p''(s) s'^2,
    q''' = 3 p''(s) s' s'' + p'''(s) s'^3

This is exactly the motion whose (u, x) the retimer constrained, not a
re-fit. ``p`` is the path, a :class:`~._joint_path.JointPath`.
Before ``start_time()`` and after ``end_time()`` the trajectory holds its end
points with zero derivatives. Units: s, rad, rad/s, rad/s^2.
"""

from __future__ import annotations

import numpy as np
from pydrake.trajectories import Trajectory

from rt_drake.retiming._joint_path import JointPath
from rt_drake.retiming._retime_errors import RetimeInputError

#: Highest derivative order the trajectory evaluates.
MAX_ORDER = 3


class PathTrajectory(Trajectory):
    """Drake's ``Trajectory`` interface of a retimed path q(s(t)).

    A subclass gives ``sample(t, order)`` (the list of q(t) and its
    derivatives from ``self._order`` to ``order``), ``self._spline`` (the
    path p(s)), ``self._t`` (the times of its grid points) and
    ``self._order`` (which derivative it is).
    """

    _order: int

    def do_value(self, t: float) -> np.ndarray:  # noqa: D102
        return self.sample(t, order=0)[0].reshape(-1, 1)

    def do_has_derivative(self) -> bool:  # noqa: D102
        return True

    def DoEvalDerivative(self, t: float, derivative_order: int) -> np.ndarray:  # noqa: D102
        return self.sample(t, order=derivative_order)[-1].reshape(-1, 1)

    def DoMakeDerivative(self, derivative_order: int) -> PathTrajectory:  # noqa: D102
        return self._copy(self._order + derivative_order)

    def do_rows(self) -> int:  # noqa: D102
        return int(np.asarray(self._spline(0.0)).size)

    def do_cols(self) -> int:  # noqa: D102
        return 1

    def do_start_time(self) -> float:  # noqa: D102
        return float(self._t[0])

    def do_end_time(self) -> float:  # noqa: D102
        return float(self._t[-1])

    def Clone(self) -> PathTrajectory:  # noqa: D102
        return self._copy(self._order)

    def __deepcopy__(self, memo: dict) -> PathTrajectory:
        return self._copy(self._order)

    def _copy(self, order: int) -> PathTrajectory:
        cls = type(self)
        copy = cls.__new__(cls)
        Trajectory.__init__(copy)
        copy.__dict__.update(self.__dict__)
        if not 0 <= order <= MAX_ORDER:
            raise RetimeInputError(f"derivatives above order {MAX_ORDER} not provided")
        copy._order = order
        return copy


class TimedPath(PathTrajectory):
    """Joint trajectory of a path retimed by TOPP-RA (see module docstring).

    Args:
        spline: The path p(s), s in [0, 1] (values (n,)).
        gridpoints: (N+1,) grid s_i, 0 to 1.
        x: (N+1,) ``s'(s_i)^2`` (1/s^2), >= 0, no two consecutive zeros.
        start_time: Time (s) at which s = 0.
        derivative_order: 0 for q(t); k for its k-th derivative (<= 3).
    """

    def __init__(
        self,
        spline: JointPath,
        gridpoints: np.ndarray,
        x: np.ndarray,
        start_time: float = 0.0,
        derivative_order: int = 0,
    ) -> None:
        Trajectory.__init__(self)
        s = np.asarray(gridpoints, dtype=float)
        x = np.maximum(np.asarray(x, dtype=float), 0.0)
        if s.ndim != 1 or x.shape != s.shape or s.size < 2:
            raise RetimeInputError(f"{s.shape=} and {x.shape=} must be equal (N+1,)")
        sd = np.sqrt(x)
        if np.any(sd[:-1] + sd[1:] <= 0.0):
            i = int(np.flatnonzero(sd[:-1] + sd[1:] <= 0.0)[0])
            raise RetimeInputError(
                f"s' is zero at both ends of segment {i}: never ends"
            )
        if not 0 <= derivative_order <= MAX_ORDER:
            raise RetimeInputError(f"derivative order must be 0..{MAX_ORDER}")
        ds = np.diff(s)
        self._spline = spline
        self._s, self._sd = s, sd
        self._u = (x[1:] - x[:-1]) / (2.0 * ds)
        self._t = float(start_time) + np.concatenate(
            [[0.0], np.cumsum(2.0 * ds / (sd[:-1] + sd[1:]))]
        )
        self._order = int(derivative_order)

    @property
    def times(self) -> np.ndarray:
        """Times (s) at which the motion passes the grid points, (N+1,)."""
        return self._t.copy()

    @property
    def duration(self) -> float:
        """``end_time() - start_time()``, s."""
        return float(self._t[-1] - self._t[0])

    def sample(self, times: float | np.ndarray, order: int = 2) -> list[np.ndarray]:
        """Return ``[q, q', ..., q^(order)]`` at each time, each (M, n).

        Vectorised; ``order`` counts from this trajectory's own order.
        """
        times = np.atleast_1d(np.asarray(times, dtype=float))
        total = self._order + order
        if total > MAX_ORDER:
            raise RetimeInputError(f"derivatives above order {MAX_ORDER} not provided")
        t0, t1 = self._t[0], self._t[-1]
        inside = (times >= t0) & (times <= t1)
        t = np.clip(times, t0, t1)
        k = np.clip(np.searchsorted(self._t, t, side="right") - 1, 0, len(self._u) - 1)
        tau = t - self._t[k]
        u = self._u[k]
        s = np.clip(self._s[k] + self._sd[k] * tau + 0.5 * u * tau**2, 0.0, 1.0)
        sd = np.where(inside, np.maximum(self._sd[k] + u * tau, 0.0), 0.0)[:, None]
        sdd = np.where(inside, u, 0.0)[:, None]
        p = [self._spline(s, nu) for nu in range(total + 1)]
        series = [p[0]]
        if total >= 1:
            series.append(p[1] * sd)
        if total >= 2:
            series.append(p[1] * sdd + p[2] * sd**2)
        if total >= 3:
            series.append(3.0 * p[2] * sd * sdd + p[3] * sd**3)
        return series[self._order :]


__all__ = ["MAX_ORDER", "PathTrajectory", "TimedPath"]
