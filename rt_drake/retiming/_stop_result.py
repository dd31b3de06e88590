"""A protective stop's result, and the whole motion: the MOVE up to t, then the stop.

Profiles on the path grid ``s`` with ``x = s'^2`` (1/s^2); times in s. The
whole motion is the MOVE's own profile up to ``s_t`` joined to the stop's
(a :class:`._timed_path.TimedPath`), or, for a jerk-limited MOVE or stop, the
MOVE itself up to t then the stop (a :class:`._spliced_path.SplicedPath`,
q, q' and q'' continuous at t).
"""

from __future__ import annotations

import dataclasses

import numpy as np
from pydrake.trajectories import PiecewisePolynomial, Trajectory

from rt_drake.retiming._jerk_stop import JerkStop
from rt_drake.retiming._jerk_timed_path import JerkTimedPath
from rt_drake.retiming._joint_path import JointPath
from rt_drake.retiming._solve import RetimeResult
from rt_drake.retiming._spliced_path import SplicedPath
from rt_drake.retiming._stop_pass import REST_X
from rt_drake.retiming._timed_path import PathTrajectory, TimedPath
from rt_drake.retiming.grid import MIN_STEP

#: s: how long the trajectory of a stop at the very start (the robot at rest
#: there) holds the start configuration.
STANDSTILL_S = 1e-3


@dataclasses.dataclass(frozen=True, eq=False)
class StopResult:
    """A protective stop (:mod:`._stop`).

    Attributes:
        trajectory: The whole motion, q(t): the retimed trajectory up to
            ``start_time``, then the stop; it ends at rest at ``s_stop``
            (a ``TimedPath``, or a ``SplicedPath`` for a jerk-limited MOVE
            or stop; at t = the start, where the robot is at
            rest, it holds the start for :data:`STANDSTILL_S`).
        stop: The stop alone, from t to rest (at rest at t: holding q(t)
            for :data:`STANDSTILL_S`).
        start_time: t, s: when the stop begins.
        duration: s from t to rest (0 if at rest at t).
        s_start: Path parameter at t.
        sd_start: Path velocity ``s'(t)``, 1/s.
        s_stop: Path parameter where the robot comes to rest.
        grasp_aware: Whether the grasp (and torques, if limited) were kept.
    """

    trajectory: Trajectory
    stop: Trajectory
    start_time: float
    duration: float
    s_start: float
    sd_start: float
    s_stop: float
    grasp_aware: bool

    @property
    def end_time(self) -> float:
        """Time (s) at which the robot is at rest."""
        return self.start_time + self.duration


def remainder(
    result: RetimeResult, s_t: float, sd_t: float
) -> tuple[np.ndarray, np.ndarray]:
    """The retimed trajectory itself from ``s_t`` to its end at rest: (s, x)."""
    s = result.gridpoints
    later = s > s_t + MIN_STEP
    later[-1] = True  # s = 1, where it rests
    return (
        np.concatenate([[s_t], s[later]]),
        np.concatenate([[sd_t * sd_t], result.sd[later] ** 2]),
    )


def joined(
    result: RetimeResult,
    spline: JointPath,
    t: float,
    s_t: float,
    sd_t: float,
    stop_s: np.ndarray,
    stop_x: np.ndarray,
    grasp_aware: bool,
) -> StopResult:
    """The retimed trajectory up to ``s_t``, then the stop profile, as one."""
    before = kept_before(result.gridpoints, s_t)
    grid = np.concatenate([result.gridpoints[before], stop_s])
    x = np.concatenate([result.sd[before] ** 2, [sd_t * sd_t], stop_x[1:]])
    start = result.trajectory.start_time()
    stop_alone = TimedPath(spline, stop_s, np.append(sd_t * sd_t, stop_x[1:]), t)
    whole: PathTrajectory = TimedPath(spline, grid, x, start)
    if isinstance(result.trajectory, JerkTimedPath):  # the MOVE itself up to t
        whole = SplicedPath(result.trajectory, t, stop_alone)
    return StopResult(
        trajectory=whole,
        stop=stop_alone,
        start_time=t,
        duration=stop_alone.duration,
        s_start=s_t,
        sd_start=sd_t,
        s_stop=float(stop_s[-1]),
        grasp_aware=grasp_aware,
    )


def spliced(
    result: RetimeResult,
    t: float,
    s_t: float,
    sd_t: float,
    found: JerkStop | None,
    grasp_aware: bool,
) -> StopResult:
    """A stop joined to the MOVE at t in q, q' and q'' (:class:`SplicedPath`).

    ``found`` None: at rest at t (the stop holds q(t)), or at the path's end;
    a ``JerkStop`` without a stop: the MOVE's own rest of the path.
    """
    move = result.trajectory
    if found is not None and found.stop is not None:
        stop: PathTrajectory = found.stop
        whole = SplicedPath(move, t, stop)
        s_stop = found.s_stop
    elif found is None and sd_t * sd_t <= REST_X:
        stop = SplicedPath(move, t, None, start=t, end=t + STANDSTILL_S)
        return StopResult(
            SplicedPath(move, t, None, end=t + STANDSTILL_S), stop, t, 0.0, s_t,
            sd_t, s_t, grasp_aware,
        )  # fmt: skip
    else:  # the MOVE itself, from t to its end at rest
        stop = SplicedPath(move, t, move, start=t)
        whole, s_stop = move, 1.0
    return StopResult(
        trajectory=whole,
        stop=stop,
        start_time=t,
        duration=float(stop.end_time() - t),
        s_start=s_t,
        sd_start=sd_t,
        s_stop=float(s_stop),
        grasp_aware=grasp_aware,
    )


def kept_before(s: np.ndarray, s_t: float) -> np.ndarray:
    """Grid points kept before ``s_t``: the start, and those MIN_STEP before it.

    A point closer to ``s_t`` would make a segment too short for its path
    acceleration to be computed from x (rounding over a step of 1e-12); the
    profile changes by at most ``2 MIN_STEP |u|`` in x without it.
    """
    before = s < s_t - MIN_STEP
    before[0] = s[0] < s_t
    return before


def at_rest(
    result: RetimeResult,
    spline: JointPath,
    t: float,
    s_t: float,
    sd_t: float,
    grasp_aware: bool,
) -> StopResult:
    """A stop of no duration: the robot is at rest at t (the path's ends)."""
    s = result.gridpoints
    before = kept_before(s, s_t)
    q = spline(s_t).reshape(-1, 1)
    hold = PiecewisePolynomial.FirstOrderHold([t, t + STANDSTILL_S], np.hstack([q, q]))
    trajectory: Trajectory = hold
    if before.any():
        grid = np.append(s[before], s_t)
        x = np.append(result.sd[before] ** 2, 0.0)
        trajectory = TimedPath(spline, grid, x, result.trajectory.start_time())
    return StopResult(trajectory, hold, t, 0.0, s_t, sd_t, s_t, grasp_aware)


__all__ = [
    "STANDSTILL_S",
    "StopResult",
    "at_rest",
    "joined",
    "kept_before",
    "remainder",
    "spliced",
]
