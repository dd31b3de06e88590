"""Release on arrival: how early a MOVE may close the valve (first_order vacuum).

With the ``first_order`` vacuum the suction force certain from the start
of a MOVE is ``f0 = part_present_fraction P A`` (N): "part present" fired,
and the level only rises while the valve stays on and the cup sealed. If
the valve closes ``L`` s before the MOVE ends, at ``t_c = T - L``, the level
decays as ``lambda(t) = lambda(t_c) exp(-(t - t_c) / tau_r)`` (the vacuum's
``release_tau_s``), so on ``[T - L, T]`` the force certain at every instant
is at least its value at T, ``f(L) = f0 exp(-L / tau_r)``.

The lead is the largest L for which the object's wrench ``w(t)`` (the cup
on the object, frame C, ``[torque; force]``), sampled at ``RATE_HZ`` over
``[T - L, T]`` and on both sides of every knot of the motion in that
window (the retime's grid times, where ``s''`` and so the wrench jump,
which the 1 kHz samples can straddle), stays in the cup's
wrench set for that force, shrunk by the grasp margin: ``F w <= g(f(L))``
with the rows of ``grasp_at(f(L))``
(:func:`~rt_drake.contact.with_suction_force` translates the set; the
MOVE's own rows are those of ``f0``). A larger L both lowers ``f(L)`` and
lengthens the window, so "holds" is monotone in L and a bisection over
``[0, LEAD_TAUS tau_r]`` (``LEAD_STEPS`` halvings) finds it. L = 0 always
holds (the MOVE was retimed for ``f0``): the valve then closes on arrival,
as before. :func:`with_release` gives a MOVE its lead.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable

import numpy as np
from pydrake.multibody.plant import MultibodyPlant
from pydrake.systems.framework import Context
from pydrake.trajectories import Trajectory

from rt_drake.contact import cached_wrench_polytope, with_suction_force
from rt_drake.dynamics.cup_frame import CupFrame
from rt_drake.dynamics.wrench import object_wrench
from rt_drake.model.scenario import Scenario
from rt_drake.model.vacuum import VacuumModel
from rt_drake.retiming import CupGrasp, GraspConstraint
from rt_drake.simulation._time_at import grid_times
from rt_drake.simulation.motion import Motion
from rt_drake.types.held_object import HeldObject

#: Hz: the wrench's sampling rate over the window.
RATE_HZ = 1000.0
#: The longest lead searched, in time constants ``tau_r`` (force down to 5 %).
LEAD_TAUS = 3.0
#: Halvings of the bisection (resolution ``LEAD_TAUS tau_r / 2^LEAD_STEPS``).
LEAD_STEPS = 10
#: s: how far each side of a knot its one-sided wrench is sampled.
KNOT_SIDE_S = 1e-9


def release_lead(
    plant: MultibodyPlant,
    trajectory: Trajectory,
    held: HeldObject,
    grasp_at: Callable[[float], GraspConstraint],
    force_s: float,
    release_tau_s: float,
    context: Context | None = None,
    cup: CupFrame | None = None,
    knots: np.ndarray | None = None,
) -> float:
    """The largest lead L (s) before ``trajectory``'s end at which the valve may close.

    Args:
        plant: The retimer's arm plant.
        trajectory: The MOVE, q(t) (rad) with derivatives.
        held: The held object.
        grasp_at: The grasp constraint of ``held`` for a suction force (N).
        force_s: ``f0``, N, the force certain while the valve is on.
        release_tau_s: ``tau_r``, s, the release's time constant.
        context: Scratch context of ``plant``.
        cup: The cup frame C of ``plant``.
        knots: s, times at which the motion's acceleration may jump (a
            retimed path's grid times); each in the window is also sampled
            ``KNOT_SIDE_S`` before and after it.
    """
    t0, t1 = trajectory.start_time(), trajectory.end_time()
    longest = min(LEAD_TAUS * release_tau_s, t1 - t0)
    times = np.append(np.arange(t1 - longest, t1, 1.0 / RATE_HZ), t1)
    if knots is not None:
        inside = np.asarray(knots, dtype=float)
        inside = inside[inside >= t1 - longest]
        sides = np.concatenate([inside - KNOT_SIDE_S, inside + KNOT_SIDE_S])
        times = np.unique(np.concatenate([times, np.clip(sides, t0, t1)]))
    q = np.array([trajectory.value(t).ravel() for t in times])
    v, vdot = (
        np.array([trajectory.EvalDerivative(t, k).ravel() for t in times])
        for k in (1, 2)
    )
    wrench = object_wrench(plant, held, q, v, vdot, context, cup)

    def holds(lead: float) -> bool:
        grasp = grasp_at(force_s * math.exp(-lead / release_tau_s))
        window = wrench[times >= t1 - lead - 1e-12]
        return bool(np.all(window @ grasp.F.T <= grasp.g))

    if holds(longest):
        return longest
    low, high = 0.0, longest
    for _ in range(LEAD_STEPS):
        middle = 0.5 * (low + high)
        if holds(middle):
            low = middle
        else:
            high = middle
    return low


def with_release(
    move: Motion,
    scenario: Scenario,
    plant: MultibodyPlant,
    context: Context,
    cup: CupFrame,
    speed: float,
) -> Motion:
    """``move`` with its valve closing early, if the grasp holds (:func:`release_lead`).

    Only with the ``first_order`` vacuum, one cup of a fixed suction force,
    the nominal grasp (:class:`~rt_drake.retiming.CupGrasp`) and the MOVE
    played as retimed (``speed`` 1); else ``move`` itself: the valve closes
    on arrival. ``plant``, ``context``, ``cup``: the retimer's.
    """
    vacuum = scenario.vacuum
    grasp = move.grasp
    if (
        vacuum.kind is not VacuumModel.FIRST_ORDER
        or not isinstance(grasp, CupGrasp)
        or scenario.tool is None
        and scenario.cup.is_uncertain()
        or speed != 1.0
    ):
        return move
    full = cached_wrench_polytope(scenario.cup)
    margin = move.grasp_margin

    def grasp_at(force: float) -> GraspConstraint:
        polytope = with_suction_force(full, force)
        return GraspConstraint.for_polytope(grasp.held, polytope).with_margin(margin)

    force = vacuum.part_present_fraction * scenario.cup.suction_force
    lead = release_lead(
        plant,
        move.trajectory,
        grasp.held,
        grasp_at,
        force,
        vacuum.release_tau_s,
        context,
        cup,
        knots=grid_times(move.trajectory),
    )
    if lead <= 0.0:
        return move
    floor = force * math.exp(-lead / vacuum.release_tau_s)
    guarantee = (
        f"{move.guarantee}; valve closed {lead:.3f} s before arrival "
        f"(at least {floor:.1f} N then)"
    )
    return dataclasses.replace(move, release_s=lead, guarantee=guarantee)


__all__ = [
    "KNOT_SIDE_S",
    "LEAD_STEPS",
    "LEAD_TAUS",
    "RATE_HZ",
    "release_lead",
    "with_release",
]
