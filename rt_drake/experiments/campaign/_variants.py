"""The comparisons of a campaign: one function per :class:`Variant`.

Each variant function computes one row's :class:`RowResult` from its
:class:`Combination`: it plans the trial's MOVE (APPROACH and REACH from
home give the grasp configuration, as in Table I), retimes it, and plays it
in the physics of the cycle (:mod:`rt_drake.experiments._rollout`). A
planner with the same seed in the same scene plans the same path, so the
rows of one trial compare the same path.

The ``optimized`` row optimises the trial's spline MOVE with the transport
experiment's :func:`~rt_drake.experiments._optimized_transport.optimize_spline`
and plays the result at speed 1. Every variant but ``robust`` plans and
retimes for the nominal object and cup; the ``robust`` row retimes the same
spline path for the object's uncertainty set and the cup's range and plays
it as the robust transport experiment does
(:func:`~rt_drake.experiments._robust_transport.true_object_world`).

To add a comparison: add a member to :class:`Variant`, write its function
here, and add it to :data:`VARIANTS`.
"""

from __future__ import annotations

import dataclasses
import hashlib
import time
from collections.abc import Callable, Mapping
from types import MappingProxyType

import numpy as np

from rt_drake.errors import RtDrakeError, ScenarioError
from rt_drake.experiments._optimized_transport import optimize_spline
from rt_drake.experiments._robust_transport import true_object_world
from rt_drake.experiments._rollout import (
    SPEED_FACTORS,
    Rollout,
    critical_speed,
    rollout_scenario,
    simulate_move,
)
from rt_drake.experiments.campaign._definition import Combination
from rt_drake.experiments.campaign._row_types import (
    RowResult,
    Status,
    Variant,
)
from rt_drake.model.scenario import Scenario
from rt_drake.simulation import Motion, OnlineMotions
from rt_drake.types.object_uncertainty import ObjectUncertainty

#: A variant: one row's results from its combination.
VariantFunction = Callable[[Combination], RowResult]


@dataclasses.dataclass(frozen=True, eq=False)
class PlannedMove:
    """A trial's MOVE, planned and retimed.

    Attributes:
        q_grasp: The grasp configuration (rad), where the MOVE starts.
        move: The MOVE (its path, retiming, grasp constraint, trajectory).
        motions: The planner and retimer that made it.
        world: The rollout scenario (arm at the grasp, short waits).
        plan_s: Wall time of planning and retiming, s.
    """

    q_grasp: np.ndarray
    move: Motion
    motions: OnlineMotions
    world: Scenario
    plan_s: float

    @property
    def detail(self) -> dict[str, object]:
        """The path's fingerprint, to pair the rows of one trial."""
        assert self.move.planned is not None
        waypoints = np.ascontiguousarray(self.move.planned.path.waypoints)
        return {
            "path_sha256": hashlib.sha256(waypoints.tobytes()).hexdigest()[:16],
            "waypoints": int(waypoints.shape[0]),
        }


def plan_move(combination: Combination, grasp_constraint: bool) -> PlannedMove:
    """Plan the trial's APPROACH, REACH and MOVE; retime the MOVE.

    For the nominal object and cup (the uncertainty set and cup range, if
    any, left to the ``robust`` variant).

    Raises:
        PlanningError: no collision-free path.
        RetimeError: e.g. the object slips off the cup even at rest.
    """
    start = time.perf_counter()
    motions = OnlineMotions(
        combination.scenario,
        grasp_constraint=grasp_constraint,
        seed=combination.planner_seed,
        robust=False,
        optimize=False,  # the spline MOVE (the ``optimized`` variant shapes it)
    )
    (obj,) = combination.scenario.objects
    approach = motions.approach(motions.q_home, obj)
    reach = motions.reach(approach.q_end, obj)
    move = motions.move(reach.q_end, obj, reach)
    q_grasp = reach.q_end
    return PlannedMove(
        q_grasp,
        move,
        motions,
        rollout_scenario(combination.scenario, q_grasp),
        time.perf_counter() - start,
    )


def _row(
    planned: PlannedMove,
    speed: float,
    rollout: Rollout,
    simulate_s: float,
    critical: float | None = None,
    duration: float | None = None,
    plan_s: float | None = None,
    **detail: object,
) -> RowResult:
    """The row of ``rollout``; duration and plan time: the planned MOVE's."""
    slip = rollout.as_dict()
    return RowResult(
        status=Status.OK,
        duration_s=planned.move.duration if duration is None else duration,
        speed=speed,
        success=rollout.success,
        slip_translation_mm=slip["max_translation_mm"],
        slip_rotation_deg=slip["max_rotation_deg"],
        critical_speed=critical,
        plan_s=planned.plan_s if plan_s is None else plan_s,
        simulate_s=simulate_s,
        detail={**planned.detail, **detail},
    )


def _at_speed_one(combination: Combination, grasp_constraint: bool) -> RowResult:
    planned = plan_move(combination, grasp_constraint)
    start = time.perf_counter()
    rollout = simulate_move(planned.world, planned.q_grasp, planned.move.trajectory)
    return _row(planned, 1.0, rollout, time.perf_counter() - start)


def constrained(combination: Combination) -> RowResult:
    """The MOVE retimed under the grasp constraint, played at speed 1."""
    return _at_speed_one(combination, grasp_constraint=True)


def unconstrained(combination: Combination) -> RowResult:
    """The same path retimed under the joint limits only, played at speed 1."""
    return _at_speed_one(combination, grasp_constraint=False)


def speed_sweep(combination: Combination) -> RowResult:
    """The constrained MOVE played 1, 1.1, 1.2, ... times faster until it slips.

    The row's rollout is the sweep's last: the first that slipped (its
    factor is ``critical_speed``), or the fastest, which held (then
    ``critical_speed`` is None). ``detail["sweep"]`` has every rollout.
    """
    planned = plan_move(combination, grasp_constraint=True)
    start = time.perf_counter()
    critical, sweep = critical_speed(
        planned.world, planned.q_grasp, planned.move.trajectory, SPEED_FACTORS
    )
    factor, last = sweep[-1]
    rollouts = [{"factor": f, "success": r.success, **r.as_dict()} for f, r in sweep]
    return _row(
        planned, factor, last, time.perf_counter() - start, critical, sweep=rollouts
    )


def optimized(combination: Combination) -> RowResult:
    """The MOVE path optimised for speed, retimed under the constraint, at speed 1.

    The trial's spline MOVE (the ``constrained`` row's path) is optimised
    from the same grasp to the same goal within the scenario's ``planning``
    budget (CPU time), retimed under the exact grasp constraint (adaptive
    grid), and played in the same physics. ``duration_s`` is the optimised
    MOVE's; ``plan_s`` adds the optimisation's wall time to the spline's
    planning. ``detail`` adds:

    - ``spline_duration_s``: the spline MOVE's duration (the
      ``constrained`` row's), and ``ratio_to_spline`` = optimised / spline;
    - ``spline_same_grid_s``: the spline path on the optimiser's grid;
    - ``optimize_cpu_s``, ``optimize_wall_s``: the optimisation's CPU and
      wall time, s;
    - ``improved``, ``evaluations``, ``max_tilt_deg``, ``rejected``;
    - ``waypoints_optimized``: the returned path's waypoints (rad), a
      clamped chord-length spline
      (:meth:`~rt_drake.planning.GeometricPath.from_waypoints`).
    """
    planned = plan_move(combination, grasp_constraint=True)
    spline, grasp = planned.move.planned, planned.move.grasp
    assert spline is not None and grasp is not None
    _, result = optimize_spline(
        combination.scenario, planned.motions.planner, spline, grasp
    )
    start = time.perf_counter()
    rollout = simulate_move(planned.world, planned.q_grasp, result.retimed.trajectory)
    return _row(
        planned,
        1.0,
        rollout,
        time.perf_counter() - start,
        duration=result.duration,
        plan_s=planned.plan_s + result.wall_s,
        spline_duration_s=planned.move.duration,
        ratio_to_spline=result.duration / planned.move.duration,
        spline_same_grid_s=result.spline_duration,
        optimize_cpu_s=result.cpu_s,
        optimize_wall_s=result.wall_s,
        improved=result.improved,
        evaluations=result.evaluations,
        max_tilt_deg=result.max_tilt_deg,
        rejected=list(result.rejected),
        waypoints_optimized=result.path.waypoints.tolist(),
    )


def robust(combination: Combination) -> RowResult:
    """The spline MOVE retimed for the uncertainty set, played with a true object.

    The trial's spline MOVE (the ``constrained`` row's path) retimed to hold
    every object of the object's uncertainty set with every cup of the cup's
    range (:meth:`~rt_drake.simulation.OnlineMotions.grasp_for`), and played
    at speed 1 with a hard true object of the set and the worst cup
    (:func:`~rt_drake.experiments._robust_transport.true_object_world`,
    seeded by the row's seed and trial). ``duration_s`` is the robust
    MOVE's; ``detail`` adds ``nominal_duration_s`` (the ``constrained``
    row's), ``price`` = robust / nominal, ``robust_retime_s``, the true
    object, and ``nominal_on_true``: the nominal MOVE played with the same
    true object and cup (held, slip).

    Raises:
        ScenarioError: neither an uncertainty set nor a cup range.
    """
    scenario = combination.scenario
    (obj,) = scenario.objects
    uncertainty = obj.uncertainty or ObjectUncertainty()
    if uncertainty.is_zero() and not scenario.cup.is_uncertain():
        raise ScenarioError(
            f"object '{obj.name}' has no uncertainty file and cup "
            f"'{combination.cup.name}' no friction or suction range: nothing "
            "for the robust variant to hold"
        )
    planned = plan_move(combination, grasp_constraint=True)
    nominal = planned.move
    assert nominal.planned is not None
    start = time.perf_counter()
    grasp = planned.motions.grasp_for(obj, nominal.planned.X_OC, robust=True)
    retimed = planned.motions.retime_path(nominal.planned.path, grasp)
    retime_s = time.perf_counter() - start
    rng = np.random.default_rng([combination.key.seed, combination.key.trial])
    world, inertias, true = true_object_world(
        scenario, planned.q_grasp, obj, uncertainty, rng
    )
    start = time.perf_counter()
    played, on_true = (
        simulate_move(world, planned.q_grasp, trajectory, object_inertias=inertias)
        for trajectory in (retimed.trajectory, nominal.trajectory)
    )
    return _row(
        planned,
        1.0,
        played,
        time.perf_counter() - start,
        duration=retimed.duration,
        plan_s=planned.plan_s + retime_s,
        nominal_duration_s=nominal.duration,
        price=retimed.duration / nominal.duration,
        robust_retime_s=retime_s,
        true_object=true.as_dict(),
        nominal_on_true={"success": on_true.success, **on_true.as_dict()},
    )


#: The registry: every :class:`Variant` and its function (read-only).
VARIANTS: Mapping[Variant, VariantFunction] = MappingProxyType(
    {
        Variant.CONSTRAINED: constrained,
        Variant.UNCONSTRAINED: unconstrained,
        Variant.SPEED_SWEEP: speed_sweep,
        Variant.OPTIMIZED: optimized,
        Variant.ROBUST: robust,
    }
)


def run_variant(combination: Combination) -> RowResult:
    """The row's result; a failure of the row is a result, not an exception.

    A typed :class:`~rt_drake.errors.RtDrakeError` (no path, the object
    slips even at rest, ...) gives an ``infeasible`` row with its message;
    any other exception (a bug) an ``error`` row with its type and message.
    """
    start = time.perf_counter()
    try:
        return VARIANTS[combination.key.variant](combination)
    except RtDrakeError as error:
        return RowResult.failed(
            Status.INFEASIBLE, error, plan_s=time.perf_counter() - start
        )
    except Exception as error:  # a bug in a variant: failures are data
        return RowResult.failed(Status.ERROR, error, plan_s=time.perf_counter() - start)


__all__ = [
    "VARIANTS",
    "PlannedMove",
    "VariantFunction",
    "constrained",
    "optimized",
    "plan_move",
    "robust",
    "run_variant",
    "speed_sweep",
    "unconstrained",
]
