"""optimize_move: a faster MOVE path than the planner's spline, within a budget.

Stages (wall time of each in :attr:`OptimizedMove.timings`, s):

1. ``spline_plan``: the planner's spline MOVE, unless given (outside the
   budget: the cycle plans it anyway).
2. ``baseline``: the spline path retimed on the adaptive grid of
   :mod:`.finish`: the duration to beat.
3. ``setup``: the path family (:mod:`.family`), the coarse retimer and its
   first grasp rows, the clearance model of the scene with the load.
4. ``search``: CMA-ES (:mod:`.search`) until the budget, less the time the
   finish needs (estimated from the baseline's retime and dense check).
5. ``finish``: the best candidates, best first: dense tilt and vertical-end
   checks, the planner's continuous collision check with the load
   (:func:`rt_drake.planning.dense_check.check_path`) and the adaptive
   retime; the first that passes and beats the baseline is returned, else
   the spline path (``improved`` False), not an error.
"""

from __future__ import annotations

import time

import numpy as np
from pydrake.math import RigidTransform
from pydrake.multibody.plant import MultibodyPlant

from rt_drake.cup_frame import CupFrame
from rt_drake.phase import Phase
from rt_drake.planning.dense_check import check_path
from rt_drake.planning.path import GeometricPath
from rt_drake.planning.result import PlannedPath
from rt_drake.planning.shape.clearance import ClearanceModel
from rt_drake.planning.shape.family import FamilyError, PathFamily, corners
from rt_drake.planning.shape.finish import retime_adaptive, vertical_drift
from rt_drake.planning.shape.kinematics import CupChain
from rt_drake.planning.shape.objective import Objective
from rt_drake.planning.shape.options import (
    VERTICAL_DRIFT,
    VERTICAL_TOLERANCE_DEG,
    Clock,
    MoveOptimizerOptions,
    MovePlanner,
    OptimizedMove,
)
from rt_drake.planning.shape.search import Candidate, cma_search
from rt_drake.planning.shape.surrogate import CoarseRetimer
from rt_drake.retiming import GraspConstraint, JointLimits, RetimeError, RetimeResult

#: Samples of the final path's tilt check.
TILT_SAMPLES = 1000
#: Via points added, one at a time, to rescue a search that found nothing.
EXTRA_VIA_POINTS = 2


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

    Args:
        planner: The cycle planner (:class:`MovePlanner`: ``plan_move``,
            ``prepare``, ``scene``).
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
    options = options or MoveOptimizerOptions()
    context = context or plant.CreateDefaultContext()
    cup = cup or CupFrame.of(plant)
    timings = {k: 0.0 for k in ("spline_plan", "baseline", "setup", "search", "finish")}
    watch = _Stopwatch(timings)
    with watch("spline_plan"):
        if spline is None:
            spline = planner.plan_move(q_grasp, name, X_WO_goal)
        else:
            planner.prepare(Phase.MOVE, name, q_grasp, spline.X_OC)
    clock = time.perf_counter if options.clock is Clock.WALL else time.process_time
    start, wall, cpu = clock(), time.perf_counter(), time.process_time()

    def result(path, retimed, improved, evaluations=0, rejected=()):
        tilt = float(np.degrees(chain.tilt(path.value(_s())).max()))
        return OptimizedMove(
            path, retimed, spline, baseline, improved, tilt, evaluations,
            time.perf_counter() - wall, time.process_time() - cpu, timings,
            tuple(rejected),
        )  # fmt: skip

    retime = _retimer(plant, limits, grasp, options, context, cup)
    with watch("baseline"):
        before = clock()
        baseline = retime(spline.path)
        retime_cost = clock() - before
    # The finish retimes a candidate and checks it densely: the baseline's
    # retime, and the planner's dense check (wall time, scaled to the clock).
    to_clock = retime_cost / max(timings["baseline"], 1e-9)
    finish_cost = 1.1 * (retime_cost + to_clock * spline.timing.check_s)
    chain = CupChain(plant, cup)
    with watch("setup"):
        surrogate = CoarseRetimer(chain, limits, grasp, options.search_gridpoints)
        surrogate.select_rows(spline.path.waypoints[None])
        clearance = ClearanceModel(planner.scene, chain)

        def objective_for(via: int) -> Objective:
            return Objective(
                _family(chain, spline, options, via), surrogate, clearance,
                planner.scene.lower, planner.scene.upper, options.tilt_bound,
                options.clearance_margin, spline.path,
            )  # fmt: skip

        try:
            objective = objective_for(options.via_points)
        except FamilyError as error:
            return result(spline.path, baseline, False, rejected=[str(error)])
        # The spline path on the search's grid: what a candidate must beat
        # there to be worth the finish (the grids' errors differ by percents).
        to_beat = surrogate.durations(spline.path.waypoints[None])[0]
    with watch("search"):
        found = cma_search(
            objective, objective.family.dim,
            lambda: clock() > start + options.budget_s - finish_cost,
            options.sigma, options.seed, options.population,
            max_evaluations=options.max_evaluations,
        )  # fmt: skip
        candidates = [(objective.family, c) for c in found.candidates]
        # Nothing feasible (e.g. a lift close to a wall, whose corners the
        # spline through few via points cuts): the starting paths through
        # more of the spline path's corners follow it more closely.
        for extra in range(1, EXTRA_VIA_POINTS + 1):
            if candidates:
                break
            rescue = objective_for(options.via_points + extra)
            x0 = np.zeros((1, rescue.family.dim))
            values, feasible = rescue(x0)
            if feasible[0]:
                candidates = [(rescue.family, Candidate(x0[0], float(values[0])))]
    rejected: list[str] = []
    with watch("finish"):
        for index, (family, candidate) in enumerate(candidates):
            late = clock() + 0.5 * finish_cost > start + options.budget_s
            if candidate.duration >= to_beat or (index and late):
                break
            path = GeometricPath.from_waypoints(family.waypoints(candidate.x)[0])
            reason = _certify(chain, family, planner.scene, path, options)
            if reason is None:
                try:
                    retimed = retime(path)
                except RetimeError as error:
                    reason = f"retime: {error}"
                else:
                    if retimed.duration < baseline.duration:
                        return result(path, retimed, True, found.evaluations, rejected)
                    reason = f"retimed {retimed.duration:.3f} s, not shorter"
            rejected.append(reason)
    return result(spline.path, baseline, False, found.evaluations, rejected)


class _Stopwatch:
    """``with watch("stage"):`` adds the block's wall time to timings[stage]."""

    def __init__(self, timings: dict) -> None:
        self.timings = timings
        for key in timings:
            timings[key] = 0.0

    def __call__(self, stage: str) -> _Stopwatch:
        self._stage = stage
        return self

    def __enter__(self) -> _Stopwatch:
        self._start = time.perf_counter()
        return self

    def __exit__(self, *exc) -> None:
        self.timings[self._stage] += time.perf_counter() - self._start


def _s() -> np.ndarray:
    return np.linspace(0.0, 1.0, TILT_SAMPLES)


def _retimer(plant, limits, grasp, options, context, cup):
    def retime(path: GeometricPath) -> RetimeResult:
        return retime_adaptive(
            plant, path, limits, grasp, options.final_gridpoints, context=context,
            cup=cup,
        )  # fmt: skip

    return retime


def _family(chain: CupChain, spline: PlannedPath, options, via: int) -> PathFamily:
    return PathFamily(
        chain,
        spline.path.waypoints[0],
        spline.path.waypoints[-1],
        corners(spline.path, via),
        options.vertical_height,
        options.vertical_points,
        np.broadcast_to(np.asarray(options.joint_scale, float), chain.num_joints),
        vertical=options.max_tilt_deg < VERTICAL_TOLERANCE_DEG,
    )


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


__all__ = ["optimize_move"]
