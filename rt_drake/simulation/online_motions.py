"""Online motions of the simulated cell: planned, then retimed, as they run.

:class:`OnlineMotions` is the sequencer's
:class:`~rt_drake.simulation.motion.MotionSource`: each phase's path comes
from the :class:`~rt_drake.planning.CyclePlanner` and is retimed by
:func:`~rt_drake.retiming.retime` under the joint limits, MOVE also under the
grasp constraint ``F w <= g`` of the held object (unless disabled). With
MOVE optimisation on (the scenario's ``planning.optimize_move``, or
``optimize=True``), the spline MOVE is then reshaped for speed by
:class:`~rt_drake.planning.shape.MoveOptimizer` within
``planning.budget_s``, and the path it returns is the one retimed. Both are
timed on the wall clock, as in the paper's Table II. The grasp polytope is
computed once, offline, per cup (as the paper did), not in the cycle.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable

import numpy as np
from pydrake.common.schema import Transform
from pydrake.math import RigidTransform
from pydrake.trajectories import Trajectory

from rt_drake.contact import cached_wrench_polytope
from rt_drake.cup_frame import CupFrame
from rt_drake.dynamics import HeldObject, path_wrench_coefficients
from rt_drake.errors import InputError
from rt_drake.planning import CyclePlanner, GeometricPath, PlannedPath
from rt_drake.planning.shape import MoveOptimizer, MoveOptimizerOptions
from rt_drake.planning.shape import warm_up as warm_up_optimizer
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
        optimize: shape each MOVE for speed (None: the scenario's
            ``planning.optimize_move``); needs the grasp constraint.
    """

    def __init__(
        self,
        scenario: Scenario,
        grasp_constraint: bool = True,
        move_speed: float = 1.0,
        gridpoints: int = 100,
        seed: int = 0,
        optimize: bool | None = None,
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
        warm_up()  # compile the retimer here, not in the first timed MOVE
        if optimize is None:
            optimize = scenario.planning.optimize_move
        self._optimizer = None
        if optimize and grasp_constraint:
            options = MoveOptimizerOptions.from_config(scenario.planning)
            self._optimizer = MoveOptimizer(
                self._plant, self._limits, options, self._cup, self._context
            )
            warm_up_optimizer()

    @property
    def q_home(self) -> np.ndarray:
        """The arm's home configuration (rad)."""
        return self._planner.q_home

    @property
    def planner(self) -> CyclePlanner:
        """The planner (its scene holds the objects of the last motion)."""
        return self._planner

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
            grasp = GraspConstraint(
                held=held_object(obj, planned.X_OC),
                F=self._polytope.F,
                g=self._polytope.g,
                cup=self._scenario.cup,
            )
        if grasp is not None and self._optimizer is not None:
            # the optimiser's search counts as planning, its final retime as retiming
            optimized = self._optimizer.optimize(self._planner, planned, grasp)
            path = optimized.path
            planned = dataclasses.replace(planned, path=path, polyline=path.waypoints)
            result = optimized.retimed
            planned_s += optimized.wall_s - optimized.retime_wall_s
            retime_s = optimized.retime_wall_s
        else:
            start = time.perf_counter()
            result = self.retime_path(planned.path, grasp)
            retime_s = time.perf_counter() - start
        trajectory: Trajectory = result.trajectory
        if carrying and self._speed != 1.0:
            trajectory = TimeScaled(trajectory, self._speed)
        return Motion(
            trajectory,
            PlanTimes(plan_s=planned_s, retime_s=retime_s),
            planned=planned,
            retimed=result,
            grasp=grasp,
        )


__all__ = ["OnlineMotions", "held_object"]
