"""A joint trajectory sampled on a controller's fixed grid, padded at rest.

A controller in a fixed-period mode (Denso b-CAP slave mode every 8 ms, UR
RTDE ``servoJ`` at 500 Hz) takes one sample per period and nothing else, so
the samples lie on the grid ``t_k = k T`` (T the period, s; k = 0..N, times
from the trajectory's start). The grid is never cut short: with D the
duration, ``N = ceil(D / T)`` so ``t_N = N T >= D``, and every sample at
``t_k >= D`` is the rest state ``(q(D), 0, 0)``: the last pose, zero
velocity, zero acceleration. Before D the samples are the trajectory's own
``q(t_k)``, ``q'(t_k)``, ``q''(t_k)`` (rad, rad/s, rad/s^2), not a re-fit.

A trajectory is a Drake ``Trajectory`` with derivatives (the retimer's
:class:`~rt_drake.retiming.TimedPath`, evaluated vectorised) or a
:class:`~rt_drake.retiming.SavedTrajectory` (an ``.npz`` file's arrays),
whose motion is rebuilt exactly from its path and profile: the clamped
cubic spline through ``waypoints`` at ``knots`` and ``x = s'^2`` at the
``gridpoints``, as :func:`~rt_drake.retiming.retime` made it.
"""

from __future__ import annotations

import dataclasses
import math
from typing import TypeAlias

import numpy as np
from pydrake.trajectories import Trajectory
from scipy.interpolate import CubicSpline

from rt_drake import arguments
from rt_drake.errors import InputError, TooLargeError
from rt_drake.retiming import (
    JerkTimedPath,
    RetimeInputError,
    SavedTrajectory,
    TimedPath,
)

#: Most samples an export holds (1000 s at 1 kHz).
MAX_SAMPLES = 1_000_000
#: rad/s: the largest joint speed at the end of a trajectory padded at rest.
REST_SPEED = 1e-6
#: A period must be a whole number of nanoseconds (ROS time) to this, ns.
NANOSECOND_TOLERANCE = 1e-3

#: What can be sampled: a Drake Trajectory with derivatives, or a file's arrays.
Sampleable: TypeAlias = Trajectory | SavedTrajectory


@dataclasses.dataclass(frozen=True, eq=False)
class GridSamples:
    """Samples on the grid ``t_k = k period`` (see the module docstring).

    Attributes:
        t: (N+1,) s from the trajectory's start, ``k period``.
        q, qd, qdd: (N+1, n) rad, rad/s, rad/s^2.
        period: s.
        period_ns: The period in whole nanoseconds (``time_from_start``).
        duration: s, the trajectory's duration D (``t[-1] >= D``).
    """

    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray
    period: float
    period_ns: int
    duration: float

    @property
    def time_ns(self) -> np.ndarray:
        """(N+1,) ``k period_ns``: each sample's time from the start, ns."""
        return np.arange(len(self.t), dtype=np.int64) * self.period_ns


def as_trajectory(trajectory: Sampleable, where: str) -> Trajectory:
    """``trajectory`` as a Drake Trajectory (a saved one's motion rebuilt).

    Raises:
        InputError: not a trajectory, or a saved one whose path or profile
            is malformed (each message names ``where`` and the key).
    """
    if isinstance(trajectory, SavedTrajectory):
        return _saved_motion(trajectory, where)
    arguments.instance(
        trajectory, "trajectory", (Trajectory, SavedTrajectory), where=where
    )
    if trajectory.cols() != 1 or not trajectory.has_derivative():
        raise InputError(
            f"{where}: trajectory must be a column vector with derivatives, got "
            f"{type(trajectory).__name__} of {trajectory.rows()} x {trajectory.cols()}"
            f"{'' if trajectory.has_derivative() else ' without derivatives'}"
        )
    return trajectory


def _saved_motion(saved: SavedTrajectory, where: str) -> TimedPath | JerkTimedPath:
    """The motion of a file's path and profile, every key checked first.

    ``waypoints`` (K, n) finite; ``knots`` (K,) and ``gridpoints`` (N+1,)
    strictly increasing from 0 to 1; ``sd`` (N+1,) finite, >= 0, never zero
    at both ends of a segment (the motion would never end).
    """
    waypoints = arguments.array(
        saved.waypoints, "key 'waypoints'", ("K", "n"), where=where
    )
    for key, size in (("knots", len(waypoints)), ("gridpoints", None)):
        values = arguments.array(
            getattr(saved, key), f"key '{key}'", ("N",), where=where
        )
        if size is not None and len(values) != size:
            raise InputError(
                f"{where}: key '{key}' has {len(values)} values for {size} waypoints"
            )
        if (
            len(values) < 2
            or np.any(np.diff(values) <= 0.0)
            or abs(values[0]) > 1e-9
            or abs(values[-1] - 1.0) > 1e-9
        ):
            raise InputError(
                f"{where}: key '{key}' must increase strictly from 0 to 1, got "
                f"{arguments.describe(values)} from {values[0]!r} to {values[-1]!r}"
            )
    gridpoints = np.asarray(saved.gridpoints, dtype=float)
    sd = arguments.array(saved.sd, "key 'sd'", (len(gridpoints),), where=where)
    if np.any(sd < 0.0) or np.any(sd[:-1] + sd[1:] <= 0.0):
        raise InputError(
            f"{where}: key 'sd' must be >= 0 and not zero at both ends of a "
            f"segment, got min {sd.min()!r}"
        )
    spline = CubicSpline(saved.knots, waypoints, bc_type="clamped")
    if len(saved.path_acceleration):  # retimed with jerk limits: s'' continuous
        u = arguments.array(
            saved.path_acceleration,
            "key 'path_acceleration'",
            (len(gridpoints),),
            where=where,
        )
        try:
            return JerkTimedPath(spline, gridpoints, sd**2, u)
        except RetimeInputError as error:
            raise InputError(f"{where}: key 'path_acceleration': {error}") from None
    return TimedPath(spline, gridpoints, sd**2)


def sample_on_grid(trajectory: Sampleable, period: float, where: str) -> GridSamples:
    """Sample ``trajectory`` every ``period`` s, padded at rest to the grid.

    Raises:
        InputError: ``period`` not finite and > 0, not a whole number of
            nanoseconds, or longer than the trajectory; a trajectory that
            does not end at rest (joint speed above :data:`REST_SPEED`).
        TooLargeError: more than :data:`MAX_SAMPLES` samples.
    """
    motion = as_trajectory(trajectory, where)
    period = arguments.number(period, "period", where=where, above=0.0)
    period_ns = round(period * 1e9)
    if period_ns < 1 or abs(period * 1e9 - period_ns) > NANOSECOND_TOLERANCE:
        raise InputError(
            f"{where}: period must be a whole number of nanoseconds (ROS time), "
            f"got {period!r} s"
        )
    start, end = motion.start_time(), motion.end_time()
    duration = end - start
    if period > duration:
        raise InputError(
            f"{where}: period {period:g} s is longer than the trajectory "
            f"({duration:.6g} s): a controller would see only its two ends"
        )
    steps = math.ceil(duration / period)
    if steps + 1 > MAX_SAMPLES:
        raise TooLargeError(
            f"{where}: a {duration:.4g} s trajectory every {period:g} s gives "
            f"{steps + 1} samples; at most {MAX_SAMPLES} are exported"
        )
    t = np.arange(steps + 1) * period
    moving = t < duration
    q_end, qd_end = _evaluate(motion, np.array([end]))[:2]
    speed = float(np.max(np.abs(qd_end)))
    if speed > REST_SPEED:
        raise InputError(
            f"{where}: trajectory ends moving (joint speed {speed:.3g} rad/s at "
            f"t = {end:.6g} s): it cannot be padded with rest samples"
        )
    n = motion.rows()
    q = np.repeat(q_end, len(t), axis=0)  # the rest samples: q(D), 0, 0
    qd, qdd = np.zeros((len(t), n)), np.zeros((len(t), n))
    q[moving], qd[moving], qdd[moving] = _evaluate(motion, start + t[moving])
    return GridSamples(
        t=t, q=q, qd=qd, qdd=qdd, period=period, period_ns=period_ns,
        duration=duration,
    )  # fmt: skip


def _evaluate(motion: Trajectory, times: np.ndarray) -> list[np.ndarray]:
    """``[q, q', q'']`` at ``times``, each (M, n): vectorised for the retimer's."""
    if isinstance(motion, (TimedPath, JerkTimedPath)):
        return motion.sample(times, order=2)
    return [
        np.array([motion.EvalDerivative(ti, order).ravel() for ti in times]).reshape(
            len(times), motion.rows()
        )
        for order in range(3)
    ]


__all__ = [
    "MAX_SAMPLES",
    "GridSamples",
    "Sampleable",
    "as_trajectory",
    "sample_on_grid",
]
