"""Table I with objects the robot does not know exactly (issue 15).

For each of n random transports (the poses of :mod:`._transport_experiment`), the MOVE
is planned once and retimed twice: for the nominal object (the one of the
scenario's model) and for every object of its uncertainty set with every
cup of the cup's range (:meth:`~rt_drake.retiming.GraspConstraint.robust`).
Each trial then plays both trajectories in the cycle's physics with the same
TRUE object, drawn (seeded) from the set's hardest corners (heaviest, largest
moments, centre of mass at a random corner:
:func:`~rt_drake.uncertainty.object_samples.hardest_corner`), and the worst cup of the
range. The robust duration is also compared with a lower bound of the true
robust optimum: the retime that holds a dense sample of the set (its
corners and ``SAMPLE`` random objects, bodies only), stacked. And the robust
trajectory is checked, at 1 kHz, for every object of that sample by another
route than the retimer's
(:func:`~rt_drake.dynamics.newton_euler.reference_object_wrenches`):
``sound_excess`` is the largest ``max_k F_k w / g_k - 1`` found (the
retimer's contract: at most 1e-3). With ``sweep``, the robust plan is also
played faster and faster with the true object until it slips (its critical
speed factor, as ``experiment transport`` finds the nominal one's).

A trial whose nominal MOVE or robust retime the retimer refuses (e.g. the
set's worst object slips off the cup even at rest) is not played: it is
recorded as ``{"index", "start", "goal", "not_retimed": "<which plan>:
<message>"}``, as ``experiment transport`` records its own, and the run
goes on.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
from pydrake.math import RigidTransform
from pydrake.multibody.tree import SpatialInertia

from rt_drake.contact import worst_cup_polytope
from rt_drake.dynamics.cup_frame import CupFrame
from rt_drake.dynamics.newton_euler import reference_object_wrenches
from rt_drake.errors import ScenarioError
from rt_drake.experiments._rollout import (
    SPEED_FACTORS,
    critical_speed,
    rollout_scenario,
    simulate_move,
)
from rt_drake.experiments._transport_experiment import (
    NotRetimed,
    not_retimed_trial,
    pose_list,
    transport_inputs,
    transport_scenario,
)
from rt_drake.experiments._trial_pool import run_trials
from rt_drake.model.plant import make_arm_plant
from rt_drake.model.scenario import (
    ObjectConfig,
    Scenario,
    load_scenario,
)
from rt_drake.planning import sample_transports
from rt_drake.retiming import GraspConstraint, RetimeError, TimedPath
from rt_drake.retiming.stage_rows import (
    normalised_rows,
    wrench_ratios,
)
from rt_drake.simulation import OnlineMotions
from rt_drake.types.object_uncertainty import ObjectUncertainty
from rt_drake.uncertainty.object_samples import (
    ObjectInertia,
    corners,
    hardest_corner,
    random_objects,
)

#: Random objects of the dense sample (besides the corners).
SAMPLE = 200


def robust_trial(
    scenario: Scenario,
    object_name: str,
    index: int,
    X_WO_start: RigidTransform,
    X_WO_goal: RigidTransform,
    seed: int,
    jerk_limits: bool = False,
    sweep: bool = False,
) -> dict[str, Any]:
    """Plan one transport, retime it nominal and robust, play both (true object).

    Every retime holds the grasp: under the scenario's
    ``planning.grasp_ramp_s`` when it gives one, and its
    ``robot.jerk_limits`` too with ``jerk_limits``. The physics is the
    scenario's ``cup_physics``. With ``sweep``, also the robust plan's
    critical speed factor (``critical_speed_factor``, ``speed_sweep``).

    A MOVE the retimer refuses, nominal or robust, is not played: the trial
    is ``{"index", "start", "goal", "not_retimed": "<which plan>:
    <message>"}``.
    """
    try:
        return _played_trial(
            scenario, object_name, index, X_WO_start, X_WO_goal, seed,
            jerk_limits, sweep,
        )  # fmt: skip
    except NotRetimed as error:
        return not_retimed_trial(index, X_WO_start, X_WO_goal, error)


def _played_trial(
    scenario: Scenario,
    object_name: str,
    index: int,
    X_WO_start: RigidTransform,
    X_WO_goal: RigidTransform,
    seed: int,
    jerk_limits: bool,
    sweep: bool,
) -> dict[str, Any]:
    """:func:`robust_trial` once both MOVEs are retimed.

    Raises:
        NotRetimed: the retimer refused the nominal MOVE or its robust retime.
    """
    obj = scenario.object(object_name)
    uncertainty = _uncertainty(obj)
    trial = transport_scenario(scenario, object_name, X_WO_start, X_WO_goal)
    motions = OnlineMotions(
        trial,
        grasp_constraint=True,
        seed=seed + index,
        robust=False,
        optimize=False,
        jerk_limits=jerk_limits,
    )
    planned_obj = trial.objects[0]
    approach = motions.approach(motions.q_home, planned_obj)
    reach = motions.reach(approach.q_end, planned_obj)
    q_grasp = reach.q_end
    try:
        nominal = motions.move(q_grasp, planned_obj, reach)
    except RetimeError as error:
        raise NotRetimed(f"nominal plan: {error}") from None
    assert nominal.planned is not None and nominal.retimed is not None
    path, X_OC = nominal.planned.path, nominal.planned.X_OC
    robust_grasp = motions.grasp_for(planned_obj, X_OC, robust=True)
    start = time.perf_counter()
    try:
        robust = motions.retime_path(path, robust_grasp)
    except RetimeError as error:
        raise NotRetimed(f"robust plan: {error}") from None
    robust_s = time.perf_counter() - start

    rng = np.random.default_rng([seed, index])
    world, inertias, true = true_object_world(trial, q_grasp, obj, uncertainty, rng)
    model = ObjectInertia.of_model(obj)
    sample = corners(model, uncertainty) + random_objects(
        model, uncertainty, SAMPLE, rng
    )
    cup = trial.cup
    held_sample = [o.held(X_OC) for o in sample]
    bound = motions.retime_path(path, GraspConstraint.for_objects(held_sample, cup))
    excess = sound_excess(trial, robust.trajectory, held_sample)
    played = {
        "nominal": simulate_move(
            world, q_grasp, nominal.trajectory, object_inertias=inertias
        )
    }
    speeds: dict[str, Any] = {}
    if sweep:  # its first rollout, at speed 1, is the robust plan's
        critical, rollouts = critical_speed(
            world, q_grasp, robust.trajectory, object_inertias=inertias
        )
        played["robust"] = rollouts[0][1]
        speeds = {
            "critical_speed_factor": critical,
            "speed_sweep": [
                {"factor": f, **r.as_dict(), "success": r.success} for f, r in rollouts
            ],
        }
    else:
        played["robust"] = simulate_move(
            world, q_grasp, robust.trajectory, object_inertias=inertias
        )
    d_n, d_r = nominal.retimed.duration, robust.duration
    return {
        "index": index,
        "start": pose_list(X_WO_start),
        "goal": pose_list(X_WO_goal),
        "true_object": true.as_dict(),
        "duration_nominal_s": d_n,
        "duration_robust_s": d_r,
        "duration_lower_bound_s": bound.duration,
        "price": d_r / d_n,
        "tightness": d_r / bound.duration,
        "sound_excess": excess,
        "sample_objects": len(held_sample),
        "success_nominal": played["nominal"].success,
        "success_robust": played["robust"].success,
        "slip_nominal": played["nominal"].as_dict(),
        "slip_robust": played["robust"].as_dict(),
        "retime_nominal_s": nominal.times.retime_s,
        "retime_robust_s": robust_s,
        "robust_pairs": robust.grasp_rows,
        "robust_vertex_objects": robust.grasp_objects,
        "guarantee_robust": robust_grasp.guarantee(),
        **speeds,
    }


def true_object_world(
    trial: Scenario,
    q_grasp: np.ndarray,
    obj: ObjectConfig,
    uncertainty: ObjectUncertainty,
    rng: np.random.Generator,
) -> tuple[Scenario, dict[str, SpatialInertia], ObjectInertia]:
    """The physics a robust plan is played in: a hard TRUE object, the worst cup.

    The true object is drawn from the set's hardest corners
    (:func:`~rt_drake.uncertainty.object_samples.hardest_corner`, one draw of ``rng``);
    the cup is the worst of its range (``friction_min``,
    ``suction_force_min``) under ``cup_physics: rim``; a bellows cup is its
    catalogue's, whatever the planner's cup.

    Returns:
        The rollout scenario (arm at ``q_grasp``), the object inertias to
        pass to :func:`._rollout.simulate_move`, and the true object.
    """
    true = hardest_corner(ObjectInertia.of_model(obj), uncertainty, rng)
    world = dataclasses.replace(
        rollout_scenario(trial, q_grasp), cup=trial.cup.worst_case()
    )
    return world, {obj.name: true.spatial_inertia()}, true


def sound_excess(scenario: Scenario, trajectory: TimedPath, objects: list) -> float:
    """Largest ``max_k F_k w / g_k - 1`` of the objects along ``trajectory``.

    At 1 kHz, the wrench by Drake's body accelerations and Newton-Euler (not
    the retimer's route), the wrench set every cup of the scenario's range
    exerts.
    """
    plant = make_arm_plant(scenario)
    times = np.append(np.arange(0.0, trajectory.duration, 1e-3), trajectory.duration)
    q, v, vdot = trajectory.sample(times + trajectory.start_time(), order=2)
    wrenches = reference_object_wrenches(plant, objects, CupFrame.of(plant), q, v, vdot)
    F, g = worst_cup_polytope(scenario.cup)
    ratio, _, _ = wrench_ratios(
        wrenches.reshape(-1, 6), normalised_rows(F, g), g, np.inf
    )
    return float(ratio.max()) - 1.0


def _speed_summary(trials: list[dict[str, Any]]) -> dict[str, Any]:
    """The robust plans' critical speed factors: median, min, each."""
    critical = [t["critical_speed_factor"] for t in trials]
    finite = [c for c in critical if c is not None]
    every = len(finite) == len(critical)
    return {
        "critical_speed_factor_median": float(np.median(finite)) if every else None,
        "critical_speed_factor_min": min(finite) if finite else None,
        "never_slipped_up_to": None if every else SPEED_FACTORS[-1],
        "critical_speed_factors": critical,
    }


def _uncertainty(obj: ObjectConfig) -> ObjectUncertainty:
    if obj.uncertainty is None or obj.uncertainty.is_zero():
        raise ScenarioError(
            f"object '{obj.name}' has no uncertainty set: give it one in the "
            "scenario (objects[].uncertainty) to compare nominal and robust plans"
        )
    return obj.uncertainty


def _trial_job(args: tuple) -> dict[str, Any]:
    """One trial in a worker: scenarios do not pickle, so it is loaded again."""
    path, object_name, index, X_start, X_goal, seed, cup, jerk, sweep = args
    return robust_trial(
        load_scenario(path).with_cup_physics(cup),
        object_name,
        index,
        RigidTransform(X_start),
        RigidTransform(X_goal),
        seed,
        jerk,
        sweep,
    )


def run_robust_transport_experiment(
    scenario_path: str | Path,
    n: int = 20,
    seed: int = 0,
    object_name: str | None = None,
    workers: int = 1,
    progress: Callable[[int, int], None] | None = None,
    cup_physics: str | None = None,
    jerk_limits: bool = False,
    sweep: bool = False,
) -> dict[str, Any]:
    """Run n trials (in ``workers`` processes); return results and a summary.

    ``progress(done, n)`` is called as each trial finishes (and with 0 first).
    ``cup_physics``: play the trials with this cup (``rim`` or ``bellows``;
    None: the scenario's ``cup_physics.kind``); the results name it. With
    ``jerk_limits``, every retime keeps the scenario's ``robot.jerk_limits``.
    With ``sweep``, each robust plan is also played faster until it slips.

    The trials the retimer refused are listed under ``not_retimed`` (not
    played), and counted in the summary; the others under ``trials``.

    Raises:
        InputError: fewer than one trial or one worker.
        ScenarioError: no ``random_transport`` section, no such object, or
            an object without an uncertainty set.
    """
    scenario, name = transport_inputs(scenario_path, n, workers, object_name)
    scenario = scenario.with_cup_physics(cup_physics)
    _uncertainty(scenario.object(name))
    pairs = sample_transports(scenario, n, seed)
    kind = scenario.cup_physics.kind
    jobs = [
        (str(scenario_path), name, i, X_s.GetAsMatrix4(), X_g.GetAsMatrix4(), seed)
        + (kind, jerk_limits, sweep)
        for i, (X_s, X_g) in enumerate(pairs)
    ]
    done = run_trials(_trial_job, jobs, workers, progress)
    trials = [t for t in done if "not_retimed" not in t]
    not_retimed = [t for t in done if "not_retimed" in t]
    obj = scenario.object(name)
    assert obj.uncertainty is not None
    return {
        "object": name,
        "seed": seed,
        "n": n,
        "cup_physics": kind,
        "jerk_limits": jerk_limits,
        "sweep": sweep,
        "grasp_ramp_s": scenario.planning.grasp_ramp_s,
        "grasp_margin": scenario.planning.grasp_margin,
        "uncertainty": dataclasses.asdict(obj.uncertainty),
        "cup": {
            "friction_min": scenario.cup.friction_min,
            "suction_force_min": scenario.cup.suction_force_min,
        },
        "trials": trials,
        "not_retimed": not_retimed,
        "summary": summarize_robust(trials, len(not_retimed)),
    }


def summarize_robust(
    trials: list[dict[str, Any]], not_retimed: int = 0
) -> dict[str, Any]:
    """Successes of both plans, durations, price and tightness statistics.

    ``trials``: the played ones; ``not_retimed``: how many more the retimer
    refused (``n`` counts the played trials, ``n_sampled`` both). With no
    trial played, only the counts. The robust plans' critical speed factors
    when the trials carry them (``sweep``): their median and minimum (None
    if one never slipped up to the last speed factor, named then).
    """
    counts = {
        "n": len(trials),
        "n_sampled": len(trials) + not_retimed,
        "not_retimed": not_retimed,
    }
    if not trials:
        return counts

    def stats(key: str) -> dict[str, float]:
        values = np.array([t[key] for t in trials], dtype=float)
        return {
            "min": float(values.min()),
            "median": float(np.median(values)),
            "mean": float(values.mean()),
            "max": float(values.max()),
        }

    return {
        **counts,
        **(_speed_summary(trials) if "critical_speed_factor" in trials[0] else {}),
        "success_nominal": sum(t["success_nominal"] for t in trials),
        "success_robust": sum(t["success_robust"] for t in trials),
        "duration_nominal_s": stats("duration_nominal_s"),
        "duration_robust_s": stats("duration_robust_s"),
        "price": stats("price"),
        "tightness": stats("tightness"),
        "sound_excess_max": max(t["sound_excess"] for t in trials),
        "retime_nominal_s": stats("retime_nominal_s"),
        "retime_robust_s": stats("retime_robust_s"),
        "slip_robust_max_mm": max(
            t["slip_robust"]["max_translation_mm"] for t in trials
        ),
        "slip_robust_max_deg": max(
            t["slip_robust"]["max_rotation_deg"] for t in trials
        ),
    }


__all__ = [
    "SAMPLE",
    "robust_trial",
    "run_robust_transport_experiment",
    "true_object_world",
]
