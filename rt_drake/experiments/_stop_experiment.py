"""Protective stops in physics: Table I's MOVEs stopped at random instants.

For each of n random transports (Table I's: start and goal sampled from the
scenario's ``random_transport``, the MOVE planned and retimed under the
grasp constraint as :mod:`._transport_experiment` does), a light curtain
trips at a random instant t, uniform over the MOVE's duration (seeded). The
MOVE up to t, then its stop, is played in the cycle's physics
(:func:`._rollout.simulate_move`) two ways:

- grasp-aware: :func:`rt_drake.retiming.protective_stop`, which keeps the
  grasp set and every limit;
- joint brake: :func:`rt_drake.retiming.joint_brake_stop`, the joints
  braking at their acceleration limits along the path, grasp ignored (what
  robots do today).

With the scenario's ``robot.jerk_limits`` (the MOVE then jerk-limited),
both stops keep the jerk limits too, from the MOVE's own acceleration at t
(a category-2 stop: the joint brake is then jerk-limited braking along the
path).

A stop succeeds by the transport experiment's hold criteria
(:class:`._rollout.Rollout`: slip under 5 mm and 3 deg). Each trial also
records the smallest grasp margin of each stop at 1 kHz
(:func:`rt_drake.retiming.check_trajectory`; negative: the wrench left the
grasp set by that fraction of g).
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
from pydrake.math import RigidTransform
from pydrake.multibody.plant import MultibodyPlant

from rt_drake.experiments._rollout import rollout_scenario, simulate_move
from rt_drake.experiments._transport_experiment import (
    played_move,
    transport_inputs,
    transport_scenario,
)
from rt_drake.experiments._trial_pool import run_trials
from rt_drake.model.plant import make_arm_plant
from rt_drake.model.scenario import Scenario, load_scenario
from rt_drake.planning import sample_transports
from rt_drake.retiming import (
    GraspConstraint,
    JointLimits,
    Margin,
    StopResult,
    check_trajectory,
    joint_brake_stop,
    protective_stop,
)
from rt_drake.simulation import OnlineMotions

#: What ``experiment stop`` writes into its directory.
STOP_FILES = ("results.json",)


def stop_trial(
    scenario: Scenario,
    object_name: str,
    index: int,
    X_WO_start: RigidTransform,
    X_WO_goal: RigidTransform,
    seed: int,
    fraction: float,
    planning_budget_s: float | None = None,
    jerk_limits: bool = False,
) -> dict[str, Any]:
    """Plan and retime one transport's MOVE, stop it at ``fraction`` of it, both ways.

    Args:
        scenario: The cell, with a ``random_transport`` section.
        object_name: The carried object.
        index: The transport's index (its planner seed is ``seed + index``).
        X_WO_start: The object's start pose (body frame O in the world W).
        X_WO_goal: Its goal pose.
        seed: The experiment's seed.
        fraction: When the stop begins, as a fraction of the MOVE's duration.
        planning_budget_s: The planner's time per call, s (None: its default).
        jerk_limits: Retime the MOVE and make both stops under the
            scenario's ``robot.jerk_limits`` too (when it gives them).
    """
    planner_scenario = transport_scenario(scenario, object_name, X_WO_start, X_WO_goal)
    motions = OnlineMotions(
        planner_scenario,
        grasp_constraint=True,
        seed=seed + index,
        optimize=False,
        jerk_limits=jerk_limits,
    )
    if planning_budget_s is not None:
        motions.planner.budget_s = planning_budget_s
    obj = planner_scenario.objects[0]
    move = played_move(scenario, motions, obj, X_WO_start)
    assert move.planned is not None and move.retimed is not None
    assert move.grasp is not None
    q_grasp = move.planned.q_start
    path, result, grasp = move.planned.path, move.retimed, move.grasp
    plant = make_arm_plant(planner_scenario)
    limits = JointLimits.from_plant(plant, planner_scenario.robot, jerk=jerk_limits)
    t = result.trajectory.start_time() + fraction * result.duration
    held = protective_stop(plant, path, limits, result, t, grasp)
    brake = joint_brake_stop(plant, path, limits, result, t)
    world = rollout_scenario(planner_scenario, q_grasp)
    held_rollout = simulate_move(world, q_grasp, held.trajectory)
    brake_rollout = simulate_move(world, q_grasp, brake.trajectory)
    return {
        "index": index,
        "move_duration_s": result.duration,
        "stop_at_s": t,
        "stop_fraction": fraction,
        "s_at_stop": held.s_start,
        "sd_at_stop": held.sd_start,
        "stop_time_s": held.duration,
        "joint_stop_time_s": brake.duration,
        "s_stop": held.s_stop,
        "joint_s_stop": brake.s_stop,
        "success_grasp_stop": held_rollout.success,
        "success_joint_stop": brake_rollout.success,
        "slip_grasp_stop": held_rollout.as_dict(),
        "slip_joint_stop": brake_rollout.as_dict(),
        "jerk_limited": limits.jerk is not None,
        **_margins(plant, limits, grasp, held, "grasp_stop"),
        **_margins(plant, limits, grasp, brake, "joint_stop"),
    }


def _margins(
    plant: MultibodyPlant,
    limits: JointLimits,
    grasp: GraspConstraint,
    stop: StopResult,
    name: str,
) -> dict[str, float | None]:
    """Smallest grasp margin of the stop alone (from t on), at 1 kHz.

    With jerk limits, also the smallest jerk margin of the whole motion (the
    MOVE up to t, then the stop: the joint acceleration continuous at t).
    """
    check = check_trajectory(plant, stop.stop, limits, grasp)
    margins: dict[str, float | None] = {
        f"grasp_margin_{name}": float(check.margins[Margin.GRASP].value)
    }
    if limits.jerk is not None:
        whole = check_trajectory(plant, stop.trajectory, limits)
        margins[f"jerk_margin_{name}"] = float(whole.margins[Margin.JERK].value)
    return margins


def _trial_job(args: tuple) -> dict[str, Any]:
    """One trial in a worker: scenarios do not pickle, so it is loaded again."""
    path, object_name, index, X_start, X_goal, seed, fraction, jerk = args
    return stop_trial(
        load_scenario(path),
        object_name,
        index,
        RigidTransform(X_start),
        RigidTransform(X_goal),
        seed,
        fraction,
        jerk_limits=jerk,
    )


def run_stop_experiment(
    scenario_path: str | Path,
    n: int = 20,
    seed: int = 0,
    object_name: str | None = None,
    workers: int = 1,
    progress: Callable[[int, int], None] | None = None,
    jerk_limits: bool = False,
) -> dict[str, Any]:
    """Run n stop trials (in ``workers`` processes); return results and a summary.

    The transports are Table I's for ``seed`` (:func:`sample_transports`);
    the stop instants are ``np.random.default_rng(seed)`` uniform fractions
    of each MOVE. ``progress(done, n)`` is called as each trial finishes.
    With ``jerk_limits``, the MOVEs and both stops keep the scenario's
    ``robot.jerk_limits`` (:func:`stop_trial`).

    Raises:
        InputError: fewer than one trial or one worker.
        ScenarioError: the scenario has no ``random_transport`` section or
            no such object.
    """
    scenario, name = transport_inputs(scenario_path, n, workers, object_name)
    pairs = sample_transports(scenario, n, seed)
    fractions = np.random.default_rng(seed).uniform(size=n)
    jobs = [
        (
            str(scenario_path),
            name,
            i,
            X_s.GetAsMatrix4(),
            X_g.GetAsMatrix4(),
            seed,
            float(fractions[i]),
            jerk_limits,
        )  # fmt: skip
        for i, (X_s, X_g) in enumerate(pairs)
    ]
    trials = run_trials(_trial_job, jobs, workers, progress)
    return {
        "object": name,
        "seed": seed,
        "n": n,
        "jerk_limits": jerk_limits,
        "trials": trials,
        "summary": summarize_stops(trials),
    }


def summarize_stops(trials: list[dict[str, Any]]) -> dict[str, Any]:
    """Successes of both stops; stop times, grasp (and jerk) margins' ranges."""
    keys = [
        "stop_time_s",
        "joint_stop_time_s",
        "grasp_margin_grasp_stop",
        "grasp_margin_joint_stop",
    ]
    if trials and "jerk_margin_grasp_stop" in trials[0]:
        keys += ["jerk_margin_grasp_stop", "jerk_margin_joint_stop"]
    return {
        "n": len(trials),
        "success_grasp_stop": sum(t["success_grasp_stop"] for t in trials),
        "success_joint_stop": sum(t["success_joint_stop"] for t in trials),
        **{key: _stats([t[key] for t in trials]) for key in keys},
    }


def stop_table(results: dict[str, Any]) -> str:
    """A short text table: one line per trial, then the summary."""
    lines = [
        " #   t(s)   frac  stop(s) joint(s)  held  joint  slip mm (held/joint)",
    ]
    for t in results["trials"]:
        lines.append(
            f"{t['index']:2d} {t['stop_at_s']:6.3f} {t['stop_fraction']:6.2f} "
            f"{t['stop_time_s']:7.3f} {t['joint_stop_time_s']:8.3f}  "
            f"{_yes(t['success_grasp_stop']):4s}  {_yes(t['success_joint_stop']):5s}  "
            f"{t['slip_grasp_stop']['max_translation_mm']:.2f} / "
            f"{t['slip_joint_stop']['max_translation_mm']:.2f}"
        )
    s = results["summary"]
    if results.get("jerk_limits"):
        lines.append("jerk-limited MOVEs and stops (the scenario's robot.jerk_limits)")
    lines.append(
        f"grasp-aware stops hold {s['success_grasp_stop']}/{s['n']}, joint-brake "
        f"stops {s['success_joint_stop']}/{s['n']}; stop time median "
        f"{s['stop_time_s']['median']:.3f} s (range "
        f"{s['stop_time_s']['min']:.3f}-{s['stop_time_s']['max']:.3f}) vs "
        f"{s['joint_stop_time_s']['median']:.3f} s "
        f"({s['joint_stop_time_s']['min']:.3f}-{s['joint_stop_time_s']['max']:.3f})"
    )
    return "\n".join(lines)


def _yes(value: bool) -> str:
    return "yes" if value else "NO"


def _stats(values: list[float]) -> dict[str, float]:
    array = np.asarray(values, dtype=float)
    return {
        "min": float(array.min()),
        "median": float(np.median(array)),
        "max": float(array.max()),
    }


__all__ = [
    "STOP_FILES",
    "run_stop_experiment",
    "stop_table",
    "stop_trial",
    "summarize_stops",
]
