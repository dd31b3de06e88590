"""Online motions of the simulated cell: planned, then retimed, as they run.

:class:`OnlineMotions` is the sequencer's
:class:`~rt_drake.simulation.motion.MotionSource`: each phase's path comes
from the :class:`~rt_drake.planning.CyclePlanner` and is retimed by
:func:`~rt_drake.retiming.retime` under the joint limits, MOVE also under the
grasp constraint ``F w <= g`` of the held object (unless disabled). With
MOVE optimisation on (the scenario's ``planning.optimize_move``, or
``optimize=True``), the spline MOVE is then reshaped for speed by
:class:`~rt_drake.shaping.MoveOptimizer` within
``planning.max_evaluations`` paths scored, and the path it returns is the
one retimed (the search compares paths under the acceleration limits; with
``robot.jerk_limits`` the kept path is retimed once more under them). Both are
timed on the wall clock, as in the paper's Table II. The grasp polytope is
computed once, offline, per cup or multi-cup tool (as the paper did: the
exact W_c, or the tool's set about the tool frame:
:func:`~rt_drake.simulation.move_grasp.move_polytope`), not in the cycle;
with a ``first_order`` vacuum the MOVE is retimed for
the force guaranteed when "part present" fires, ``part_present_fraction
P A``: the same polytope translated (:func:`~rt_drake.contact.with_suction_force`).

An object with an uncertainty set (scenario key ``uncertainty``), or a cup
with a friction or suction range, is held robustly: every object of the set,
with every cup of the range (:meth:`~rt_drake.retiming.GraspConstraint.robust`);
with a ``first_order`` vacuum the suction range then reaches down to
``part_present_fraction`` of its lowest P A.

The pick (:meth:`OnlineMotions.pick`) is one motion through the approach
pose (:mod:`rt_drake.planning._pick`), retimed rest to rest; APPROACH ends
when it passes the approach pose. The cycle's first pick (no retreat: the
cup rests on nothing) is staged instead (:mod:`._first_pick`): a straight
APPROACH timed by Ruckig, on which the arm starts, then the REACH, planned
and retimed while the APPROACH runs; the blended pick where the straight
line is not clean or the scenario limits the torques
(``split_first_pick=False``: always the blended pick).

Grids. TOPP-RA gives one path acceleration per grid segment, so on 100
uniform points it leaves about 6 % of a motion unused where the profile
changes fast (the ends, the turns at the lines). Under the acceleration
limits the pick is retimed on an adaptive grid
(:meth:`OnlineMotions.retime_free`, :func:`~rt_drake.shaping.retime_adaptive`:
400 points placed by a 100-point profile; 4-6 % shorter). With jerk limits
it stays on the uniform grid: on ``gridpoints`` adaptive points its
jerk-limited retime (the first pick's is on the critical path) took 0.99-1.23 s
of CPU against 0.57-0.60 s, for 0-2 % of motion. A shaped MOVE's
jerk-limited retime takes ``gridpoints`` points placed by the optimiser's
final (adaptive, acceleration-limited) profile
(:meth:`OnlineMotions.retime_on_profile`, :func:`~rt_drake.shaping.adaptive_grid`):
as many as the uniform grid, at about the same CPU, 0.1-4 % shorter. Every
grid holds the limits between its points as any other
(:func:`~rt_drake.retiming.retime`).
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable

import numpy as np
from pydrake.math import RigidTransform
from pydrake.trajectories import Trajectory

from rt_drake import arguments
from rt_drake.contact import (
    cached_wrench_polytope,
    with_suction_force,
    worst_cup_polytope,
)
from rt_drake.dynamics.cup_frame import CupFrame
from rt_drake.dynamics.wrench import path_wrench_coefficients
from rt_drake.model.plant import make_arm_plant
from rt_drake.model.scenario import (
    ObjectConfig,
    Scenario,
)
from rt_drake.model.vacuum import VacuumModel
from rt_drake.planning import CyclePlanner, GeometricPath, PlannedPath
from rt_drake.retiming import (
    CupGrasp,
    GraspConstraint,
    JerkTimedPath,
    JointLimits,
    ObjectSetGrasp,
    RetimeError,
    RetimeResult,
    TimedPath,
    TimeScaled,
    retime,
    warm_up,
)
from rt_drake.shaping import (
    ADAPTIVE_WEIGHT,
    MoveOptimizer,
    MoveOptimizerOptions,
    adaptive_grid,
    retime_adaptive,
)
from rt_drake.shaping import warm_up as warm_up_optimizer
from rt_drake.simulation._first_pick import first_approach, then_reach
from rt_drake.simulation._release import release_lead
from rt_drake.simulation.motion import Motion, PhasePart, PlanTimes
from rt_drake.simulation.move_grasp import (
    grasp_limits,
    held_object,
    move_cup,
    move_polytope,
)
from rt_drake.types.object_uncertainty import ObjectUncertainty
from rt_drake.types.phase import Phase
from rt_drake.uncertainty.inertial_set import uncertain_object

#: The guarantee of a MOVE retimed without the grasp constraint.
NO_GUARANTEE = "none: joint limits only"


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
        optimize: shape each MOVE for speed (None: the scenario's
            ``planning.optimize_move``); needs the grasp constraint.
        jerk_limits: retime every motion under the scenario's
            ``robot.jerk_limits`` too (when it gives them).
        split_first_pick: stage a pick without retreat (the cycle's first)
            as a straight APPROACH, then the REACH (:mod:`._first_pick`);
            False: the blended pick, as every other.
    """

    def __init__(
        self,
        scenario: Scenario,
        grasp_constraint: bool = True,
        move_speed: float = 1.0,
        gridpoints: int = 100,
        seed: int = 0,
        robust: bool = True,
        optimize: bool | None = None,
        jerk_limits: bool = False,
        split_first_pick: bool = True,
    ) -> None:
        arguments.instance(scenario, "scenario", Scenario, where="OnlineMotions")
        arguments.number(move_speed, "move_speed", where="OnlineMotions", above=0.0)
        self._scenario = scenario
        self._planner = CyclePlanner(scenario, seed=seed)
        self._plant = make_arm_plant(scenario)
        self._cup = CupFrame.of(self._plant, scenario.robot.cup_frame)
        self._context = self._plant.CreateDefaultContext()
        self._limits = JointLimits.from_plant(
            self._plant, scenario.robot, jerk=jerk_limits
        )
        self._grasp_limits = grasp_limits(self._limits, scenario)
        self._speed = move_speed
        self._gridpoints = gridpoints
        # Ruckig bounds velocity, acceleration and jerk, not torques.
        self._split_first = split_first_pick and self._limits.torque is None
        self._polytope = None
        if grasp_constraint:
            self._polytope = move_polytope(scenario)
        self._robust = robust
        # One cup with a friction or suction range: its worst-case rows, once.
        self._worst_cup = None
        if (
            grasp_constraint
            and robust
            and scenario.tool is None
            and scenario.cup.is_uncertain()
        ):
            self._worst_cup = worst_cup_polytope(move_cup(scenario))
        warm_up()  # compile the retimer here, not in the first timed MOVE
        if optimize is None:
            optimize = scenario.planning.optimize_move
        self._optimizer = None
        if optimize and grasp_constraint:
            options = MoveOptimizerOptions.from_config(scenario.planning)
            # The search compares paths under the acceleration limits; the
            # path it keeps is then retimed once under the jerk limits too
            # (:meth:`_timed`): a jerk-limited retime costs about 60x more.
            self._optimizer = MoveOptimizer(
                self._plant,
                dataclasses.replace(self._limits, jerk=None),
                options,
                self._cup,
                self._context,
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

    @property
    def jerk_limited(self) -> bool:
        """Whether a grasp-constrained motion is retimed under jerk limits.

        The robot's ``robot.jerk_limits`` (when applied) or the grasp's
        ``planning.grasp_ramp_s``
        (:func:`~rt_drake.simulation.move_grasp.grasp_limits`).
        """
        return self._grasp_limits.jerk is not None

    def retime_path(
        self, path: GeometricPath, grasp: GraspConstraint | None
    ) -> RetimeResult:
        """Retime ``path`` under the joint limits (and ``grasp`` if given).

        With ``grasp``, the jerk limits are also tightened by the scenario's
        ``planning.grasp_ramp_s``
        (:func:`~rt_drake.simulation.move_grasp.grasp_limits`). The retimer adds the
        path's knots to the ``gridpoints`` uniform points and holds every
        limit between grid points too.
        """
        return retime(
            self._plant,
            path,
            self._limits if grasp is None else self._grasp_limits,
            grasp,
            gridpoints=self._gridpoints,
            context=self._context,
            cup=self._cup,
        )

    def retime_free(self, path: GeometricPath) -> RetimeResult:
        """Retime ``path`` without a held object (the pick).

        Under the acceleration limits on an adaptive grid
        (:func:`~rt_drake.shaping.retime_adaptive`); with jerk limits on the
        uniform one (:meth:`retime_path`). Module docstring.
        """
        if self._limits.jerk is not None:
            return self.retime_path(path, None)
        return retime_adaptive(
            self._plant, path, self._limits, None, context=self._context, cup=self._cup
        )

    def retime_on_profile(
        self, path: GeometricPath, grasp: GraspConstraint | None, profile: RetimeResult
    ) -> RetimeResult:
        """Retime ``path`` on ``gridpoints`` points placed by ``profile``'s s'(s).

        :func:`~rt_drake.shaping.adaptive_grid` (equal steps of time and of
        the variation of ``s'^2`` along ``profile``, the same path's retime
        under the acceleration limits); if the retimer fails numerically on
        that grid, on the uniform one (:meth:`retime_path`). With ``grasp``,
        under the limits of a grasp-constrained motion, as
        :meth:`retime_path` (``planning.grasp_ramp_s``).
        """
        grid = adaptive_grid(
            profile.gridpoints, profile.sd, self._gridpoints, ADAPTIVE_WEIGHT
        )
        try:
            return retime(
                self._plant,
                path,
                self._limits if grasp is None else self._grasp_limits,
                grasp,
                gridpoints=grid,
                context=self._context,
                cup=self._cup,
            )
        except RetimeError:
            return self.retime_path(path, grasp)

    def grasp_price(
        self,
        path: GeometricPath,
        grasp: GraspConstraint,
        with_grasp: RetimeResult | None = None,
    ) -> float:
        """What ``grasp`` costs on ``path`` (s): the duration with it less without.

        At the acceleration limits (no jerk limits): with the grasp by
        :func:`~rt_drake.shaping.retime_adaptive` (``with_grasp``: that retime
        already done, e.g. the optimiser's), without it on the same grid
        points, so that both solve the same discretisation and the price is
        never negative (on grids of their own the two differed by up to
        5 ms either way). A report figure, not part of the motion: its wall
        time is not counted as planning.
        """
        plain = dataclasses.replace(self._limits, jerk=None)
        if with_grasp is None:
            with_grasp = retime_adaptive(
                self._plant, path, plain, grasp, context=self._context, cup=self._cup
            )
        without = retime(
            self._plant,
            path,
            plain,
            None,
            gridpoints=with_grasp.gridpoints,
            context=self._context,
            cup=self._cup,
        )
        return with_grasp.duration - without.duration

    def grasp_for(
        self, obj: ObjectConfig, X_OC: RigidTransform, robust: bool | None = None
    ) -> GraspConstraint:
        """The grasp constraint of ``obj`` held at ``X_OC``.

        Robust (every object of its uncertainty set, every cup of the cup's
        range) when ``robust`` (default: as constructed) and the scenario
        gives a set or a range; else the nominal object and cup. Shrunk by
        the scenario's ``planning.grasp_margin``.
        """
        margin = self._scenario.planning.grasp_margin
        robust = self._robust if robust is None else robust
        held = held_object(obj, X_OC)
        uncertainty = obj.uncertainty or ObjectUncertainty()
        uncertain_cup = (
            self._scenario.tool is None and self._scenario.cup.is_uncertain()
        )
        if not robust or (uncertainty.is_zero() and not uncertain_cup):
            polytope = self._polytope or move_polytope(self._scenario)
            return GraspConstraint.for_polytope(held, polytope).with_margin(margin)
        cup = move_cup(self._scenario)
        F, g = self._worst_cup or worst_cup_polytope(cup)
        R_CO = X_OC.inverse().rotation().matrix()
        objects = uncertain_object(held, uncertainty, R_CO)
        grasp = ObjectSetGrasp(held=held, F=F, g=g, cup=cup, objects=objects)
        return grasp.with_margin(margin)

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
        if result.path_acceleration is not None:  # jerk-limited: s'' at s_i
            u = result.path_acceleration[:, None]
        x = (result.sd**2)[:, None]
        w = a * u + b * x + c
        return np.min((grasp.g - w @ grasp.F.T) / grasp.g, axis=1)

    def approach(self, q_start: np.ndarray, obj: ObjectConfig) -> Motion:
        """From ``q_start`` to above ``obj``."""
        return self._timed(self._planner.plan_approach, q_start, obj, carrying=False)

    def reach(self, q_start: np.ndarray, obj: ObjectConfig) -> Motion:
        """Straight down onto ``obj``."""
        return self._timed(self._planner.plan_reach, q_start, obj, carrying=False)

    def straight_approach(
        self, q_start: np.ndarray, obj: ObjectConfig
    ) -> Motion | None:
        """From rest at ``q_start`` to above ``obj`` on a straight line, or None.

        The staged first pick's first part (:func:`._first_pick.first_approach`):
        what the cycle's first motion waits for.
        """
        self._place_objects_for(obj)
        return first_approach(self._planner, self._limits, q_start, obj.name)

    def pick(
        self, q_start: np.ndarray, obj: ObjectConfig, retreat: bool = False
    ) -> Motion:
        """Retreat (if ``retreat``), approach and reach ``obj``.

        Without ``retreat`` (the first pick), staged if the straight APPROACH
        is clean (:mod:`._first_pick`; parts APPROACH and REACH, each with
        its own plan times). Else one motion without a stop: APPROACH until
        the cup passes the approach pose (its plan times: the retreat,
        transit and blend, and the retime, plus a straight APPROACH tried
        and blocked), then REACH (its plan times: the descent's IK line).
        """
        tried_s = 0.0
        if not retreat and self._split_first:
            start = time.perf_counter()
            approach = self.straight_approach(q_start, obj)
            if approach is not None:
                return then_reach(approach, self._planner, self.retime_free, obj.name)
            tried_s = time.perf_counter() - start
        self._place_objects_for(obj)
        start = time.perf_counter()
        planned = self._planner.plan_pick(q_start, obj.name, retreat)
        plan_s = time.perf_counter() - start + tried_s
        start = time.perf_counter()
        result = self.retime_free(planned.path.path)
        t_approach = time_at(result, planned.s_approach)
        retime_s = time.perf_counter() - start
        reach_s = min(planned.reach_timing.total_s, plan_s)
        parts = (
            PhasePart(
                Phase.APPROACH,
                t_approach,
                PlanTimes(plan_s=plan_s - reach_s, retime_s=retime_s),
            ),
            PhasePart(Phase.REACH, result.duration, PlanTimes(plan_s=reach_s)),
        )
        return Motion(
            result.trajectory,
            PlanTimes(plan_s=plan_s, retime_s=retime_s),
            planned=planned.path,
            retimed=result,
            parts=parts,
        )

    def move(
        self, q_start: np.ndarray, obj: ObjectConfig, pick: Motion | None = None
    ) -> Motion:
        """Carry ``obj`` from its grasp to its goal (lifting along ``pick``'s line).

        ``pick`` is the pick or REACH motion that ended at ``q_start``.
        """
        planned_reach = None if pick is None else pick.planned

        def plan(q: np.ndarray, name: str) -> PlannedPath:
            return self._planner.plan_move(q, name, reach=planned_reach)

        motion = self._timed(plan, q_start, obj, carrying=True)
        return self._with_release(motion)

    def _with_release(self, move: Motion) -> Motion:
        """``move`` with its valve closing early, if the grasp holds (:mod:`._release`).

        Only with the ``first_order`` vacuum, one cup of a fixed suction
        force, the nominal grasp (:class:`~rt_drake.retiming.CupGrasp`) and
        the MOVE played as retimed; else the valve closes on arrival.
        """
        vacuum = self._scenario.vacuum
        grasp = move.grasp
        if (
            vacuum.kind is not VacuumModel.FIRST_ORDER
            or not isinstance(grasp, CupGrasp)
            or self._scenario.tool is None
            and self._scenario.cup.is_uncertain()
            or self._speed != 1.0
        ):
            return move
        full = cached_wrench_polytope(self._scenario.cup)
        margin = self._scenario.planning.grasp_margin

        def grasp_at(force: float) -> GraspConstraint:
            polytope = with_suction_force(full, force)
            return GraspConstraint.for_polytope(grasp.held, polytope).with_margin(
                margin
            )

        force = vacuum.part_present_fraction * self._scenario.cup.suction_force
        lead = release_lead(
            self._plant,
            move.trajectory,
            grasp.held,
            grasp_at,
            force,
            vacuum.release_tau_s,
            self._context,
            self._cup,
            knots=_knots(move.trajectory),
        )
        if lead <= 0.0:
            return move
        floor = force * math.exp(-lead / vacuum.release_tau_s)
        guarantee = (
            f"{move.guarantee}; valve closed {lead:.3f} s before arrival "
            f"(at least {floor:.1f} N then)"
        )
        return dataclasses.replace(move, release_s=lead, guarantee=guarantee)

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
        grasp, acceleration_limited = None, None
        if carrying and self._polytope is not None:
            grasp = self.grasp_for(obj, planned.X_OC)
        if grasp is not None and self._optimizer is not None:
            # the optimiser's search counts as planning, its final retime as retiming
            optimized = self._optimizer.optimize(self._planner, planned, grasp)
            path = optimized.path
            planned = dataclasses.replace(planned, path=path, polyline=path.waypoints)
            result = acceleration_limited = optimized.retimed
            planned_s += optimized.wall_s - optimized.retime_wall_s
            retime_s = optimized.retime_wall_s
            if self.jerk_limited:  # the kept path, jerk-limited
                planned_s += retime_s
                start = time.perf_counter()
                result = self.retime_on_profile(path, grasp, optimized.retimed)
                retime_s = time.perf_counter() - start
        else:
            start = time.perf_counter()
            result = self.retime_path(planned.path, grasp)
            retime_s = time.perf_counter() - start
        price = float("nan")  # cheap only beside the optimiser's own retime
        if grasp is not None and acceleration_limited is not None:
            price = self.grasp_price(planned.path, grasp, acceleration_limited)
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
            grasp_price_s=price,
        )


def _knots(trajectory: object) -> np.ndarray | None:
    """Times (s) at which a retimed motion passes its grid points.

    There its acceleration may jump (TOPP-RA's piecewise-constant s''); None
    for a motion without a grid.
    """
    if isinstance(trajectory, TimedPath | JerkTimedPath):
        return trajectory.times
    return None


def time_at(result: RetimeResult, s: float) -> float:
    """Time (s) at which the retimed motion reaches path parameter ``s``.

    On grid segment i (``s_i <= s <= s_{i+1}``) the path acceleration u_i is
    constant, so with ``d = s - s_i``: ``tau = 2 d / (s'_i + sqrt(s'_i^2 +
    2 u_i d))``, after ``t_i = sum_{k<i} 2 ds_k / (s'_k + s'_{k+1})``.
    Jerk-limited (u continuous, not constant): at a grid point (a path knot,
    such as the pick's approach pose) the time the motion passes it, else
    :meth:`~rt_drake.retiming.JerkTimedPath.time_at` (bisection: 10 ms).
    """
    if isinstance(result.trajectory, JerkTimedPath):
        grid = result.gridpoints
        i = int(np.argmin(np.abs(grid - s)))
        if abs(grid[i] - s) <= 1e-12:
            return float(result.trajectory.times[i])
        return result.trajectory.time_at(s)
    grid, sd, sdd = result.gridpoints, result.sd, result.sdd
    i = int(np.clip(np.searchsorted(grid, s, side="right") - 1, 0, len(grid) - 2))
    dt = 2.0 * np.diff(grid) / (sd[:-1] + sd[1:])
    d = s - grid[i]
    root = np.sqrt(max(sd[i] ** 2 + 2.0 * sdd[i] * d, 0.0))
    tau = 2.0 * d / (sd[i] + root) if sd[i] + root > 0.0 else 0.0
    return float(result.trajectory.start_time() + dt[:i].sum() + tau)


__all__ = ["NO_GUARANTEE", "OnlineMotions", "time_at"]
