"""Protective stops along the path: :func:`protective_stop`, :func:`joint_brake_stop`.

A light curtain trips at time t of a retimed MOVE. The robot is at the path
parameter ``s_t = s(t)`` with ``x_t = s'(t)^2``; the stop brings it to rest
along the same path ``q(s)``, never leaving it.

:func:`protective_stop` keeps every limit of the retime and the grasp:

1. the shortest stop: the first grid point at rest under maximal braking,
   from the controllable sets of rest (:mod:`._stop_pass`), on the retime's
   own grid from ``s_t`` on, then again with the segments up to that point
   split into :data:`STOP_SUBDIVISION` (so the stop ends at most a quarter
   of a grid step beyond the shortest on the retime's grid);
2. the fastest profile to that point: :func:`~._solve.retime` of the
   sub-path ``[s_t, s_stop]`` (reparametrised to [0, 1], ``sigma = (s -
   s_t) / L``, ``L = s_stop - s_t``, so ``x_sigma = x_s / L^2``) from
   ``sd_start = sqrt(x_t) / L`` to rest: TOPP-RA's backward pass from rest at
   ``s_stop``, met by the trajectory's own state at t. The retimer holds
   every limit between grid points too (cuts and refinements), so the stop
   passes :func:`~._check.check_trajectory` at 1 kHz within its 1e-3
   contract. Where it adds constraints the grid-point pass did not see and
   ``s_stop`` is no longer reachable at rest, the next candidates are tried
   (1, 2, 4, ... grid points further); at the path's end the stop is the
   retimed trajectory itself, which ends at rest.

A grasp of a set of objects (``ObjectSetGrasp``): step 1 brakes under the
nominal object's rows (a stop no longer than the set's), step 2 retimes
under every object of the set (the retimer's exact set rows), and the
candidates grow from there until the whole set holds. With jerk limits
too, the jerk-limited stops hold every object's rows (as the retimer's).

With jerk limits (``limits.jerk``) the stop is :mod:`._jerk_stop`'s instead:
from the MOVE's own ``(s, s', s'')`` at t, the path acceleration continuous
there, the jerk-limited retime of the sub-path over a searched stop
distance; step 1 gives its lower bound, a jerk-limited braking simulated
on step 1's samples (:func:`._stop_distance.braking_distance`, times
:data:`GUESS_FACTOR`) the distance the search starts from. The whole motion is then a
:class:`._spliced_path.SplicedPath` (the MOVE up to t, then the stop).

:func:`joint_brake_stop` is what robots do today: each joint brakes as hard
as its acceleration limit allows, along the path, under the joint velocity
and acceleration limits only (no grasp, no torques).

Without jerk limits, jerk is not limited on either stop: the path
acceleration jumps at t (as TOPP-RA's does between segments).
"""

from __future__ import annotations

import dataclasses
import functools

import numpy as np
from pydrake.multibody.plant import MultibodyPlant
from pydrake.systems.framework import Context

from rt_drake import arguments
from rt_drake.dynamics.cup_frame import CupFrame
from rt_drake.retiming._jerk_stop import JerkStopProblem, jerk_stop
from rt_drake.retiming._jerk_timed_path import JerkTimedPath
from rt_drake.retiming._joint_path import JointPath, PathLike, as_joint_path
from rt_drake.retiming._retime_errors import (
    PathNotControllableError,
    RetimeError,
    RetimeInputError,
)
from rt_drake.retiming._samples import PathSamples, sample_path
from rt_drake.retiming._solve import RetimeResult, retime
from rt_drake.retiming._stop_distance import braking_distance
from rt_drake.retiming._stop_pass import REST_X, StopPass, grid_constraints, stop_pass
from rt_drake.retiming._stop_result import (
    STANDSTILL_S,
    StopResult,
    at_rest,
    joined,
    remainder,
    spliced,
)
from rt_drake.retiming._sub_path import STOP_GRIDPOINTS, stop_grid, sub_path
from rt_drake.retiming.grid import MIN_STEP
from rt_drake.retiming.limits import GRASP_ATTRIBUTES, GraspConstraint, JointLimits

#: The jerk-limited stop's search starts from this factor times the simulated
#: braking distance (:func:`._stop_distance.braking_distance`), which fell
#: 3-50 % short of the stop distance found (median 13 %) on the MOVE-like
#: paths of ``benchmarks/bench_stop.py``.
GUESS_FACTOR = 1.1
#: Parts each grid segment up to the first stop point is split into, for a
#: second braking pass (a stop at most a fine step longer than the shortest).
STOP_SUBDIVISION = 4


class StopNotFoundError(RetimeError):
    """The state at t cannot be brought to rest within the path's limits."""


def protective_stop(
    plant: MultibodyPlant,
    path: PathLike,
    limits: JointLimits,
    result: RetimeResult,
    t: float,
    grasp: GraspConstraint | None = None,
    *,
    context: Context | None = None,
    cup: CupFrame | None = None,
) -> StopResult:
    """The fastest stop to rest from time ``t`` of ``result`` that keeps the grasp.

    Args:
        plant: The retimer's plant, as given to
            :func:`~rt_drake.retiming.retime` for ``result``.
        path: The path ``result`` retimed.
        limits: Its joint limits (torques kept if ``limits.torque``).
        result: The retimed trajectory.
        t: When the stop begins, s, in ``[start_time, end_time]`` of
            ``result.trajectory``.
        grasp: Its grasp (one held object, or a set of objects); None: no
            object.
        context: Scratch context of ``plant``.
        cup: The cup frame C (default: the plant's ``suction_cup``).

    Returns:
        The stop; velocity, acceleration, torque (if limited) and grasp
        limits hold throughout.

    Raises:
        RetimeInputError: ``t`` not a finite number inside the trajectory,
            or a malformed argument.
        StopNotFoundError: the state at t cannot be brought to rest within
            the path (not for a trajectory this retimer made).
    """
    return _stop(plant, path, limits, result, t, grasp, context, cup, True)


def guided_stop(
    plant: MultibodyPlant,
    path: PathLike,
    limits: JointLimits,
    result: RetimeResult,
    t: float,
    grasp: GraspConstraint | None,
    context: Context | None,
    cup: CupFrame | None,
    guess: float | None,
    *,
    simulate: bool = True,
) -> StopResult:
    """:func:`protective_stop` with a guess of the stop distance in s.

    With jerk limits, the search over the stop distance walks from
    ``guess`` (a neighbouring instant's stop distance,
    :func:`._jerk_stop.jerk_stop`); None: from the simulated braking's, or,
    if not ``simulate``, the full search from ``L_0`` (the reference
    ``benchmarks/bench_stop.py`` compares with). Without jerk limits:
    exactly :func:`protective_stop`.
    """
    return _stop(
        plant, path, limits, result, t, grasp, context, cup, True, guess, simulate
    )


def joint_brake_stop(
    plant: MultibodyPlant,
    path: PathLike,
    limits: JointLimits,
    result: RetimeResult,
    t: float,
    *,
    context: Context | None = None,
    cup: CupFrame | None = None,
) -> StopResult:
    """The stop robots make today: the joints brake at their limits, grasp ignored.

    The fastest stop along the path from time ``t`` of ``result`` under the
    joint velocity and acceleration limits only (torques and grasp are not
    constrained). Arguments and errors as :func:`protective_stop`.
    """
    if isinstance(limits, JointLimits):
        limits = dataclasses.replace(limits, torque=None)
    return _stop(plant, path, limits, result, t, None, context, cup, False)


def _stop(
    plant: MultibodyPlant,
    path: PathLike,
    limits: JointLimits,
    result: RetimeResult,
    t: float,
    grasp: GraspConstraint | None,
    context: Context | None,
    cup: CupFrame | None,
    grasp_aware: bool,
    guess: float | None = None,
    simulate: bool = True,
) -> StopResult:
    """Both stops (see the module docstring); ``guess``: see :func:`guided_stop`."""
    _check_objects(plant, limits, result, grasp, context, cup)
    spline = as_joint_path(path)
    if spline.num_joints != limits.num_joints:
        raise RetimeInputError(
            f"stop: path has {spline.num_joints} joints but {limits.num_joints=}"
        )
    s_t, sd_t, sdd_t = path_state_at(result, t)
    context = context or plant.CreateDefaultContext()
    cup = cup or CupFrame.of(plant)
    smooth = isinstance(result.trajectory, JerkTimedPath) or limits.jerk is not None
    if smooth and (sd_t * sd_t <= REST_X or s_t >= 1.0 - MIN_STEP):
        return spliced(result, float(t), s_t, sd_t, None, grasp_aware)
    if sd_t * sd_t <= REST_X:  # at rest already: the trajectory up to t
        return at_rest(result, spline, float(t), s_t, sd_t, grasp_aware)
    if s_t >= 1.0 - MIN_STEP:  # at the end already: the MOVE rests there
        stop_s, stop_x = remainder(result, s_t, sd_t)
        return joined(result, spline, float(t), s_t, sd_t, stop_s, stop_x, grasp_aware)
    s_grid = result.gridpoints  # it ends at 1
    held = None if grasp is None else grasp.held
    F, g = (None, None) if grasp is None else (grasp.F, grasp.g)

    def brake(s: np.ndarray) -> tuple[StopPass, PathSamples]:
        samples = sample_path(
            plant, spline, s, limits.velocity, limits.torque is not None, held,
            context, cup,
        )  # fmt: skip
        rows = grid_constraints(samples, limits, F, g)
        return stop_pass(rows, s, sd_t * sd_t), samples

    s = np.concatenate([[s_t], s_grid[s_grid > s_t + MIN_STEP]])
    braking, ahead = brake(s)
    if braking.stop_index is not None:  # again, on a finer grid up to there
        index = braking.stop_index
        head = subdivided(s[: index + 1], STOP_SUBDIVISION)
        fine, _ = brake(head)  # rest at s[index] reachable: its controllable sets
        if fine.stop_index is not None:
            s, braking = np.concatenate([head, s[index + 1 :]]), fine
    if limits.jerk is not None:
        problem = JerkStopProblem(
            plant, spline, limits, grasp, context, cup, float(t), s_t, sd_t, sdd_t,
            s_grid, result.sd**2,
        )  # fmt: skip
        at = 1 if braking.stop_index is None else braking.stop_index
        rest_time = result.trajectory.end_time() - float(t)
        if guess is None and simulate:  # the simulated jerk-limited braking's
            simulated = braking_distance(
                ahead, spline(ahead.s, 3), limits, F, g, sd_t, sdd_t
            )
            guess = GUESS_FACTOR * simulated if simulated > 0.0 else None
        found = jerk_stop(problem, float(s[at] - s_t), rest_time, guess)
        return spliced(result, float(t), s_t, sd_t, found, grasp_aware)
    if braking.stop_index is None:
        raise StopNotFoundError(
            f"no stop to rest within the path from t = {t:.4f} s (s = {s_t:.4f}, "
            f"s' = {sd_t:.4g} 1/s): the state is outside the set from which rest "
            f"is reachable",
            s=s_t,
        )
    for index in _candidates(braking.stop_index, len(s) - 1):
        if index == len(s) - 1 and s[index] >= 1.0 - MIN_STEP:
            stop_s, stop_x = remainder(result, s_t, sd_t)
        else:
            try:
                stop_s, stop_x = _retimed_stop(
                    plant, spline, limits, grasp, context, cup, s, index, sd_t
                )
            except PathNotControllableError:
                continue
        return joined(result, spline, float(t), s_t, sd_t, stop_s, stop_x, grasp_aware)
    raise AssertionError("the path's end is always a candidate")  # pragma: no cover


def state_at(result: RetimeResult, t: float) -> tuple[float, float]:
    """``(s(t), s'(t))`` of a retimed trajectory (see :func:`path_state_at`)."""
    s, sd, _ = path_state_at(result, t)
    return s, sd


def path_state_at(result: RetimeResult, t: float) -> tuple[float, float, float]:
    """``(s(t), s'(t), s''(t))`` of a retimed trajectory (exact, from its profile).

    Without jerk limits, within segment k, ``s = s_k + s'_k tau + u_k tau^2
    / 2``, ``s' = s'_k + u_k tau``, ``s'' = u_k`` with ``tau = t - t_k``;
    with them, the :class:`JerkTimedPath`'s own state.

    Raises:
        RetimeInputError: ``t`` not a finite number in ``[t0, tf]``.
    """
    trajectory = result.trajectory
    times = trajectory.times
    if not (
        isinstance(t, (int, float, np.number))
        and not isinstance(t, bool)
        and np.isfinite(t)
    ):
        raise RetimeInputError(f"stop: t must be a finite number (s), got {t!r}")
    if not times[0] <= t <= times[-1]:
        raise RetimeInputError(
            f"stop: t = {t!r} s is outside the trajectory "
            f"[{times[0]:.6g}, {times[-1]:.6g}] s"
        )
    if isinstance(trajectory, JerkTimedPath):
        s, sd, sdd, _ = (float(v[0]) for v in trajectory.path_state(float(t)))
        return s, sd, sdd
    k = int(np.clip(np.searchsorted(times, t, side="right") - 1, 0, len(times) - 2))
    tau = float(t) - times[k]
    u = result.sdd[k]
    sd = max(result.sd[k] + u * tau, 0.0)
    s = min(result.gridpoints[k] + result.sd[k] * tau + 0.5 * u * tau**2, 1.0)
    return float(s), float(sd), float(u)


def subdivided(s: np.ndarray, parts: int) -> np.ndarray:
    """The grid ``s`` with each segment split into ``parts`` equal ones."""
    steps = np.arange(parts) / parts
    fine = (s[:-1, None] + np.diff(s)[:, None] * steps).ravel()
    return np.append(fine, s[-1])


def _candidates(first: int, last: int) -> list[int]:
    """Grid indices to try: ``first``, then 1, 2, 4, ... further, then ``last``."""
    out, step = [first], 1
    while out[-1] < last:
        out.append(min(first + step, last))
        step *= 2
    return out


def _retimed_stop(
    plant: MultibodyPlant,
    spline: JointPath,
    limits: JointLimits,
    grasp: GraspConstraint | None,
    context: Context,
    cup: CupFrame,
    s: np.ndarray,
    index: int,
    sd_t: float,
) -> tuple[np.ndarray, np.ndarray]:
    """The retimed sub-path from ``s[0]`` to rest at ``s[index]``: (s, x) grid.

    Raises:
        PathNotControllableError: the state at ``s[0]`` cannot reach rest
            there under the retimer's constraints (or only from a lower
            speed, after TOPP-RA's safeguard lowered it).
    """
    start, length = s[0], s[index] - s[0]
    sub = sub_path(spline, start, s[index])
    grid = stop_grid(s[1:index], start, length)
    stop = retime(
        plant, sub, limits, grasp, grid, sd_start=sd_t / length, context=context,
        cup=cup,
    )  # fmt: skip
    if abs(length * stop.sd[0] - sd_t) > 1e-9 * max(sd_t, 1.0):
        # TOPP-RA's forward pass lowered the start (its safeguard when the
        # start is on the edge of K_0): not the trajectory's state at t.
        raise PathNotControllableError("the stop does not start at s'(t)", s=start)
    return start + length * stop.gridpoints, (length * stop.sd) ** 2


def _check_objects(
    plant: object,
    limits: object,
    result: object,
    grasp: object,
    context: object,
    cup: object,
) -> None:
    """Refuse arguments of the wrong type, naming them."""
    check = functools.partial(arguments.instance, where="stop", error=RetimeInputError)
    check(plant, "plant", MultibodyPlant)
    check(limits, "limits", JointLimits)
    check(result, "result", RetimeResult)
    if grasp is not None:
        arguments.having(
            grasp, "grasp", "GraspConstraint", GRASP_ATTRIBUTES, where="stop",
            error=RetimeInputError,
        )  # fmt: skip
    if context is not None:
        check(context, "context", Context)
    if cup is not None:
        check(cup, "cup", CupFrame)


__all__ = [
    "STANDSTILL_S",
    "STOP_GRIDPOINTS",
    "GUESS_FACTOR",
    "STOP_SUBDIVISION",
    "StopNotFoundError",
    "StopResult",
    "guided_stop",
    "joint_brake_stop",
    "protective_stop",
    "state_at",
    "sub_path",
    "subdivided",
]
