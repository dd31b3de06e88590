"""The paper's Table I experiment, in simulation (Section V-A).

For each of n random transports of one object (start pose in the bin region,
goal on the destination region, both sampled from the scenario's
``random_transport``): plan the MOVE path, retime it with and without the
grasp constraint, and play each in the physics of the cycle
(:mod:`._rollout`). Then play the constrained MOVE faster and faster to find
the speed at which the object starts to slip.

The grasp configuration comes from APPROACH and REACH from home, or, when
``random_transport.start_on_cup`` is set (objects in free space, as the
paper's regions), from IK at the start pose with the object already sealed
on the cup (the grasp yaw flip whose MOVE is fastest). With ``optimize``,
each trial also optimises its MOVE and plays it (:mod:`._optimized_transport`).
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
from pydrake.common.schema import Transform
from pydrake.math import RigidTransform

from rt_drake.errors import InputError, RtDrakeError, ScenarioError
from rt_drake.experiments._optimized_transport import (
    REPLAY_FILE,
    optimized_trial,
    summarize_optimized,
)
from rt_drake.experiments._rollout import (
    SPEED_FACTORS,
    critical_speed,
    rollout_scenario,
    simulate_move,
)
from rt_drake.experiments._trial_pool import run_trials
from rt_drake.model.scenario import (
    ObjectConfig,
    Scenario,
    load_scenario,
)
from rt_drake.planning import GeometricPath, PlanningError, sample_transports
from rt_drake.retiming import GraspConstraint, RetimeError, RetimeResult
from rt_drake.simulation import Motion, OnlineMotions
from rt_drake.types.phase import Phase


def transport_inputs(
    scenario_path: str | Path, n: int, workers: int, object_name: str | None
) -> tuple[Scenario, str]:
    """The scenario and the carried object's name, after checking the arguments.

    Raises:
        InputError: n or workers not an integer, or below one.
        ScenarioError: the scenario has no ``random_transport`` section or
            no such object.
    """
    scenario = load_scenario(scenario_path)
    for what, value in (
        ("number of trials", n),
        ("number of worker processes", workers),
    ):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
            raise InputError(f"{what} must be an integer, got {value!r}")
    if n < 1:
        raise InputError(f"number of trials must be >= 1, got {n}")
    if workers < 1:
        raise InputError(f"number of worker processes must be >= 1, got {workers}")
    transport = scenario.random_transport
    if transport is None:
        raise ScenarioError(
            f"{scenario_path}: the scenario has no 'random_transport' section"
        )
    name = object_name or transport.object
    scenario.object(name)
    return scenario, name


def transport_scenario(
    scenario: Scenario,
    object_name: str,
    X_WO_start: RigidTransform,
    X_WO_goal: RigidTransform,
) -> Scenario:
    """``scenario`` holding only ``object_name``, at one transport's poses.

    ``X_WO_start`` and ``X_WO_goal``: the object's body frame O in the world W.
    """
    obj = scenario.object(object_name)
    moved = dataclasses.replace(
        obj, start=Transform(X_WO_start), goal=Transform(X_WO_goal)
    )
    return dataclasses.replace(scenario, objects=[moved])


def transport_trial(
    scenario: Scenario,
    object_name: str,
    index: int,
    X_WO_start: RigidTransform,
    X_WO_goal: RigidTransform,
    seed: int,
    optimize: bool = False,
    replay_path: Path | None = None,
    jerk_limits: bool = False,
) -> dict[str, Any]:
    """Plan, retime (with and without the constraint) and simulate one transport.

    With ``optimize``, also the optimised MOVE (:func:`.optimized_trial`),
    its Meshcat replay written to ``replay_path`` if given. With
    ``jerk_limits``, both retimes keep the scenario's ``robot.jerk_limits``
    (the constrained one also ``planning.grasp_ramp_s``'s).

    A path that the retimer refuses with or without the constraint (a
    :class:`~rt_drake.retiming.RetimeError`, e.g. not controllable under
    the jerk limits) is not played: the trial is ``{"index", "start",
    "goal", "not_retimed": "<which retime>: <message>"}``.
    """
    try:
        return _retimed_trial(
            scenario, object_name, index, X_WO_start, X_WO_goal, seed, optimize,
            replay_path, jerk_limits,
        )  # fmt: skip
    except NotRetimed as error:
        return not_retimed_trial(index, X_WO_start, X_WO_goal, error)


class NotRetimed(RtDrakeError):
    """The retimer refused one of a trial's MOVEs (its message says which)."""


def not_retimed_trial(
    index: int, X_WO_start: RigidTransform, X_WO_goal: RigidTransform, error: Exception
) -> dict[str, Any]:
    """A trial not played: ``{"index", "start", "goal", "not_retimed"}``."""
    return {
        "index": index,
        "start": pose_list(X_WO_start),
        "goal": pose_list(X_WO_goal),
        "not_retimed": str(error),
    }


def _retimed_trial(
    scenario: Scenario,
    object_name: str,
    index: int,
    X_WO_start: RigidTransform,
    X_WO_goal: RigidTransform,
    seed: int,
    optimize: bool,
    replay_path: Path | None,
    jerk_limits: bool,
) -> dict[str, Any]:
    """:func:`transport_trial` once both MOVEs are retimed.

    Raises:
        NotRetimed: the retimer refused the MOVE with or without the
            grasp constraint.
    """
    planner_scenario = transport_scenario(scenario, object_name, X_WO_start, X_WO_goal)
    constrained = OnlineMotions(
        planner_scenario,
        grasp_constraint=True,
        seed=seed + index,
        optimize=False,
        jerk_limits=jerk_limits,
    )
    planned_obj = planner_scenario.objects[0]
    transport = scenario.random_transport
    if transport is not None and transport.start_on_cup:
        start = time.perf_counter()
        try:
            move_c = move_from_the_cup(constrained, planned_obj, X_WO_start)
        except RetimeError as error:
            raise NotRetimed(f"with the grasp constraint: {error}") from None
        q_grasp = move_c.planned.q_start if move_c.planned is not None else None
    else:
        approach = constrained.approach(constrained.q_home, planned_obj)
        reach = constrained.reach(approach.q_end, planned_obj)
        q_grasp = reach.q_end
        start = time.perf_counter()
        try:
            move_c = constrained.move(q_grasp, planned_obj, reach)
        except RetimeError as error:
            raise NotRetimed(f"with the grasp constraint: {error}") from None
    assert move_c.planned is not None and move_c.retimed is not None
    assert q_grasp is not None
    assert move_c.grasp is not None
    path = move_c.planned.path
    result_c = move_c.retimed
    try:
        result_u = constrained.retime_path(path, grasp=None)
    except RetimeError as error:
        raise NotRetimed(f"without the grasp constraint: {error}") from None
    plan_s = time.perf_counter() - start

    rollout_world = rollout_scenario(planner_scenario, q_grasp)
    unconstrained = simulate_move(rollout_world, q_grasp, result_u.trajectory)
    critical, sweep = critical_speed(rollout_world, q_grasp, move_c.trajectory)
    constrained_rollout = sweep[0][1]
    d_u, d_c = result_u.duration, result_c.duration
    trial = {
        "index": index,
        "start": pose_list(X_WO_start),
        "goal": pose_list(X_WO_goal),
        "duration_unconstrained_s": d_u,
        "duration_constrained_s": d_c,
        "time_extension_pct": 100.0 * (d_c - d_u) / d_c,
        "success_unconstrained": unconstrained.success,
        "success_constrained": constrained_rollout.success,
        "slip_unconstrained": unconstrained.as_dict(),
        "slip_constrained": constrained_rollout.as_dict(),
        "critical_speed_factor": critical,
        "speed_sweep": [
            {"factor": f, **r.as_dict(), "success": r.success} for f, r in sweep
        ],
        "plan_and_retime_s": plan_s,
        "profiles": _profiles(constrained, path, move_c.grasp, result_c, result_u),
    }
    if optimize:
        trial.update(
            optimized_trial(
                planner_scenario,
                constrained.planner,
                move_c.planned,
                result_c,
                move_c.grasp,
                rollout_world,
                replay_path,
                constrained,
            )  # fmt: skip
        )
    return trial


def played_move(
    scenario: Scenario,
    motions: OnlineMotions,
    obj: ObjectConfig,
    X_WO_start: RigidTransform,
) -> Motion:
    """A trial's MOVE, planned and retimed as the experiments play it.

    With ``random_transport.start_on_cup`` the MOVE from the object sealed
    on the cup at ``X_WO_start`` (:func:`move_from_the_cup`); else APPROACH
    and REACH from home, then the MOVE from the grasp they reach.

    Raises:
        PlanningError, RetimeError: a motion does not plan or retime.
    """
    transport = scenario.random_transport
    if transport is not None and transport.start_on_cup:
        return move_from_the_cup(motions, obj, X_WO_start)
    approach = motions.approach(motions.q_home, obj)
    reach = motions.reach(approach.q_end, obj)
    return motions.move(reach.q_end, obj, reach)


def move_from_the_cup(
    motions: OnlineMotions, obj: ObjectConfig, X_WO_start: RigidTransform
) -> Motion:
    """The fastest MOVE from the object sealed on the cup at X_WO_start.

    For each grasp yaw flip (:meth:`CyclePlanner.grasps`), the configuration
    by IK at the start and its MOVE, planned and retimed under the grasp
    constraint; the flip whose MOVE is shortest in time. (The first flip
    alone can put the goal on another IK branch: on random_transport_paper,
    seed 0, transport 16's MOVE with the wrist turned half a turn took 4.95 s
    and tilted the cup 138 deg.)

    A flip whose MOVE the retimer refuses is skipped like one that does
    not plan.

    Raises:
        PlanningError: no grasp yaw flip has a reachable, collision-free
            configuration whose MOVE plans (the last flip's error).
        RetimeError: likewise, the last flip's MOVE planned but the retimer
            refused it.
    """
    planner = motions.planner
    error: PlanningError | RetimeError | None = None
    best: tuple[float, Motion] | None = None
    for X_OC in planner.grasps(obj.name):
        try:
            planner.prepare(Phase.MOVE, obj.name, planner.q_home, X_OC)
            q = planner.configuration_for(X_WO_start @ X_OC, planner.q_home, obj.name)
            motion = motions.move(q, obj)
        except (PlanningError, RetimeError) as exc:
            error = exc
            continue
        assert motion.retimed is not None
        if best is None or motion.retimed.duration < best[0]:
            best = (motion.retimed.duration, motion)
    if best is None:
        assert error is not None
        raise error
    return best[1]


def pose_list(X: RigidTransform) -> list[float]:
    """[x, y, z, yaw_deg] of X (m, deg: yaw about the world's z)."""
    yaw = math.degrees(
        math.atan2(X.rotation().matrix()[1, 0], X.rotation().matrix()[0, 0])
    )
    return [*map(float, X.translation()), yaw]


def _profiles(
    motions: OnlineMotions,
    path: GeometricPath,
    grasp: GraspConstraint,
    constrained: RetimeResult,
    unconstrained: RetimeResult,
) -> dict[str, list[float]]:
    """s'(s), its velocity-limit bound, and the grasp margin over time, for plots.

    ``s`` is the constrained retime's grid (of ``sd_constrained`` and
    ``sd_velocity_limit``), ``s_unconstrained`` the other's.
    """
    return {
        "s": constrained.gridpoints.tolist(),
        "sd_constrained": constrained.sd.tolist(),
        # the retimer refines each grid where its own limits need it, so the
        # two grids may differ
        "s_unconstrained": unconstrained.gridpoints.tolist(),
        "sd_unconstrained": unconstrained.sd.tolist(),
        "sd_velocity_limit": motions.velocity_bound(
            path, constrained.gridpoints
        ).tolist(),
        "t_constrained": constrained.trajectory.times.tolist(),
        "t_unconstrained": unconstrained.trajectory.times.tolist(),
        "margin_constrained": motions.grasp_margin(path, constrained, grasp).tolist(),
        "margin_unconstrained": motions.grasp_margin(
            path, unconstrained, grasp
        ).tolist(),
    }


def _trial_job(args: tuple) -> dict[str, Any]:
    """One trial in a worker: scenarios do not pickle, so it is loaded again."""
    path, object_name, index, X_start, X_goal, seed, optimize, replay, cup, jerk = args
    scenario = load_scenario(path).with_cup_physics(cup)
    return transport_trial(
        scenario,
        object_name,
        index,
        RigidTransform(X_start),
        RigidTransform(X_goal),
        seed,
        optimize,
        replay,
        jerk,
    )


def run_transport_experiment(
    scenario_path: str | Path,
    n: int = 20,
    seed: int = 0,
    object_name: str | None = None,
    workers: int = 1,
    optimize: bool | None = None,
    out_dir: Path | None = None,
    progress: Callable[[int, int], None] | None = None,
    cup_physics: str | None = None,
    jerk_limits: bool = False,
) -> dict[str, Any]:
    """Run n trials (in ``workers`` processes); return results and a summary.

    ``cup_physics``: simulate the rollouts with this cup (``rim`` or
    ``bellows``; None: the scenario's ``cup_physics.kind``); the results
    name it. With ``jerk_limits``, every retime keeps the scenario's
    ``robot.jerk_limits``.

    With ``optimize`` (None: the scenario's ``planning.optimize_move``),
    each trial also optimises its MOVE and plays it; the
    first trial's optimised MOVE is replayed in Meshcat into
    ``out_dir / REPLAY_FILE`` if ``out_dir`` is given.
    ``progress(done, n)`` is called as each trial finishes (and with 0 first).

    Raises:
        InputError: fewer than one trial or one worker.
        ScenarioError: the scenario has no ``random_transport`` section or
            no such object.
    """
    scenario, name = transport_inputs(scenario_path, n, workers, object_name)
    scenario = scenario.with_cup_physics(cup_physics)
    if optimize is None:
        optimize = scenario.planning.optimize_move
    pairs = sample_transports(scenario, n, seed)
    replay = None if out_dir is None or not optimize else Path(out_dir) / REPLAY_FILE
    jobs = [
        (
            str(scenario_path),
            name,
            i,
            X_s.GetAsMatrix4(),
            X_g.GetAsMatrix4(),
            seed,
            optimize,
            replay if i == 0 else None,
            scenario.cup_physics.kind,
            jerk_limits,
        )  # fmt: skip
        for i, (X_s, X_g) in enumerate(pairs)
    ]
    done = run_trials(_trial_job, jobs, workers, progress)
    trials = [t for t in done if "not_retimed" not in t]
    not_retimed = [t for t in done if "not_retimed" in t]
    if not trials:
        first = not_retimed[0]
        raise RetimeError(
            f"{scenario_path}: none of the {n} MOVEs could be retimed; path "
            f"{first['index']}: {first['not_retimed']}"
        )
    return {
        "object": name,
        "seed": seed,
        "n": n,
        "optimize": optimize,
        "cup_physics": scenario.cup_physics.kind,
        "jerk_limits": jerk_limits,
        "grasp_ramp_s": scenario.planning.grasp_ramp_s,
        "trials": trials,
        "not_retimed": not_retimed,
        "summary": summarize(trials, len(not_retimed)),
    }


def summarize(trials: list[dict[str, Any]], not_retimed: int = 0) -> dict[str, Any]:
    """Counts of successes, duration and extension statistics, critical speeds.

    ``trials``: the played ones; ``not_retimed``: how many more the retimer
    refused (``n`` counts the played trials, ``n_sampled`` both).
    """
    critical = [t["critical_speed_factor"] for t in trials]
    finite = [c for c in critical if c is not None]
    return {
        "n": len(trials),
        "n_sampled": len(trials) + not_retimed,
        "not_retimed": not_retimed,
        "success_constrained": sum(t["success_constrained"] for t in trials),
        "success_unconstrained": sum(t["success_unconstrained"] for t in trials),
        "duration_constrained_s": _stats([t["duration_constrained_s"] for t in trials]),
        "duration_unconstrained_s": _stats(
            [t["duration_unconstrained_s"] for t in trials]
        ),
        "time_extension_pct": _stats([t["time_extension_pct"] for t in trials]),
        "critical_speed_factor_median": float(np.median(finite))
        if len(finite) == len(critical)
        else None,
        "critical_speed_factor_min": min(finite) if finite else None,
        "never_slipped_up_to": None
        if len(finite) == len(critical)
        else SPEED_FACTORS[-1],
        "critical_speed_factors": critical,
        **(summarize_optimized(trials) if "duration_optimized_s" in trials[0] else {}),
    }


def _stats(values: list[float]) -> dict[str, float]:
    array = np.asarray(values, dtype=float)
    return {
        "min": float(array.min()),
        "median": float(np.median(array)),
        "mean": float(array.mean()),
        "max": float(array.max()),
    }


__all__ = [
    "move_from_the_cup",
    "run_transport_experiment",
    "summarize",
    "transport_inputs",
    "transport_scenario",
    "transport_trial",
]
