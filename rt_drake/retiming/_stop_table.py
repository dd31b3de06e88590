"""Protective stops computed ahead: :func:`stop_table` and :meth:`StopTable.at`.

A grasp-aware stop under jerk limits solves several jerk-limited retimes
(:mod:`._jerk_stop`): too slow to compute when the light curtain trips. A
cell computes them while the MOVE is planned, for the instants

    ``t_k = t_0 + k * period``, ``k = 0, 1, ...`` while ``t_k < t_f``, and ``t_f``

(``t_0``, ``t_f``: the trajectory's start and end times, s). A trip at time
``t`` takes the stop starting at the first ``t_k >= t``: the robot follows
the MOVE until then, as a controller does within its reaction latency (at
most one period).

Each stop is :func:`._stop.protective_stop`'s at ``t_k``. Under jerk
limits, the search over the stop distance starts from the previous
instant's stop distance scaled by the change of a 1-D model's
(:mod:`._stop_distance`; :func:`._stop.guided_stop`), and from a simulated
jerk-limited braking's (as a stop computed alone) at the first instant and
after the MOVE's own remainder. Without jerk limits each stop is computed
alone (a few ms).
"""

from __future__ import annotations

import dataclasses

import numpy as np
from pydrake.multibody.plant import MultibodyPlant
from pydrake.systems.framework import Context

from rt_drake import arguments
from rt_drake.dynamics.cup_frame import CupFrame
from rt_drake.retiming._joint_path import PathLike, as_joint_path
from rt_drake.retiming._retime_errors import RetimeInputError
from rt_drake.retiming._solve import RetimeResult
from rt_drake.retiming._stop import guided_stop, path_state_at
from rt_drake.retiming._stop_distance import path_stop_distance
from rt_drake.retiming._stop_result import StopResult
from rt_drake.retiming.limits import GraspConstraint, JointLimits


@dataclasses.dataclass(frozen=True, eq=False)
class StopTable:
    """Grasp-aware stops at the instants ``t_k`` of a MOVE.

    Attributes:
        times: (K,) the instants ``t_k`` (s), increasing, the last the
            trajectory's end time.
        stops: The K stops, ``stops[k]`` starting at ``times[k]``.
        period: s between instants.
    """

    times: np.ndarray
    stops: tuple[StopResult, ...]
    period: float

    def at(self, t: float) -> StopResult:
        """The stop for a trip at ``t``: the one starting at the first ``t_k >= t``.

        Raises:
            RetimeInputError: ``t`` not a finite number in ``[t_0, t_f]``.
        """
        t = arguments.number(
            t, "t", where="stop table", low=float(self.times[0]),
            high=float(self.times[-1]), error=RetimeInputError,
        )  # fmt: skip
        k = int(np.searchsorted(self.times, t, side="left"))
        return self.stops[min(k, len(self.stops) - 1)]


def stop_instants(start: float, end: float, period: float) -> np.ndarray:
    """``t_k = start + k period`` while ``< end``, then ``end`` (s)."""
    count = int(np.ceil((end - start) / period - 1e-9))
    times = start + period * np.arange(max(count, 1))
    return np.append(times[times < end - 1e-9], end)


def stop_table(
    plant: MultibodyPlant,
    path: PathLike,
    limits: JointLimits,
    result: RetimeResult,
    period: float,
    grasp: GraspConstraint | None = None,
    *,
    context: Context | None = None,
    cup: CupFrame | None = None,
) -> StopTable:
    """Grasp-aware stops from every ``t_k`` of ``result`` (module docstring).

    Args:
        plant: The retimer's plant, as for
            :func:`~rt_drake.retiming.protective_stop`.
        path: The path ``result`` retimed.
        limits: Its joint limits (jerk limits: jerk-limited stops).
        result: The retimed MOVE.
        period: s between the instants (> 0): the controller's reaction
            latency at most.
        grasp: Its grasp (one held object, or a set of objects); None: no
            object.
        context: Scratch context of ``plant``.
        cup: The cup frame C (default: the plant's ``suction_cup``).

    Returns:
        The table; ``table.at(t)`` is the stop for a trip at t.

    Raises:
        RetimeInputError: a malformed argument (as ``protective_stop``), or
            ``period`` not a finite number > 0.
        StopNotFoundError: as ``protective_stop``.
    """
    period = arguments.number(
        period, "period", where="stop_table", above=0.0, error=RetimeInputError
    )
    for value, name, kind in (
        (plant, "plant", MultibodyPlant),
        (limits, "limits", JointLimits),
        (result, "result", RetimeResult),
    ):
        arguments.instance(
            value, name, kind, where="stop_table", error=RetimeInputError
        )
    trajectory = result.trajectory
    times = stop_instants(trajectory.start_time(), trajectory.end_time(), period)
    context = context or plant.CreateDefaultContext()
    spline = as_joint_path(path) if limits.jerk is not None else None
    stops: list[StopResult] = []
    previous: tuple[StopResult, float] | None = None
    for t in times:
        guess, model = None, 0.0
        if spline is not None:
            assert limits.jerk is not None
            s, sd, sdd = path_state_at(result, float(t))
            model = path_stop_distance(spline, limits, s, sd, sdd)
            guess = _guess(previous, model)
        stop = guided_stop(
            plant, path, limits, result, float(t), grasp, context, cup, guess
        )
        stops.append(stop)
        previous = (stop, model)
    return StopTable(times, tuple(stops), period)


def _guess(previous: tuple[StopResult, float] | None, model: float) -> float | None:
    """The previous instant's stop distance, scaled by the 1-D model's change.

    ``L_k = L_{k-1} m_k / m_{k-1}`` with ``m`` the 1-D stop distance of
    :mod:`._stop_distance` (it follows the MOVE's own path acceleration,
    which the stop distance depends on most); None (the stop's own guess,
    the simulated braking's) at the first instant, after a stop at rest or
    after the MOVE's own remainder.
    """
    if previous is None:
        return None
    stop, model_before = previous
    if not stop.s_start < stop.s_stop < 1.0 or model_before <= 0.0 or model <= 0.0:
        return None
    return (stop.s_stop - stop.s_start) * model / model_before


__all__ = ["StopTable", "stop_instants", "stop_table"]
