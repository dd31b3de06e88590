"""Online motions of the simulated cell: planned, then retimed, as they run.

:class:`OnlineMotions` is the sequencer's
:class:`~rt_drake.simulation.motion.MotionSource`: each phase's path comes
from the :class:`~rt_drake.planning.CyclePlanner` and is retimed by
:func:`~rt_drake.retiming.retime` under the joint limits, MOVE also under the
grasp constraint ``F w <= g`` of the held object (unless disabled). An object
with an uncertainty set (scenario key ``uncertainty``), or a cup with a
friction or suction range, is held robustly: every object of the set, with
every cup of the range (:meth:`~rt_drake.retiming.GraspConstraint.robust`).
Both are timed on the wall clock, as in the paper's Table II. The grasp
polytopes are computed once, offline, per cup (as the paper did), not in the
cycle.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable

import numpy as np
from pydrake.common.schema import Transform
from pydrake.math import RigidTransform
from pydrake.trajectories import Trajectory

from rt_drake.contact import cached_wrench_polytope, worst_cup_polytope
from rt_drake.cup_frame import CupFrame
from rt_drake.dynamics import HeldObject, path_wrench_coefficients
from rt_drake.errors import InputError
from rt_drake.inertial_set import uncertain_object
from rt_drake.planning import CyclePlanner, GeometricPath, PlannedPath
from rt_drake.plant import make_arm_plant
from rt_drake.retiming import (
    GraspConstraint,
    JointLimits,
    RetimeResult,
    TimeScaled,
    retime,
    warm_up,
)
from rt_drake.scenario import ObjectConfig, Scenario
from rt_drake.simulation.motion import Motion, PlanTimes
from rt_drake.uncertainty import ObjectUncertainty

#: The guarantee of a MOVE retimed without the grasp constraint.
NO_GUARANTEE = "none: joint limits only"


def held_object(obj: ObjectConfig, X_OC: RigidTransform) -> HeldObject:
    """Inertia of ``obj`` in the cup frame, held at grasp ``X_OC``."""
    return HeldObject.from_scenario_object(
        dataclasses.replace(obj, grasp=Transform(X_OC))
    )


class OnlineMotions:
    """APPROACH, REACH, MOVE: planned and retimed online.

    Args:
        scenario: the cell.
        grasp_constraint: retime MOVE under ``F w <= g`` (else joint limits only).
        move_speed: play each MOVE this many times faster than retimed
            (1: as retimed; > 1 leaves the constraint, for slip experiments).
        gridpoints: TOPP-RA grid size.
        seed: planner seed.
        robust: hold every object of an object's uncertainty set (and every
            cup of the cup's range) when the scenario gives one; False: the
            nominal object and cup only.
    """

    def __init__(
        self,
        scenario: Scenario,
        grasp_constraint: bool = True,
        move_speed: float = 1.0,
        gridpoints: int = 100,
        seed: int = 0,
        robust: bool = True,
    ) -> None:
        if not move_speed > 0:
            raise InputError(f"speed factor must be > 0, got {move_speed}")
        self._scenario = scenario
        self._planner = CyclePlanner(scenario, seed=seed)
        self._plant = make_arm_plant(scenario)
        self._cup = CupFrame.of(self._plant)
        self._context = self._plant.CreateDefaultContext()
        self._limits = JointLimits.from_plant(self._plant, scenario.robot)
        self._speed = move_speed
        self._gridpoints = gridpoints
        self._polytope = (
            cached_wrench_polytope(scenario.cup) if grasp_constraint else None
        )
        self._robust = robust
        self._worst_cup = (
            worst_cup_polytope(scenario.cup)
            if grasp_constraint and robust and scenario.cup.is_uncertain()
            else None
        )
        warm_up()  # compile the retimer here, not in the first timed MOVE

    @property
    def q_home(self) -> np.ndarray:
        """The arm's home configuration (rad)."""
        return self._planner.q_home

    def retime_path(
        self, path: GeometricPath, grasp: GraspConstraint | None
    ) -> RetimeResult:
        """Retime ``path`` under the joint limits (and ``grasp`` if given)."""
        return retime(
            self._plant,
            path,
            self._limits,
            grasp,
            gridpoints=self._gridpoints,
            context=self._context,
            cup=self._cup,
        )

    def grasp_for(
        self, obj: ObjectConfig, X_OC: RigidTransform, robust: bool | None = None
    ) -> GraspConstraint:
        """The grasp constraint of ``obj`` held at ``X_OC``.

        Robust (every object of its uncertainty set, every cup of the cup's
        range) when ``robust`` (default: as constructed) and the scenario
        gives a set or a range; else the nominal object and cup.
        """
        robust = self._robust if robust is None else robust
        cup = self._scenario.cup
        held = held_object(obj, X_OC)
        uncertainty = obj.uncertainty or ObjectUncertainty()
        if not robust or (uncertainty.is_zero() and not cup.is_uncertain()):
            polytope = self._polytope or cached_wrench_polytope(cup)
            return GraspConstraint(held=held, F=polytope.F, g=polytope.g, cup=cup)
        F, g = self._worst_cup or worst_cup_polytope(cup)
        R_CO = X_OC.inverse().rotation().matrix()
        return GraspConstraint(
            held=held,
            F=F,
            g=g,
            cup=cup,
            objects=uncertain_object(held, uncertainty, R_CO),
            worst_cup=cup.is_uncertain(),
        )

    def velocity_bound(self, path: GeometricPath, s: np.ndarray) -> np.ndarray:
        """Largest s' (1/s) the joint velocity limits allow at each s."""
        dq = np.abs(path.deriv(s))
        with np.errstate(divide="ignore"):
            return np.min(self._limits.velocity / dq, axis=1)

    def grasp_margin(
        self, path: GeometricPath, result: RetimeResult, grasp: GraspConstraint
    ) -> np.ndarray:
        """``min_r (g_r - F_r w) / g_r`` at each grid point of ``result``.

        w is the wrench ``grasp``'s object needs along ``path`` timed by
        ``result`` (``a u + b x + c``, with the segment's u; the last grid
        point takes the last segment's u). Negative: the grasp constraint is
        violated there.
        """
        s = result.gridpoints
        a, b, c = path_wrench_coefficients(
            self._plant,
            grasp.held,
            path.value(s),
            path.deriv(s),
            path.deriv2(s),
            self._context,
            self._cup,
        )
        u = np.append(result.sdd, result.sdd[-1])[:, None]
        x = (result.sd**2)[:, None]
        w = a * u + b * x + c
        return np.min((grasp.g - w @ grasp.F.T) / grasp.g, axis=1)

    def approach(self, q_start: np.ndarray, obj: ObjectConfig) -> Motion:
        """From ``q_start`` to above ``obj``."""
        return self._timed(self._planner.plan_approach, q_start, obj, carrying=False)

    def reach(self, q_start: np.ndarray, obj: ObjectConfig) -> Motion:
        """Straight down onto ``obj``."""
        return self._timed(self._planner.plan_reach, q_start, obj, carrying=False)

    def move(
        self, q_start: np.ndarray, obj: ObjectConfig, reach: Motion | None = None
    ) -> Motion:
        """Carry ``obj`` from its grasp to its goal (lifting along ``reach``)."""
        planned_reach = None if reach is None else reach.planned

        def plan(q: np.ndarray, name: str) -> PlannedPath:
            return self._planner.plan_move(q, name, reach=planned_reach)

        return self._timed(plan, q_start, obj, carrying=True)

    def _place_objects_for(self, obj: ObjectConfig) -> None:
        """Objects picked before ``obj`` are at their goals, the rest at their starts.

        Derived from the picking order on every call (not accumulated), so a
        re-run of the same cycle plans in the same scene.
        """
        names = [o.name for o in self._scenario.objects]
        current = names.index(obj.name)
        for index, other in enumerate(self._scenario.objects):
            pose = other.goal if index < current else other.start
            self._planner.set_object_pose(other.name, pose.GetDeterministicValue())

    def _timed(
        self,
        plan: Callable[[np.ndarray, str], PlannedPath],
        q_start: np.ndarray,
        obj: ObjectConfig,
        carrying: bool,
    ) -> Motion:
        self._place_objects_for(obj)
        start = time.perf_counter()
        planned: PlannedPath = plan(q_start, obj.name)
        planned_s = time.perf_counter() - start
        grasp = None
        if carrying and self._polytope is not None:
            grasp = self.grasp_for(obj, planned.X_OC)
        start = time.perf_counter()
        result = self.retime_path(planned.path, grasp)
        retime_s = time.perf_counter() - start
        trajectory: Trajectory = result.trajectory
        guarantee = ""
        if carrying:
            guarantee = NO_GUARANTEE if grasp is None else grasp.guarantee()
        if carrying and self._speed != 1.0:
            trajectory = TimeScaled(trajectory, self._speed)
            guarantee = f"none: played {self._speed:g}x faster than retimed"
        return Motion(
            trajectory,
            PlanTimes(plan_s=planned_s, retime_s=retime_s),
            planned=planned,
            retimed=result,
            grasp=grasp,
            guarantee=guarantee,
        )


__all__ = ["NO_GUARANTEE", "OnlineMotions", "held_object"]
