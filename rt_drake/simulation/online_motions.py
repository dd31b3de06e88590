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
when it passes the approach pose. With the optimisation on and the
scenario's ``planning.shape_picks``, its transit between the retreat and
descent lines is shaped by the same optimiser
(:func:`~rt_drake.shaping.shape_pick`, joint limits only); where the
shaping fails, the blended pick is played and a warning says so, once.
The cycle's first pick (no retreat: the cup rests on nothing) is staged
instead (:mod:`._first_pick`): a straight
APPROACH timed by Ruckig, on which the arm starts, then the REACH, planned
and retimed while the APPROACH runs; the blended pick where the straight
line is not clean or the scenario limits the torques
(``split_first_pick=False``: always the blended pick).

Each motion is retimed on the grid it takes
(:class:`~._motion_retimer.MotionRetimer`, whose docstring says which).

With ``planning.grasp_margin: ring`` a MOVE's margin is its own: the
(shaped) path is retimed at the margins
:func:`~rt_drake.retiming.retime_for_ring` tries until the bellows' ring of
that MOVE's planned wrench stays in the grasp set (the shaping searches
under the unshrunk set); its retimes count as retiming.
"""

from __future__ import annotations

import dataclasses
import functools
import time
import warnings
from collections.abc import Callable

import numpy as np
from pydrake.math import RigidTransform
from pydrake.trajectories import Trajectory

from rt_drake import arguments
from rt_drake.contact import worst_cup_polytope
from rt_drake.dynamics.cup_frame import CupFrame
from rt_drake.errors import RtDrakeError
from rt_drake.model.plant import make_arm_plant
from rt_drake.model.scenario import (
    ObjectConfig,
    Scenario,
)
from rt_drake.planning import CyclePlanner, GeometricPath, PlannedPath, PlannedPick
from rt_drake.retiming import (
    GraspConstraint,
    JointLimits,
    RetimeResult,
    TimeScaled,
    retime_for_ring,
    warm_up,
)
from rt_drake.shaping import (
    MoveOptimizer,
    MoveOptimizerOptions,
    ShapedPick,
    shape_pick,
)
from rt_drake.shaping import warm_up as warm_up_optimizer
from rt_drake.simulation._blended_pick import blended_pick
from rt_drake.simulation._first_pick import first_approach, then_reach
from rt_drake.simulation._motion_retimer import MotionRetimer
from rt_drake.simulation._release import with_release
from rt_drake.simulation._time_at import time_at
from rt_drake.simulation.motion import Motion, PlanTimes
from rt_drake.simulation.move_grasp import (
    grasp_for,
    grasp_limits,
    move_cup,
    move_polytope,
    ring_tool,
)

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
        optimize: shape each MOVE (it needs the grasp constraint), and,
            with the scenario's ``planning.shape_picks``, each blended
            pick's transit for speed (None: the scenario's
            ``planning.optimize_move``).
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
        self._retimer = MotionRetimer(
            self._plant,
            self._limits,
            self._grasp_limits,
            gridpoints,
            self._context,
            self._cup,
        )
        # Ruckig bounds velocity, acceleration and jerk, not torques.
        self._split_first = split_first_pick and self._limits.torque is None
        self._polytope = None
        self._ring = None
        if grasp_constraint:
            self._polytope = move_polytope(scenario)
            self._ring = ring_tool(scenario, robust)
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
        self._shaping_failed = False
        if optimize:
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

        :meth:`._motion_retimer.MotionRetimer.retime_path`.
        """
        return self._retimer.retime_path(path, grasp)

    def retime_free(
        self,
        path: GeometricPath,
        on_profile: bool = True,
        profile: RetimeResult | None = None,
    ) -> RetimeResult:
        """Retime ``path`` without a held object (the pick).

        :meth:`._motion_retimer.MotionRetimer.retime_free` (``profile``:
        ``path``'s acceleration-limited adaptive retime, if already done).
        """
        return self._retimer.retime_free(path, on_profile, profile)

    def retime_on_profile(
        self, path: GeometricPath, grasp: GraspConstraint | None, profile: RetimeResult
    ) -> RetimeResult:
        """Retime ``path`` on ``gridpoints`` points placed by ``profile``'s s'(s).

        :meth:`._motion_retimer.MotionRetimer.retime_on_profile`.
        """
        return self._retimer.retime_on_profile(path, grasp, profile)

    def grasp_price(
        self,
        path: GeometricPath,
        grasp: GraspConstraint,
        with_grasp: RetimeResult | None = None,
    ) -> float:
        """What ``grasp`` costs on ``path`` (s): the duration with it less without.

        :meth:`._motion_retimer.MotionRetimer.grasp_price`.
        """
        return self._retimer.grasp_price(path, grasp, with_grasp)

    def grasp_for(
        self, obj: ObjectConfig, X_OC: RigidTransform, robust: bool | None = None
    ) -> GraspConstraint:
        """The grasp constraint of ``obj`` held at ``X_OC``.

        :func:`~rt_drake.simulation.move_grasp.grasp_for`, robust when
        ``robust`` (default: as constructed).
        """
        robust = self._robust if robust is None else robust
        return grasp_for(
            self._scenario, obj, X_OC, robust, self._polytope, self._worst_cup
        )

    def velocity_bound(self, path: GeometricPath, s: np.ndarray) -> np.ndarray:
        """Largest s' (1/s) the joint velocity limits allow at each s.

        :meth:`._motion_retimer.MotionRetimer.velocity_bound`.
        """
        return self._retimer.velocity_bound(path, s)

    def grasp_margin(
        self, path: GeometricPath, result: RetimeResult, grasp: GraspConstraint
    ) -> np.ndarray:
        """``min_r (g_r - F_r w) / g_r`` at each grid point of ``result``.

        :meth:`._motion_retimer.MotionRetimer.grasp_margin`.
        """
        return self._retimer.grasp_margin(path, result, grasp)

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
        its own plan times). Else the blended pick, one motion without a
        stop (:mod:`._blended_pick`; a straight APPROACH tried and blocked
        is charged to its APPROACH).
        """
        tried_s = 0.0
        if not retreat and self._split_first:
            start = time.perf_counter()
            approach = self.straight_approach(q_start, obj)
            if approach is not None:
                return then_reach(approach, self._planner, self._retime_reach, obj.name)
            tried_s = time.perf_counter() - start
        self._place_objects_for(obj)
        shape = None
        if self._optimizer is not None and self._scenario.planning.shape_picks:
            shape = self._shape_pick
        return blended_pick(
            self._planner, self._retime_pick, q_start, obj.name, retreat, tried_s, shape
        )

    def _shape_pick(self, pick: PlannedPick) -> ShapedPick | None:
        """The shaped pick (:func:`~rt_drake.shaping.shape_pick`), None if it failed.

        A failure is said once (a ``RuntimeWarning``), not hidden: the
        blended pick is then played.
        """
        assert self._optimizer is not None  # pick() passes it only then
        try:
            return shape_pick(
                self._optimizer, self._planner, pick, played=self._retime_pick
            )
        except RtDrakeError as error:
            if not self._shaping_failed:
                self._shaping_failed = True
                warnings.warn(
                    f"pick shaping failed for {pick.path.object} ({error}); the "
                    "blended pick is played there (said once per run)",
                    RuntimeWarning,
                    stacklevel=2,
                )
            return None

    def _retime_pick(
        self, path: GeometricPath, profile: RetimeResult | None
    ) -> RetimeResult:
        """A pick's retime (:meth:`retime_free`, from ``profile`` if given)."""
        return self.retime_free(path, profile=profile)

    def _retime_reach(self, path: GeometricPath) -> RetimeResult:
        """The staged REACH's retime: on the uniform grid under jerk limits."""
        return self.retime_free(path, on_profile=False)

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
        return with_release(
            motion, self._scenario, self._plant, self._context, self._cup, self._speed
        )

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
        margin, ring = 0.0, ""
        if grasp is not None and self._optimizer is not None:
            # the optimiser's search counts as planning, its final retime as
            # retiming. Under jerk limits (no ring) its finish compares the
            # candidates and the spline path as played: a path faster at the
            # acceleration limits can be slower under the jerk limits.
            played = None
            if self.jerk_limited and self._ring is None:
                played = functools.partial(self._played_move, grasp=grasp)
            optimized = self._optimizer.optimize(
                self._planner, planned, grasp, played=played
            )
            path = optimized.path
            planned = dataclasses.replace(planned, path=path, polyline=path.waypoints)
            result = acceleration_limited = optimized.retimed
            planned_s += optimized.wall_s - optimized.retime_wall_s
            retime_s = optimized.retime_wall_s
            margin = self._scenario.planning.fixed_margin
            as_played = (
                optimized.played if optimized.improved else optimized.spline_played
            )
            if as_played is not None:
                result = as_played
            elif self._ring is not None:  # the kept path again, for the ring
                planned_s += retime_s
                start = time.perf_counter()
                profile = optimized.retimed
                result, grasp, margin, ring = self._retime_move(
                    path, grasp, lambda g: self.retime_on_profile(path, g, profile)
                )
                retime_s = time.perf_counter() - start
        else:
            start = time.perf_counter()
            if grasp is None:
                result = self.retime_path(planned.path, None)
            else:
                path = planned.path
                result, grasp, margin, ring = self._retime_move(
                    path, grasp, lambda g: self.retime_path(path, g)
                )
            retime_s = time.perf_counter() - start
        price = float("nan")  # cheap only beside the optimiser's own retime
        if grasp is not None and acceleration_limited is not None and not ring:
            price = self.grasp_price(planned.path, grasp, acceleration_limited)
        trajectory: Trajectory = result.trajectory
        guarantee = ""
        if carrying:
            guarantee = NO_GUARANTEE if grasp is None else grasp.guarantee() + ring
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
            grasp_margin=margin,
        )

    def _played_move(
        self, path: GeometricPath, profile: RetimeResult, grasp: GraspConstraint
    ) -> RetimeResult:
        """A MOVE path's retime as played under jerk limits, from its ``profile``."""
        return self.retime_on_profile(path, grasp, profile)

    def _retime_move(
        self,
        path: GeometricPath,
        grasp: GraspConstraint,
        retime_with: Callable[[GraspConstraint], RetimeResult],
    ) -> tuple[RetimeResult, GraspConstraint, float, str]:
        """``(result, grasp shrunk, m, words)``: a MOVE retimed with its margin.

        The scenario's ``planning.grasp_margin`` (``grasp`` has it already);
        with ``ring``, the least the bellows' ring needs
        (:func:`~rt_drake.retiming.retime_for_ring`; ``grasp`` unshrunk) and
        words for the guarantee.
        """
        if self._ring is None:
            return retime_with(grasp), grasp, self._scenario.planning.fixed_margin, ""
        found = retime_for_ring(
            retime_with, path, grasp, self._ring, self._plant, self._context, self._cup
        )
        words = (
            f"; bellows ring held at margin {found.margin:.3f} (ring rows "
            f"{found.load.ring:.3f}, D {found.load.factor:.2f}, "
            f"{found.retimes} retimes)"
        )
        return found.result, found.grasp, found.margin, words


__all__ = ["NO_GUARANTEE", "OnlineMotions", "time_at"]
