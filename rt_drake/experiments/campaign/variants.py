"""The comparisons of a campaign: one function per :class:`Variant`.

Each variant function computes one row's :class:`RowResult` from its
:class:`Combination`: it plans the trial's MOVE (APPROACH and REACH from
home give the grasp configuration, as in Table I), retimes it, and plays it
in the physics of the cycle (:mod:`rt_drake.experiments.rollout`). A
planner with the same seed in the same scene plans the same path, so the
rows of one trial compare the same path.

To add a comparison (e.g. ``optimized`` once MOVE path optimisation lands,
``robust`` for uncertainty sets): add a member to :class:`Variant`, write
its function here, and add it to :data:`VARIANTS`.
"""

from __future__ import annotations

import dataclasses
import hashlib
import time
from collections.abc import Callable, Mapping
from types import MappingProxyType

import numpy as np

from rt_drake.errors import RtDrakeError
from rt_drake.experiments.campaign.campaign import Combination
from rt_drake.experiments.campaign.rows import RowResult, Status, Variant
from rt_drake.experiments.rollout import (
    SPEED_FACTORS,
    Rollout,
    critical_speed,
    rollout_scenario,
    simulate_move,
)
from rt_drake.scenario import Scenario
from rt_drake.simulation import Motion, OnlineMotions

#: A variant: one row's results from its combination.
VariantFunction = Callable[[Combination], RowResult]


@dataclasses.dataclass(frozen=True, eq=False)
class PlannedMove:
    """A trial's MOVE, planned and retimed.

    Attributes:
        q_grasp: The grasp configuration (rad), where the MOVE starts.
        move: The MOVE (its path, retiming and trajectory).
        world: The rollout scenario (arm at the grasp, short waits).
        plan_s: Wall time of planning and retiming, s.
    """

    q_grasp: np.ndarray
    move: Motion
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

    Raises:
        PlanningError: no collision-free path.
        RetimeError: e.g. the object slips off the cup even at rest.
    """
    start = time.perf_counter()
    motions = OnlineMotions(
        combination.scenario,
        grasp_constraint=grasp_constraint,
        seed=combination.planner_seed,
    )
    (obj,) = combination.scenario.objects
    approach = motions.approach(motions.q_home, obj)
    reach = motions.reach(approach.q_end, obj)
    move = motions.move(reach.q_end, obj, reach)
    q_grasp = reach.q_end
    return PlannedMove(
        q_grasp,
        move,
        rollout_scenario(combination.scenario, q_grasp),
        time.perf_counter() - start,
    )


def _row(
    planned: PlannedMove,
    speed: float,
    rollout: Rollout,
    simulate_s: float,
    critical: float | None = None,
    **detail: object,
) -> RowResult:
    slip = rollout.as_dict()
    return RowResult(
        status=Status.OK,
        duration_s=planned.move.duration,
        speed=speed,
        success=rollout.success,
        slip_translation_mm=slip["max_translation_mm"],
        slip_rotation_deg=slip["max_rotation_deg"],
        critical_speed=critical,
        plan_s=planned.plan_s,
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


#: The registry: every :class:`Variant` and its function (read-only).
VARIANTS: Mapping[Variant, VariantFunction] = MappingProxyType(
    {
        Variant.CONSTRAINED: constrained,
        Variant.UNCONSTRAINED: unconstrained,
        Variant.SPEED_SWEEP: speed_sweep,
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
    "plan_move",
    "run_variant",
    "speed_sweep",
    "unconstrained",
]
