"""The paper's Table I experiment, in simulation (Section V-A).

For each of n random transports of one object (start pose in the bin region,
goal on the destination region, both sampled from the scenario's
``random_transport``): plan the MOVE path, retime it with and without the
grasp constraint, and play each in the physics of the cycle diagram (the
station and sequencer of ``rt-drake run``; the arm starts at the grasp, the
valve is on for the attach wait, then the MOVE runs). Then play the
constrained MOVE faster and faster to find the speed at which the object
starts to slip (the paper saw slip at 120-140 %).

A rollout succeeds when, during the MOVE, the object moves less than
:data:`SLIP_TRANSLATION` and turns less than :data:`SLIP_ROTATION` relative
to the cup.
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Sequence
from concurrent.futures import ProcessPoolExecutor
from multiprocessing import get_context
from pathlib import Path
from typing import Any

import numpy as np
from pydrake.common.schema import Transform
from pydrake.math import RigidTransform
from pydrake.trajectories import PiecewisePolynomial, Trajectory

from rt_drake.cycle import run_cycle
from rt_drake.errors import ScenarioError
from rt_drake.motions import PlannedMotions, TimeScaled
from rt_drake.planning.transport import sample_transports
from rt_drake.retime import RetimeResult
from rt_drake.scenario import Scenario, Timing, load_scenario
from rt_drake.systems.sequencer import UPDATE_PERIOD, Motion

#: m and rad: a rollout slipped if the object moved more on the cup.
SLIP_TRANSLATION = 5e-3
SLIP_ROTATION = math.radians(3.0)
#: Speed factors of the sweep, in order; the first one that slips is critical.
SPEED_FACTORS = (1.0, 1.1, 1.2, 1.3, 1.4, 1.6, 1.8, 2.0, 2.5, 3.0)
#: s, the attach and detach waits of a rollout (shorter than a cycle's 1 s).
ROLLOUT_WAIT_S = 0.3


@dataclasses.dataclass(frozen=True)
class Rollout:
    """One simulated MOVE: its slip (m, rad) and whether it stayed put."""

    slip_translation: float
    slip_rotation: float

    @property
    def success(self) -> bool:
        """Slip under 5 mm and 3 deg."""
        return (
            self.slip_translation < SLIP_TRANSLATION
            and self.slip_rotation < SLIP_ROTATION
        )

    def as_dict(self) -> dict[str, float]:
        """``max_translation_mm``, ``max_rotation_deg``."""
        return {
            "max_translation_mm": 1e3 * self.slip_translation,
            "max_rotation_deg": math.degrees(self.slip_rotation),
        }


class _Replay:
    """A MotionSource that stands at the grasp, then plays a given MOVE."""

    def __init__(self, q_grasp: np.ndarray, move: Trajectory) -> None:
        self._hold = PiecewisePolynomial.ZeroOrderHold(
            [0.0, UPDATE_PERIOD], np.column_stack([q_grasp, q_grasp])
        )
        self._move = move

    def approach(self, q_start, obj) -> Motion:  # noqa: D102
        return Motion(self._hold, {})

    def reach(self, q_start, obj) -> Motion:  # noqa: D102
        return Motion(self._hold, {})

    def move(self, q_start, obj) -> Motion:  # noqa: D102
        return Motion(self._move, {})


def rollout_scenario(trial: Scenario, q_grasp: np.ndarray) -> Scenario:
    """The ``trial`` scenario (object at its sampled start), the arm at the grasp.

    The attach and detach waits are shortened to :data:`ROLLOUT_WAIT_S`.
    """
    return dataclasses.replace(
        trial,
        robot=dataclasses.replace(trial.robot, home=[float(q) for q in q_grasp]),
        timing=Timing(attach_s=ROLLOUT_WAIT_S, detach_s=ROLLOUT_WAIT_S),
    )


def simulate_move(
    scenario: Scenario, q_grasp: np.ndarray, move: Trajectory, speed: float = 1.0
) -> Rollout:
    """Play ``move`` (``speed`` times faster) in the cycle's physics; measure slip."""
    trajectory = move if speed == 1.0 else TimeScaled(move, speed)
    result = run_cycle(scenario, _Replay(q_grasp, trajectory), max_sim_time=30.0)
    (record,) = result.records
    return Rollout(record.max_slip_translation, record.max_slip_rotation)


def critical_speed(
    scenario: Scenario,
    q_grasp: np.ndarray,
    move: Trajectory,
    factors: Sequence[float] = SPEED_FACTORS,
) -> tuple[float | None, list[tuple[float, Rollout]]]:
    """The first factor of ``factors`` at which the object slips (None: never)."""
    sweep: list[tuple[float, Rollout]] = []
    for factor in factors:
        rollout = simulate_move(scenario, q_grasp, move, factor)
        sweep.append((factor, rollout))
        if not rollout.success:
            return factor, sweep
    return None, sweep


def transport_trial(
    scenario: Scenario, object_name: str, index: int, X_WO_start, X_WO_goal, seed: int
) -> dict[str, Any]:
    """Plan, retime (with and without the constraint) and simulate one transport."""
    obj = scenario.object(object_name)
    planner_scenario = dataclasses.replace(
        scenario,
        objects=[
            dataclasses.replace(
                obj, start=Transform(X_WO_start), goal=Transform(X_WO_goal)
            )
        ],
    )
    constrained = PlannedMotions(
        planner_scenario, grasp_constraint=True, seed=seed + index
    )
    planned_obj = planner_scenario.objects[0]
    approach = constrained.approach(constrained.q_home, planned_obj)
    q_grasp = constrained.reach(approach.q_end, planned_obj).q_end
    start = time.perf_counter()
    move_c = constrained.move(q_grasp, planned_obj)
    path = constrained.last_path
    result_c: RetimeResult = constrained.last_move
    result_u: RetimeResult = constrained.retime_path(path, grasp=None)
    plan_s = time.perf_counter() - start

    rollout_world = rollout_scenario(planner_scenario, q_grasp)
    unconstrained = simulate_move(rollout_world, q_grasp, result_u.trajectory)
    critical, sweep = critical_speed(rollout_world, q_grasp, move_c.trajectory)
    constrained_rollout = sweep[0][1]
    d_u, d_c = result_u.duration, result_c.duration
    return {
        "index": index,
        "start": _pose_list(X_WO_start),
        "goal": _pose_list(X_WO_goal),
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
        "profiles": _profiles(constrained, path, result_c, result_u),
    }


def _pose_list(X: RigidTransform) -> list[float]:
    """[x, y, z, yaw_deg]."""
    yaw = math.degrees(
        math.atan2(X.rotation().matrix()[1, 0], X.rotation().matrix()[0, 0])
    )
    return [*map(float, X.translation()), yaw]


def _profiles(
    motions: PlannedMotions,
    path,
    constrained: RetimeResult,
    unconstrained: RetimeResult,
) -> dict:
    """s'(s), its velocity-limit bound, and the grasp margin over time, for plots."""
    return {
        "s": constrained.gridpoints.tolist(),
        "sd_constrained": constrained.sd.tolist(),
        "sd_unconstrained": unconstrained.sd.tolist(),
        "sd_velocity_limit": motions.velocity_bound(
            path, constrained.gridpoints
        ).tolist(),
        "t_constrained": constrained.trajectory.times.tolist(),
        "t_unconstrained": unconstrained.trajectory.times.tolist(),
        "margin_constrained": motions.grasp_margin(path, constrained).tolist(),
        "margin_unconstrained": motions.grasp_margin(path, unconstrained).tolist(),
    }


def _trial_job(args: tuple) -> dict[str, Any]:
    """One trial in a worker: scenarios do not pickle, so it is loaded again."""
    path, object_name, index, X_start, X_goal, seed = args
    scenario = load_scenario(path)
    return transport_trial(
        scenario,
        object_name,
        index,
        RigidTransform(X_start),
        RigidTransform(X_goal),
        seed,
    )


def run_transport_experiment(
    scenario_path: str | Path,
    n: int = 20,
    seed: int = 0,
    object_name: str | None = None,
    workers: int = 1,
) -> dict[str, Any]:
    """Run n trials (in ``workers`` processes); return results and a summary."""
    scenario = load_scenario(scenario_path)
    if n < 1:
        raise ValueError(f"--n must be >= 1, got {n}")
    if workers < 1:
        raise ValueError(f"--workers must be >= 1, got {workers}")
    transport = scenario.random_transport
    if transport is None:
        raise ScenarioError(
            f"{scenario_path}: the scenario has no 'random_transport' section"
        )
    name = object_name or transport.object
    scenario.object(name)
    pairs = sample_transports(scenario, n, seed)
    jobs = [
        (str(scenario_path), name, i, X_s.GetAsMatrix4(), X_g.GetAsMatrix4(), seed)
        for i, (X_s, X_g) in enumerate(pairs)
    ]
    if workers == 1:
        trials = [_trial_job(job) for job in jobs]
    else:
        with ProcessPoolExecutor(workers, mp_context=get_context("spawn")) as pool:
            trials = list(pool.map(_trial_job, jobs))
    return {
        "object": name,
        "seed": seed,
        "n": n,
        "trials": trials,
        "summary": summarize(trials),
    }


def summarize(trials: list[dict[str, Any]]) -> dict[str, Any]:
    """Counts of successes, duration and extension statistics, critical speeds."""
    critical = [t["critical_speed_factor"] for t in trials]
    finite = [c for c in critical if c is not None]
    return {
        "n": len(trials),
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
    }


def _stats(values: list[float]) -> dict[str, float]:
    array = np.asarray(values, dtype=float)
    return {
        "min": float(array.min()),
        "median": float(np.median(array)),
        "mean": float(array.mean()),
        "max": float(array.max()),
    }
