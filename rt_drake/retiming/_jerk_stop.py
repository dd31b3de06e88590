"""The jerk-limited stop: from the motion's own (s, s', s'') at t to rest.

With ``limits.jerk`` the stop must start where the retimed motion is at t
in path position, velocity and acceleration (``s_t``, ``s'_t``, ``s''_t``:
the joint acceleration ``q' s'' + q'' s'^2`` is then continuous at t, so
the jerk stays bounded), and end at rest at some ``s_stop`` on the path.

For a stop distance ``L = s_stop - s_t`` the fastest such stop is the
jerk-limited retime (:func:`._jerk.jerk_limited`: TOPP-RA first, then its
LPs) of the sub-path ``sigma = (s - s_t) / L`` in [0, 1], from
``sigma' = s'_t / L`` with ``sigma'' = s''_t / L`` fixed, to rest. Its
duration ``T(L)`` is defined from the shortest feasible L on, and grows
with L from there (about 1 % per 1 % of L on the MOVE-like paths of
``benchmarks/bench_stop.py``), so the stop kept is the one at the shortest
L found with a stop. Each L tried costs one jerk-limited retime, so the
search tries few. From a guess (:func:`_walk`; :mod:`._stop` guesses by
a simulated jerk-limited braking, :mod:`._stop_table` by the previous
instant's stop): from the guess, down (or up) by growing factors until
the answer changes, then bisections to :data:`RESOLUTION`. Without a
guess (the search before guesses, kept as the reference):

1. ``L_0``: the acceleration-limited shortest stop (:mod:`._stop_pass`),
   a lower bound (a jerk limit only removes profiles);
2. ``L_k = GROWTH^k L_0`` until a stop is found (the path's end caps it:
   the motion itself ends at rest there);
3. :data:`BISECTIONS` bisections between the last L without a stop and the
   first with one.

The LPs are linearised first at the smaller of TOPP-RA's stop profile and
the motion's own (which continues from ``s''_t``: a profile TOPP-RA
alone, braking or speeding up at once, can leave the first LP without a
solution where a stop exists), then at TOPP-RA's alone.

The stop kept is the fastest found, or the motion's own remainder if that
is faster (near the end of a MOVE, in its own final braking). Every stop
holds the jerk-limited retimer's contract: every limit, jerk included, and
the grasp rows at its points, and within 1e-3 between them.
"""

from __future__ import annotations

import dataclasses
from typing import NamedTuple

import numpy as np
from pydrake.multibody.plant import MultibodyPlant
from pydrake.systems.framework import Context

from rt_drake.dynamics.cup_frame import CupFrame
from rt_drake.retiming._jerk import jerk_limited
from rt_drake.retiming._jerk_set import SetGrasp
from rt_drake.retiming._jerk_timed_path import JerkTimedPath
from rt_drake.retiming._joint_path import JointPath
from rt_drake.retiming._retime_errors import (
    LimitsBetweenGridPointsError,
    PathNotControllableError,
)
from rt_drake.retiming._samples import PathSamples, sample_path
from rt_drake.retiming._set_slack import set_slack, set_torque_slack
from rt_drake.retiming._set_tables import parameter_columns, torque_normals
from rt_drake.retiming._solve import BETWEEN_TOLERANCE, retime
from rt_drake.retiming._sub_path import stop_grid, sub_path
from rt_drake.retiming.grid import MIN_STEP
from rt_drake.retiming.limits import GraspConstraint, JointLimits, ObjectSetGrasp
from rt_drake.retiming.stage_rows import normalised_rows

#: Factor between successive stop distances tried until a stop is found.
GROWTH = 1.3
#: Relative decreases of s'_t from which TOPP-RA's profile is tried (the
#: jerk LPs themselves start at s'_t).
LOWER_START = (0.0, 1e-3, 1e-2)
#: Bisections of the stop distance between the last failure and a stop.
BISECTIONS = 4
#: Relative resolution of the stop distance when the search starts from a
#: guess (:func:`_walk`); the full search's is ``0.3 / 2^4``, about 0.019.
RESOLUTION = 0.015
#: First relative step of the walk from a guess (doubled at each step).
FIRST_STEP = 0.04


class JerkStop(NamedTuple):
    """A jerk-limited stop.

    Attributes:
        stop: q(t) from t to rest (None: the motion's own remainder).
        s_stop: Path parameter where it rests.
        tried: Stop distances L tried, each with its duration (inf: no stop).
    """

    stop: JerkTimedPath | None
    s_stop: float
    tried: list[tuple[float, float]]


@dataclasses.dataclass(frozen=True)
class JerkStopProblem:
    """What a jerk-limited stop from time t is retimed with.

    Attributes:
        plant, spline, limits, grasp, context, cup: As for the retime
            (``limits.jerk`` set; grasp of one object, of a set of objects
            (every object's grasp and torque rows, :mod:`._jerk_set`, the
            start widened by :mod:`._set_slack`), or None).
        t: s, when the stop begins.
        s: ``s_t``; sd: ``s'_t`` (1/s, > 0); sdd: ``s''_t`` (1/s^2).
        own: The motion's grid points (those after ``s_t`` are kept in each
            stop's grid).
        own_x: ``s'^2`` of the motion there (1/s^2).
    """

    plant: MultibodyPlant
    spline: JointPath
    limits: JointLimits
    grasp: GraspConstraint | None
    context: Context
    cup: CupFrame
    t: float
    s: float
    sd: float
    sdd: float
    own: np.ndarray
    own_x: np.ndarray

    def stop(self, length: float, thorough: bool = True) -> JerkTimedPath | None:
        """The fastest jerk-limited stop to rest at ``s + length`` (None: none).

        In sigma, ``x_sigma = x_s / L^2`` and ``u_sigma = u_s / L``. Not
        ``thorough``: the LPs linearised at the first profile only (the
        module docstring's), not again at TOPP-RA's alone.
        """
        sub = sub_path(self.spline, self.s, self.s + length)
        grid = stop_grid(self.own, self.s, length)
        sd, sdd = self.sd / length, self.sdd / length
        robust = self.grasp is not None and self.grasp.is_robust
        columns = layout = None
        if robust:  # every object of the set: its parameter columns
            assert isinstance(self.grasp, ObjectSetGrasp)
            columns, layout = parameter_columns(self.grasp.objects)
        held = None if self.grasp is None or robust else self.grasp.held
        torque = self.limits.torque is not None
        F = None if self.grasp is None else self.grasp.F
        g = None if self.grasp is None else self.grasp.g
        start = sample_path(
            self.plant, sub, np.zeros(1), self.limits.velocity, torque, held,
            self.context, self.cup, columns,
        )  # fmt: skip
        limits, g = start_slack(start, sd * sd, sdd, self.limits, F, g)
        objects = None
        if layout is not None and F is not None and g is not None:
            g = set_slack(start, sd * sd, sdd, F, g, layout)
            normals = None
            if limits.torque is not None:  # every object's torques
                wider_torque = set_torque_slack(
                    start, sd * sd, sdd, limits.torque, layout
                )
                limits = dataclasses.replace(limits, torque=wider_torque)
                normals = torque_normals(wider_torque)[1]
            objects = SetGrasp(normalised_rows(F, g), layout, normals)

        def sample(s: np.ndarray) -> PathSamples:
            return sample_path(
                self.plant, sub, s, limits.velocity, torque, held, self.context,
                self.cup, columns,
            )  # fmt: skip

        wider = None
        if self.grasp is not None and g is not None:
            wider = dataclasses.replace(self.grasp, g=g)
        plain = dataclasses.replace(limits, jerk=None)
        # TOPP-RA's profile is only where the LPs are linearised: from just
        # below s'_t if the state at t is on the edge of K_0.
        topp = None
        for lower in LOWER_START:
            try:
                topp = retime(
                    self.plant, sub, plain, wider, grid,
                    sd_start=sd * (1.0 - lower), context=self.context, cup=self.cup,
                )  # fmt: skip
                break
            except PathNotControllableError:
                continue
        if topp is None:
            return None
        x_topp = topp.sd**2
        x_move = np.interp(self.s + length * topp.gridpoints, self.own, self.own_x)
        profile = None
        linearisations = [np.minimum(x_topp, x_move / length**2), x_topp]
        for x_bar in linearisations[: 2 if thorough else 1]:
            try:
                profile = jerk_limited(
                    sub, sample, topp.gridpoints, x_bar, limits,
                    None if robust else F, None if robust else g, objects, sd, 0.0,
                    self.t, BETWEEN_TOLERANCE, sdd_start=sdd,
                )  # fmt: skip
                break
            except (PathNotControllableError, LimitsBetweenGridPointsError):
                continue
        if profile is None:
            return None
        return profile.trajectory


def start_slack(
    start: PathSamples,
    x: float,
    u: float,
    limits: JointLimits,
    F: np.ndarray | None,
    g: np.ndarray | None,
) -> tuple[JointLimits, np.ndarray | None]:
    """Limits and grasp offsets widened to hold the start state ``(x, u)``.

    The motion's state at t keeps each limit within the retimer's contract
    between grid points, not exactly: a limit it binds can be exceeded there
    by up to ``BETWEEN_TOLERANCE``, which would leave the stop's LPs, whose
    start is fixed, without a solution. Each limit (per joint; per grasp
    row) is widened to the start's own value where that exceeds it:
    ``x <= x_cap``, ``|q' u + q'' x| <= a``, ``|tau| <= tau_max``, ``F w <=
    g``, so the stop holds them within the motion's own excess at t.
    """
    widen = 1.0 + 1e-9
    velocity = limits.velocity * np.sqrt(max(1.0, widen * x / start.x_cap[0]))
    joint = np.abs(start.dq[0] * u + start.ddq[0] * x)
    acceleration = np.maximum(limits.acceleration, widen * joint)
    torque = limits.torque
    # A set of objects' torques (start.torque the arm's alone): set_torque_slack.
    if torque is not None and start.torque is not None and start.torque_set is None:
        a, b, c = (v[0] for v in start.torque)
        torque = np.maximum(torque, widen * np.abs(a * u + b * x + c))
    if F is not None and g is not None and start.wrench is not None:
        a, b, c = (v[0] for v in start.wrench)
        g = np.maximum(g, widen * (F @ (a * u + b * x + c)))
    wider = dataclasses.replace(
        limits, velocity=velocity, acceleration=acceleration, torque=torque
    )
    return wider, g


def jerk_stop(
    problem: JerkStopProblem,
    shortest: float,
    remainder: float,
    guess: float | None = None,
) -> JerkStop:
    """The fastest jerk-limited stop found by the module docstring's search.

    Args:
        problem: The stop's data.
        shortest: ``L_0``, the acceleration-limited shortest stop distance.
        remainder: Duration (s) of the motion's own rest of the path.
        guess: A stop distance near the shortest with a stop (a neighbouring
            instant's): the search walks from it (:func:`_walk`) instead.
    """
    if guess is not None:
        walked = _walk(problem, shortest, guess)
        if walked.stops:
            return _kept(problem, walked, remainder)
        # None found with one linearisation: the full search, thorough.
    room = 1.0 - problem.s
    tried: list[tuple[float, float]] = []
    found: dict[float, JerkTimedPath] = {}

    def attempt(length: float) -> bool:
        stop = problem.stop(length)
        tried.append((length, np.inf if stop is None else stop.duration))
        if stop is not None:
            found[length] = stop
        return stop is not None

    low, length = None, max(min(shortest, room), MIN_STEP)
    while length < room - MIN_STEP and not attempt(length):
        low, length = length, length * GROWTH
    if found and low is not None:
        high = length
        for _ in range(BISECTIONS):
            middle = 0.5 * (low + high)
            if attempt(middle):
                high = middle
            else:
                low = middle
    return _kept(problem, _Found(tried, found), remainder)


class _Found(NamedTuple):
    """Stop distances tried (each with its duration, inf: none) and the stops."""

    tried: list[tuple[float, float]]
    stops: dict[float, JerkTimedPath]


def _kept(problem: JerkStopProblem, found: _Found, remainder: float) -> JerkStop:
    """The fastest stop found, or the motion's remainder if that is faster."""
    if not found.stops:
        return JerkStop(None, 1.0, found.tried)
    best = min(found.stops, key=lambda key: found.stops[key].duration)
    if found.stops[best].duration >= remainder:
        return JerkStop(None, 1.0, found.tried)
    return JerkStop(found.stops[best], problem.s + best, found.tried)


def _walk(problem: JerkStopProblem, shortest: float, guess: float) -> _Found:
    """Stops from ``guess`` to the shortest distance with one, within RESOLUTION.

    From ``L = guess`` (at least ``shortest``): with a stop there, down by
    factors ``1 + f, 1 + 2f, 1 + 4f, ...`` (``f`` = :data:`FIRST_STEP`)
    until a distance without one; without, up by the same factors until
    one (the path's end caps it); then bisections (geometric) until the
    last distance without a stop and the first with one are within ``1 +
    r`` (``r`` = :data:`RESOLUTION`). Each distance is tried with the LPs
    linearised once (not ``thorough``: on the cases of
    ``benchmarks/bench_stop.py`` the second linearisation never found a
    stop the first missed, and a distance without a stop cost both); if
    none has a stop, :func:`jerk_stop` runs the full, thorough search.
    """
    room = 1.0 - problem.s
    found = _Found([], {})

    def attempt(length: float) -> bool:
        stop = problem.stop(length, thorough=False)
        found.tried.append((length, np.inf if stop is None else stop.duration))
        if stop is not None:
            found.stops[length] = stop
        return stop is not None

    floor = max(min(shortest, room), MIN_STEP)
    length = min(max(guess, floor), room)
    if length >= room - MIN_STEP:
        return found
    low: float | None = None
    high: float | None = None
    step = FIRST_STEP
    if attempt(length):
        high = length
        while high > floor * (1.0 + 1e-9):
            candidate = max(high / (1.0 + step), floor)
            if not attempt(candidate):
                low = candidate
                break
            high, step = candidate, 2.0 * step
    else:
        low = length
        while True:
            candidate = low * (1.0 + step)
            if candidate >= room - MIN_STEP:
                return found
            if attempt(candidate):
                high = candidate
                break
            low, step = candidate, 2.0 * step
    while low is not None and high is not None and high / low > 1.0 + RESOLUTION:
        middle = float(np.sqrt(low * high))
        if attempt(middle):
            high = middle
        else:
            low = middle
    return found


__all__ = [
    "BISECTIONS",
    "GROWTH",
    "JerkStop",
    "JerkStopProblem",
    "RESOLUTION",
    "jerk_stop",
    "start_slack",
]
