"""The optimised MOVE of a Table I transport, next to the spline MOVE (issue 13).

:func:`optimized_trial` takes the spline MOVE a transport trial planned and
played, shapes it for speed (:class:`rt_drake.shaping.MoveOptimizer`,
the scenario's ``planning`` tilt and budget), and plays the optimised MOVE
in the same physics with its own speed sweep. Per trial it returns the keys
``duration_optimized_s`` (s, under the exact grasp constraint),
``success_optimized``, ``optimize_wall_s`` and
``critical_speed_factor_optimized``, and what the report needs: the spline
path's duration on the optimiser's grid (``duration_spline_same_grid_s``)
and the cup's position, tilt and grasp margin over time along both MOVEs
(``cup_profiles``). :func:`optimize_spline` is its optimisation alone (the
campaign's ``optimized`` variant plays its result at speed 1).

The optimiser's budget is counted in paths scored (the scenario's
``planning.max_evaluations``), so the trials, two at a time on a shared
machine, give the same paths whatever its load; ``optimize_wall_s`` is the
wall time the optimisation took.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from pydrake.geometry import StartMeshcat
from pydrake.trajectories import Trajectory

from rt_drake.atomic_file import write_text_atomically
from rt_drake.experiments._rollout import (
    critical_speed,
    simulate_move,
)
from rt_drake.model.plant import make_arm_plant
from rt_drake.model.scenario import Scenario
from rt_drake.planning import CyclePlanner, PlannedPath
from rt_drake.retiming import GraspConstraint, JointLimits, Margin, RetimeResult
from rt_drake.shaping import (
    MoveOptimizer,
    MoveOptimizerOptions,
    OptimizedMove,
    warm_up,
)
from rt_drake.shaping.cup_chain import CupChain
from rt_drake.simulation import OnlineMotions

#: Samples in time of the cup profiles.
PROFILE_SAMPLES = 200
#: File name of the Meshcat replay of one optimised transport.
REPLAY_FILE = "optimized_replay.html"


def optimized_trial(
    scenario: Scenario,
    planner: CyclePlanner,
    spline: PlannedPath,
    spline_retimed: RetimeResult,
    grasp: GraspConstraint,
    rollout_world: Scenario,
    replay_path: Path | None = None,
    motions: OnlineMotions | None = None,
) -> dict[str, Any]:
    """Optimise the MOVE ``spline``, play it, and return the per-trial keys.

    The optimiser compares paths under the acceleration limits; when
    ``motions`` (the trial's, which retimed ``spline``) retimes a
    grasp-constrained motion under jerk limits (``robot.jerk_limits``, or
    the grasp's ``planning.grasp_ramp_s``), the kept path is retimed once
    more under them, as the cycle does
    (:meth:`~rt_drake.simulation.OnlineMotions.retime_on_profile`), so that
    both MOVEs are played under the same limits.

    Args:
        scenario: The trial's scenario (its ``planning`` gives tilt and budget).
        planner: The planner that planned ``spline`` (its scene as then).
        spline: The trial's spline MOVE.
        spline_retimed: Its retime (Table I's, with the constraint).
        grasp: The grasp constraint it was retimed under.
        rollout_world: The rollout scenario (:func:`._rollout.rollout_scenario`).
        replay_path: Write a Meshcat replay (HTML) of the optimised MOVE here.
        motions: The trial's motions (None: the optimiser's own retime).
    """
    optimizer, result = optimize_spline(scenario, planner, spline, grasp)
    retimed = result.retimed
    if motions is not None and motions.jerk_limited:
        retimed = motions.retime_on_profile(result.path, grasp, result.retimed)
    q_grasp = spline.q_start
    trajectory = retimed.trajectory
    critical, sweep = critical_speed(rollout_world, q_grasp, trajectory)
    if replay_path is not None:
        meshcat = StartMeshcat()
        simulate_move(rollout_world, q_grasp, trajectory, meshcat=meshcat)
        write_text_atomically(replay_path, meshcat.StaticHtml())
    chain = optimizer.chain
    return {
        "duration_optimized_s": retimed.duration,
        "success_optimized": sweep[0][1].success,
        "optimize_wall_s": result.wall_s,
        "critical_speed_factor_optimized": critical,
        "optimize_cpu_s": result.cpu_s,
        "duration_spline_same_grid_s": result.spline_duration,
        "improved": result.improved,
        "evaluations": result.evaluations,
        "max_tilt_optimized_deg": result.max_tilt_deg,
        "rejected": list(result.rejected),
        "slip_optimized": sweep[0][1].as_dict(),
        "speed_sweep_optimized": [
            {"factor": f, **r.as_dict(), "success": r.success} for f, r in sweep
        ],
        "waypoints_optimized": result.path.waypoints.tolist(),
        "cup_profiles": {
            "spline": cup_profile(chain, spline_retimed),
            "optimized": cup_profile(chain, retimed),
        },
    }


def optimize_spline(
    scenario: Scenario,
    planner: CyclePlanner,
    spline: PlannedPath,
    grasp: GraspConstraint,
) -> tuple[MoveOptimizer, OptimizedMove]:
    """Shape the spline MOVE ``spline`` for speed, retimed under ``grasp``.

    The optimiser has the scenario's ``planning`` tilt and evaluation budget
    (module docstring).

    Returns:
        The optimiser (its ``chain`` gives the cup kinematics) and its result:
        the returned path, retimed under the exact grasp constraint on the
        adaptive grid, never slower than the spline path on that grid.
    """
    plant = make_arm_plant(scenario)
    limits = JointLimits.from_plant(plant, scenario.robot)
    options = MoveOptimizerOptions.from_config(scenario.planning)
    warm_up()
    optimizer = MoveOptimizer(plant, limits, options)
    return optimizer, optimizer.optimize(planner, spline, grasp)


def cup_profile(chain: CupChain, retimed: RetimeResult) -> dict[str, list[float]]:
    """Cup position (m, W), tilt (deg) and grasp margin over time, for plots.

    Position and tilt at :data:`PROFILE_SAMPLES` times; the grasp margin
    ``min_k (g_k - F_k w) / g_k`` at the grid points (the retimer's).
    """
    trajectory: Trajectory = retimed.trajectory
    t = np.linspace(trajectory.start_time(), trajectory.end_time(), PROFILE_SAMPLES)
    q = np.array([trajectory.value(ti).ravel() for ti in t])
    _, p = chain.cup_pose(q)
    return {
        "t": (t - t[0]).tolist(),
        "x": p[:, 0].tolist(),
        "y": p[:, 1].tolist(),
        "z": p[:, 2].tolist(),
        "tilt_deg": np.degrees(chain.tilt(q)).tolist(),
        "t_grid": (retimed.trajectory.times - t[0]).tolist(),
        "grasp_margin": retimed.margins[Margin.GRASP].tolist(),
    }


def summarize_optimized(trials: list[dict[str, Any]]) -> dict[str, Any]:
    """The optimised MOVEs over the trials: successes, durations, ratios, speeds.

    ``ratio_median``: median of ``duration_optimized_s`` over the Table I
    spline duration (``duration_constrained_s``, 100 uniform points);
    ``ratio_same_grid_median``: over the spline path on the optimiser's grid
    (``duration_spline_same_grid_s``), the path's own gain.
    """
    optimized = np.array([t["duration_optimized_s"] for t in trials])
    spline = np.array([t["duration_constrained_s"] for t in trials])
    same_grid = np.array([t["duration_spline_same_grid_s"] for t in trials])
    critical = [t["critical_speed_factor_optimized"] for t in trials]
    finite = [c for c in critical if c is not None]
    return {
        "success_optimized": sum(t["success_optimized"] for t in trials),
        "improved": sum(t["improved"] for t in trials),
        "duration_optimized_s": _stats(optimized),
        "ratio_median": float(np.median(optimized / spline)),
        "ratio_same_grid_median": float(np.median(optimized / same_grid)),
        "optimize_wall_s_median": float(
            np.median([t["optimize_wall_s"] for t in trials])
        ),
        "optimize_cpu_s_median": float(
            np.median([t["optimize_cpu_s"] for t in trials])
        ),
        "critical_speed_factor_optimized_min": min(finite) if finite else None,
        "critical_speed_factors_optimized": critical,
    }


def _stats(values: np.ndarray) -> dict[str, float]:
    return {
        "min": float(values.min()),
        "median": float(np.median(values)),
        "mean": float(values.mean()),
        "max": float(values.max()),
    }


__all__ = [
    "PROFILE_SAMPLES",
    "REPLAY_FILE",
    "cup_profile",
    "optimize_spline",
    "optimized_trial",
    "summarize_optimized",
]
