"""MoveOptimizer: a faster MOVE path than the planner's spline, in a fixed effort.

Stages (wall time of each in :attr:`OptimizedMove.timings`, s):

1. ``setup``: the scene with the load (the planner's ``prepare``), the
   clearance model; after the baseline, the coarse retimer (its grid placed
   at equal steps of the baseline's time, :meth:`MoveOptimizer.search_grid`)
   and its first grasp rows, the path family (:mod:`._family`), the warm
   starts (:mod:`._starts`).
2. ``baseline``: the spline path retimed by :func:`~._finish.retime_adaptive`,
   the duration to beat (the same scheme as the returned path's).
3. ``search``: CMA-ES (:mod:`._search`) from the best of x = 0 and the warm
   starts, ``max_evaluations`` candidate paths scored.
4. ``finish``: at most ``finish_tries`` of the best candidates, best first:
   dense tilt and vertical-end checks, the planner's continuous collision
   check with the load (:func:`rt_drake.planning.dense_check.check_path`)
   and the final retime (:func:`~._finish.retime_adaptive`); the first that
   passes and beats the baseline is returned, else the spline path
   (``improved`` False, the reasons in ``rejected``), not an error.

The effort is counted in evaluations, not in time: no stage reads a clock
to decide anything (the clocks only fill :attr:`OptimizedMove.timings`), so
the same spline path, options and seed give the same path on an idle or a
loaded machine. The planner's spline MOVE is an input: the cycle plans it
anyway (``spline_plan`` in the timings when :func:`optimize_move` plans it).
"""

from __future__ import annotations

import copy
import time
from collections.abc import Callable

import numpy as np
from pydrake.math import RigidTransform
from pydrake.multibody.plant import MultibodyPlant

from rt_drake import arguments
from rt_drake.dynamics.cup_frame import CupFrame
from rt_drake.planning.dense_check import check_path
from rt_drake.planning.result import PlannedPath
from rt_drake.retiming import GraspConstraint, JointLimits, RetimeError, RetimeResult
from rt_drake.shaping._clearance import ClearanceModel
from rt_drake.shaping._family import (
    FamilyError,
    PathFamily,
    corners,
)
from rt_drake.shaping._finish import (
    adaptive_grid,
    retime_adaptive,
    vertical_drift,
)
from rt_drake.shaping._objective import Objective
from rt_drake.shaping._options import (
    VERTICAL_DRIFT,
    VERTICAL_TOLERANCE_DEG,
    MoveOptimizerOptions,
    MovePlanner,
    OptimizedMove,
)
from rt_drake.shaping._search import (
    Candidate,
    cma_search,
)
from rt_drake.shaping._shape_task import Found, ShapeTask, StageClock
from rt_drake.shaping._starts import start_parameters
from rt_drake.shaping._surrogate import CoarseRetimer, EndGrid
from rt_drake.shaping.cup_chain import CupChain
from rt_drake.types.path import GeometricPath
from rt_drake.types.phase import Phase

#: Samples of the final path's tilt check.
TILT_SAMPLES = 1000
#: Via points added, one at a time, to rescue a search that found nothing.
EXTRA_VIA_POINTS = 2
#: Candidates the search returns, best first (the finish tries
#: ``finish_tries`` of them).
KEEP = 6


class MoveOptimizer:
    """Shapes MOVE paths of one arm for speed under the grasp constraint.

    Build it once per arm (it holds the batched kinematics) and call
    :meth:`optimize` per MOVE.

    Args:
        plant: The retimer's arm plant (positions = the path's joints).
        limits: Joint velocity and acceleration limits.
        options: Settings (defaults if None).
        cup: The cup frame C of ``plant`` (default ``CupFrame.of(plant)``).
        context: Scratch context of ``plant``.
    """

    def __init__(
        self,
        plant: MultibodyPlant,
        limits: JointLimits,
        options: MoveOptimizerOptions | None = None,
        cup: CupFrame | None = None,
        context=None,
    ) -> None:
        arguments.instance(plant, "plant", MultibodyPlant, where="MoveOptimizer")
        arguments.instance(limits, "limits", JointLimits, where="MoveOptimizer")
        if options is not None:
            arguments.instance(
                options, "options", MoveOptimizerOptions, where="MoveOptimizer"
            )
        if cup is not None:
            arguments.instance(cup, "cup", CupFrame, where="MoveOptimizer")
        self.plant = plant
        self.limits = limits
        self.options = options or MoveOptimizerOptions()
        self.cup = cup or CupFrame.of(plant)
        self.context = context or plant.CreateDefaultContext()
        self.chain = CupChain(plant, self.cup)

    def with_options(self, options: MoveOptimizerOptions) -> MoveOptimizer:
        """The same arm's optimiser with other options (kinematics shared)."""
        other = copy.copy(self)
        other.options = options
        return other

    def retime(
        self, path: GeometricPath, grasp: GraspConstraint | None
    ) -> RetimeResult:
        """``path`` retimed as the optimiser does (:func:`.retime_adaptive`)."""
        return retime_adaptive(
            self.plant, path, self.limits, grasp, self.options.final_gridpoints,
            context=self.context, cup=self.cup, chain=self.chain,
        )  # fmt: skip

    def optimize(
        self,
        planner: MovePlanner,
        spline: PlannedPath,
        grasp: GraspConstraint,
        timings: dict[str, float] | None = None,
        played: Callable[[GeometricPath, RetimeResult], RetimeResult] | None = None,
    ) -> OptimizedMove:
        """A MOVE as fast as found from the spline MOVE ``spline`` (same ends).

        Args:
            planner: The cycle planner (:class:`MovePlanner`), whose scene
                holds the other objects where they are.
            spline: The planner's MOVE (start: the grasp configuration).
            grasp: The carried object's grasp constraint ``F w <= g``.
            timings: Stage times (s) already spent (e.g. ``spline_plan``).
            played: The retime the MOVE is played with, from a path and its
                retime at the acceleration limits (e.g. the cycle's under
                jerk limits), or None: that retime itself. With it the
                finish keeps, of the ``finish_tries`` best candidates, the
                one whose played retime is the shortest, if it is shorter
                than the spline path's played retime
                (:attr:`OptimizedMove.played`, ``spline_played``).

        Raises:
            RetimeError: the spline path cannot be retimed.
        """
        options = self.options
        watch = StageClock(timings)
        with watch("setup"):
            scene = planner.prepare(
                Phase.MOVE, spline.object, spline.q_start, spline.X_OC
            )
        return self.shape(
            ShapeTask(
                scene, spline, grasp, lambda via: self._family(spline, via),
                lambda family, path: _certify(self.chain, family, scene, path, options),
                options.tilt_bound, None, options.starts, played,
            ),
            watch,
        )  # fmt: skip

    def shape(self, task: ShapeTask, watch: StageClock) -> OptimizedMove:
        """The search and the finish (stages 1-4) of ``task``, its scene prepared.

        :meth:`optimize` shapes a MOVE so; :func:`._pick_shaping.shape_pick`
        a pick. ``watch`` holds the stages' times since it was made (the
        scene's preparation included).
        """
        options = self.options
        wall, cpu = watch.wall, watch.cpu
        chain, spline, grasp = self.chain, task.spline, task.grasp
        scene = task.scene
        with watch("setup"):
            clearance = ClearanceModel(scene, chain)
        with watch("baseline"):
            baseline = self.retime(spline.path, grasp)
        with watch("setup"):
            surrogate = CoarseRetimer(
                chain, self.limits, grasp, self.search_grid(baseline),
                ends=self.end_grid(),
            )  # fmt: skip
            surrogate.select_rows(spline.path.waypoints[None])

            def objective_for(via: int) -> Objective:
                return Objective(
                    task.family(via), surrogate, clearance, scene.lower,
                    scene.upper, task.tilt_bound, options.clearance_margin,
                    spline.path, task.span,
                )  # fmt: skip

            try:
                objective: Objective | None = objective_for(options.via_points)
            except FamilyError as error:
                objective, family_error = None, str(error)
        baseline_played = None
        if task.played is not None:
            with watch("baseline"):
                baseline_played = task.played(spline.path, baseline)
        baseline_wall = watch.timings["baseline"]

        def result(path, retimed, improved, evaluations, rejected, retime_wall, played):
            tilt = float(np.degrees(chain.tilt(path.value(_s())).max()))
            return OptimizedMove(
                path, retimed, spline, baseline, improved, tilt, evaluations,
                time.perf_counter() - wall, time.process_time() - cpu, retime_wall,
                dict(watch.timings), tuple(rejected), played, baseline_played,
            )  # fmt: skip

        if objective is None:
            return result(
                spline.path, baseline, False, 0, [family_error], baseline_wall,
                baseline_played,
            )  # fmt: skip
        with watch("search"):
            candidates, evaluations = self._search(
                objective, objective_for, spline, task.starts
            )
        # The spline path on the search's grid: what a candidate must beat
        # there to be worth the finish (the grids' errors differ by percents).
        to_beat = surrogate.durations(spline.path.waypoints[None])[0]
        with watch("finish"):
            found = self._finish(task, candidates, to_beat, baseline, baseline_played)
        if found.path is not None:
            return result(
                found.path, found.retimed, True, evaluations, found.rejected,
                found.wall_s, found.played,
            )  # fmt: skip
        return result(
            spline.path, baseline, False, evaluations, found.rejected, baseline_wall,
            baseline_played,
        )  # fmt: skip

    def _finish(
        self,
        task: ShapeTask,
        candidates: list[tuple[PathFamily, Candidate]],
        to_beat: float,
        baseline: RetimeResult,
        baseline_played: RetimeResult | None,
    ) -> Found:
        """Stage 4: the first candidate that passes and beats the baseline.

        With ``task.played``, every one of the ``finish_tries`` candidates
        that passes is retimed as played, and the fastest that beats the
        baseline's played retime is kept.
        """
        found = Found()
        best = baseline if baseline_played is None else baseline_played
        for family, candidate in candidates[: self.options.finish_tries]:
            if candidate.duration >= to_beat:
                break
            path = GeometricPath.from_waypoints(family.waypoints(candidate.x)[0])
            reason = task.certify(family, path)
            if reason is None:
                before_wall = time.perf_counter()
                try:
                    retimed = self.retime(path, task.grasp)
                    played = (
                        retimed if task.played is None else task.played(path, retimed)
                    )
                except RetimeError as error:
                    reason = f"retime: {error}"
                else:
                    wall_s = time.perf_counter() - before_wall
                    if played.duration < best.duration:
                        best = played
                        found = Found(
                            path, retimed, played if task.played else None, wall_s,
                            found.rejected,
                        )  # fmt: skip
                        if task.played is None:
                            break
                        continue
                    reason = f"retimed {played.duration:.3f} s, not shorter"
            found.rejected.append(reason)
        return found

    def search_grid(self, baseline: RetimeResult) -> int | np.ndarray:
        """The search's grid: its points at equal steps of the spline's time.

        ``search_gridpoints`` points placed by the spline path's retimed
        profile (:func:`~._finish.adaptive_grid` with weight
        ``search_grid_weight``), or uniform if that weight is None.
        """
        options = self.options
        if options.search_grid_weight is None:
            return options.search_gridpoints
        return adaptive_grid(
            baseline.gridpoints, baseline.sd, options.search_gridpoints,
            options.search_grid_weight,
        )  # fmt: skip

    def end_grid(self) -> EndGrid | None:
        """Each candidate's own grid over its vertical ends, or None (options)."""
        options = self.options
        if options.search_end_points == 0:
            return None
        return EndGrid(
            options.search_end_points, options.search_end_span,
            options.vertical_points,
        )  # fmt: skip

    def _family(self, spline: PlannedPath, via: int) -> PathFamily:
        options = self.options
        return PathFamily(
            self.chain,
            spline.path.waypoints[0],
            spline.path.waypoints[-1],
            corners(spline.path, via),
            options.vertical_height,
            options.vertical_points,
            np.broadcast_to(
                np.asarray(options.joint_scale, float), self.chain.num_joints
            ),
            vertical=options.max_tilt_deg < VERTICAL_TOLERANCE_DEG,
        )

    def _search(
        self,
        objective: Objective,
        objective_for: Callable[[int], Objective],
        spline: PlannedPath,
        starts: int,
    ) -> tuple[list[tuple[PathFamily, Candidate]], int]:
        """CMA-ES from x = 0 and ``starts`` warm starts; rescue paths if none found."""
        options = self.options
        x0 = start_parameters(objective.family, spline.path, starts)
        found = cma_search(
            objective, objective.family.dim, options.max_evaluations, options.sigma,
            options.seed, options.population, keep=KEEP, x0=x0,
        )  # fmt: skip
        candidates = [(objective.family, c) for c in found.candidates]
        evaluations = found.evaluations
        # Nothing feasible (e.g. a lift close to a wall, whose corners the
        # spline through few via points cuts): the starting paths through
        # more of the spline path's corners follow it more closely.
        for extra in range(1, EXTRA_VIA_POINTS + 1):
            if candidates:
                break
            try:
                rescue = objective_for(options.via_points + extra)
            except FamilyError:
                break
            x = np.zeros((1, rescue.family.dim))
            values, feasible = rescue(x)
            evaluations += 1
            if feasible[0]:
                candidates = [(rescue.family, Candidate(x[0], float(values[0])))]
        return candidates, evaluations


def optimize_move(
    planner: MovePlanner,
    plant: MultibodyPlant,
    q_grasp: np.ndarray,
    name: str,
    grasp: GraspConstraint,
    limits: JointLimits,
    options: MoveOptimizerOptions | None = None,
    X_WO_goal: RigidTransform | None = None,
    spline: PlannedPath | None = None,
    context=None,
    cup: CupFrame | None = None,
) -> OptimizedMove:
    """A MOVE of object ``name`` from ``q_grasp`` to its place, as fast as found.

    :meth:`MoveOptimizer.optimize` for one MOVE, planning the spline MOVE
    first if ``spline`` is None (its time is ``timings["spline_plan"]``).

    Args:
        planner: The cycle planner (:class:`MovePlanner`).
        plant: The retimer's arm plant (positions = the path's joints).
        q_grasp: Grasp configuration (rad), the MOVE's start.
        name: The carried object.
        grasp: Its grasp constraint ``F w <= g``.
        limits: Joint velocity and acceleration limits.
        options: Settings (defaults if None).
        X_WO_goal: Place pose of the object (default: its scenario goal).
        spline: The planner's MOVE from ``q_grasp`` if already planned.
        context: Scratch context of ``plant``.
        cup: The cup frame C of ``plant`` (default ``CupFrame.of(plant)``).

    Raises:
        PlanningError: the spline MOVE could not be planned.
        RetimeError: the spline path cannot be retimed.
    """
    timings = {"spline_plan": 0.0}
    if spline is None:
        before = time.perf_counter()
        spline = planner.plan_move(q_grasp, name, X_WO_goal)
        timings["spline_plan"] = time.perf_counter() - before
    optimizer = MoveOptimizer(plant, limits, options, cup, context)
    return optimizer.optimize(planner, spline, grasp, timings)


def _s() -> np.ndarray:
    return np.linspace(0.0, 1.0, TILT_SAMPLES)


def _certify(chain, family, scene, path: GeometricPath, options) -> str | None:
    """None if the path passes the tilt, vertical-end and collision checks."""
    tilt = chain.tilt(path.value(_s())).max()
    if tilt > options.tilt_bound + 1e-9:
        return f"tilt {np.degrees(tilt):.2f} deg above the bound"
    s_up, s_down = family.segment_ends(path.knots)
    drift = max(
        vertical_drift(chain, path, 0.0, s_up), vertical_drift(chain, path, s_down, 1.0)
    )
    if drift > VERTICAL_DRIFT:
        return f"a vertical end segment drifts {1e3 * drift:.2f} mm"
    check = check_path(scene, path)
    if not check.ok:
        return f"{check.reason} at s = {check.s:.3f}"
    return None


__all__ = ["KEEP", "MoveOptimizer", "optimize_move"]
