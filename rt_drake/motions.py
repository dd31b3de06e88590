"""Online motions of the cycle: planned (rt_drake.planning), then retimed.

:class:`PlannedMotions` is the sequencer's
:class:`~rt_drake.systems.sequencer.MotionSource`: each phase's path comes
from the :class:`~rt_drake.planning.CyclePlanner` and is retimed by
:func:`~rt_drake.retime.retime` under the joint limits, MOVE also under the
grasp constraint ``F w <= g`` of the held object (unless disabled). Both are
timed on the wall clock, as in the paper's Table II. The grasp polytope is
computed once, offline, per cup (as the paper did), not in the cycle.
"""

from __future__ import annotations

import dataclasses
import time

import numpy as np
from pydrake.common.schema import Transform
from pydrake.math import RigidTransform
from pydrake.trajectories import Trajectory

from rt_drake.contact import cached_wrench_polytope
from rt_drake.dynamics import HeldObject, path_wrench_coefficients
from rt_drake.planning import CyclePlanner, PlannedPath
from rt_drake.plant import make_arm_plant
from rt_drake.retime import RetimeResult, retime
from rt_drake.retiming.limits import GraspConstraint, JointLimits
from rt_drake.retiming.warm import warm_up
from rt_drake.scenario import ObjectConfig, Scenario
from rt_drake.systems.sequencer import Motion


class TimeScaled(Trajectory):
    """``q_f(t) = q(f t)``: a trajectory played ``f`` times faster.

    Derivatives scale as ``q_f^(k)(t) = f^k q^(k)(f t)``; the time span is
    ``[t0 / f, t1 / f]``.
    """

    def __init__(self, trajectory: Trajectory, factor: float) -> None:
        Trajectory.__init__(self)
        if not factor > 0:
            raise ValueError(f"speed factor must be > 0, got {factor}")
        self._trajectory = trajectory
        self._factor = float(factor)

    def do_value(self, t: float) -> np.ndarray:  # noqa: D102
        return self._trajectory.value(self._factor * t)

    def do_has_derivative(self) -> bool:  # noqa: D102
        return True

    def DoEvalDerivative(self, t: float, derivative_order: int) -> np.ndarray:  # noqa: D102, N802
        return self._factor**derivative_order * self._trajectory.EvalDerivative(
            self._factor * t, derivative_order
        )

    def do_rows(self) -> int:  # noqa: D102
        return self._trajectory.rows()

    def do_cols(self) -> int:  # noqa: D102
        return self._trajectory.cols()

    def do_start_time(self) -> float:  # noqa: D102
        return self._trajectory.start_time() / self._factor

    def do_end_time(self) -> float:  # noqa: D102
        return self._trajectory.end_time() / self._factor

    def Clone(self) -> TimeScaled:  # noqa: D102, N802
        return TimeScaled(self._trajectory.Clone(), self._factor)

    def __deepcopy__(self, memo: dict) -> TimeScaled:
        return self.Clone()


def held_object(obj: ObjectConfig, X_OC: RigidTransform) -> HeldObject:
    """Inertia of ``obj`` in the cup frame, held at grasp ``X_OC``."""
    return HeldObject.from_scenario_object(
        dataclasses.replace(obj, grasp=Transform(X_OC))
    )


class PlannedMotions:
    """APPROACH, REACH, MOVE: planned and retimed online.

    Args:
        scenario: the cell.
        grasp_constraint: retime MOVE under ``F w <= g`` (else joint limits only).
        move_speed: play each MOVE this many times faster than retimed
            (1: as retimed; > 1 leaves the constraint, for slip experiments).
        gridpoints: TOPP-RA grid size.
        seed: planner seed.
    """

    def __init__(
        self,
        scenario: Scenario,
        grasp_constraint: bool = True,
        move_speed: float = 1.0,
        gridpoints: int = 100,
        seed: int = 0,
    ) -> None:
        if not move_speed > 0:
            raise ValueError(f"speed factor must be > 0, got {move_speed}")
        self._scenario = scenario
        self._planner = CyclePlanner(scenario, seed=seed)
        self._plant = make_arm_plant(scenario)
        self._context = self._plant.CreateDefaultContext()
        self._limits = JointLimits.from_plant(self._plant, scenario.robot)
        self._speed = move_speed
        self._gridpoints = gridpoints
        self._polytope = (
            cached_wrench_polytope(scenario.cup) if grasp_constraint else None
        )
        warm_up()  # compile the retimer here, not in the first timed MOVE
        #: The last MOVE's retime result, path and grasp: outputs for reports
        #: and plots, never read back by the planning.
        self.last_move: RetimeResult | None = None
        self.last_path = None
        self.last_grasp: GraspConstraint | None = None

    @property
    def q_home(self) -> np.ndarray:
        """The arm's home configuration (rad)."""
        return self._planner.q_home

    def retime_path(self, path, grasp: GraspConstraint | None) -> RetimeResult:
        """Retime ``path`` under the joint limits (and ``grasp`` if given)."""
        return retime(
            self._plant,
            path,
            self._limits,
            grasp,
            gridpoints=self._gridpoints,
            context=self._context,
        )

    def velocity_bound(self, path, s: np.ndarray) -> np.ndarray:
        """Largest s' (1/s) the joint velocity limits allow at each s."""
        dq = np.abs(path.deriv(s))
        with np.errstate(divide="ignore"):
            return np.min(self._limits.velocity / dq, axis=1)

    def grasp_margin(self, path, result: RetimeResult) -> np.ndarray:
        """``min_r (g_r - F_r w) / g_r`` at each grid point of ``result``.

        w is the wrench the last MOVE's object needs (``a u + b x + c``, with
        the segment's u; the last grid point takes the last segment's u).
        Negative: the grasp constraint is violated there.
        """
        grasp = self.last_grasp
        if grasp is None:
            raise ValueError(
                "grasp_margin needs a MOVE retimed under the grasp constraint"
            )
        s = result.gridpoints
        a, b, c = path_wrench_coefficients(
            self._plant,
            grasp.held,
            path.value(s),
            path.deriv(s),
            path.deriv2(s),
            self._context,
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

    def move(self, q_start: np.ndarray, obj: ObjectConfig) -> Motion:
        """Carry ``obj`` from its grasp to its goal."""
        return self._timed(self._planner.plan_move, q_start, obj, carrying=True)

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
        self, plan, q_start: np.ndarray, obj: ObjectConfig, carrying: bool
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
        start = time.perf_counter()
        result = self.retime_path(planned.path, grasp)
        retime_s = time.perf_counter() - start
        trajectory: Trajectory = result.trajectory
        if carrying:
            self.last_move, self.last_path = result, planned.path
            self.last_grasp = grasp
            if self._speed != 1.0:
                trajectory = TimeScaled(trajectory, self._speed)
        return Motion(trajectory, {"plan": planned_s, "retime": retime_s})
