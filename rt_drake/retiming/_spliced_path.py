"""One motion up to a switch time, another after it: a protective stop's q(t).

``q(t) = q_1(t)`` for ``t < t_s`` and ``q_2(t)`` for ``t >= t_s`` (with their
derivatives, rad, rad/s, rad/s^2, rad/s^3), on ``[start, end]``. Without a
second motion the robot rests at ``q_1(t_s)`` after ``t_s`` (velocity and
higher derivatives 0). The two motions meet at ``t_s`` in q, q' and, for a
jerk-limited stop, q'' (the stop starts from the first motion's state there).
"""

from __future__ import annotations

import numpy as np
from pydrake.trajectories import Trajectory

from rt_drake.retiming._retime_errors import RetimeInputError
from rt_drake.retiming._timed_path import MAX_ORDER, PathTrajectory


class SplicedPath(PathTrajectory):
    """``first`` before ``switch``, then ``second`` (or rest), on ``[start, end]``.

    Args:
        first: q(t) before the switch (a ``PathTrajectory``).
        switch: t_s, s.
        second: q(t) from the switch on; None: rest at ``first``'s q(t_s).
        start: Start time, s (default: ``first``'s).
        end: End time, s (default: ``second``'s).
        derivative_order: 0 for q(t); k for its k-th derivative (<= 3).
    """

    def __init__(
        self,
        first: PathTrajectory,
        switch: float,
        second: PathTrajectory | None = None,
        start: float | None = None,
        end: float | None = None,
        derivative_order: int = 0,
    ) -> None:
        Trajectory.__init__(self)
        t0 = first.start_time() if start is None else float(start)
        if end is None:
            if second is None:
                raise RetimeInputError("a spliced path at rest needs an end time")
            end = second.end_time()
        if not t0 <= switch <= float(end):
            raise RetimeInputError(f"switch {switch} outside [{t0}, {end}] s")
        self._first, self._second, self._switch = first, second, float(switch)
        self._spline = first._spline
        self._t = np.array([t0, float(end)])
        self._order = int(derivative_order)

    def sample(self, times: float | np.ndarray, order: int = 2) -> list[np.ndarray]:
        """Return ``[q, q', ..., q^(order)]`` at each time, each (M, n)."""
        total = self._order + order
        if total > MAX_ORDER:
            raise RetimeInputError(f"derivatives above order {MAX_ORDER} not provided")
        times = np.clip(np.atleast_1d(np.asarray(times, dtype=float)), *self._t)
        before = np.less(times, self._switch)[:, None]
        early = self._first.sample(np.minimum(times, self._switch), total)
        if self._second is None:
            late = [np.broadcast_to(self._hold(), early[0].shape)]
            late += [np.zeros_like(v) for v in early[1:]]
        else:
            late = self._second.sample(np.maximum(times, self._switch), total)
        series = [np.where(before, a, b) for a, b in zip(early, late, strict=True)]
        return series[self._order :]

    def _hold(self) -> np.ndarray:
        """The configuration (1, n) at the switch, where the robot rests."""
        return self._first.sample(np.array([self._switch]), 0)[0]


__all__ = ["SplicedPath"]
