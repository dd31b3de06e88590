"""Planning benchmark: median wall time of APPROACH, REACH and MOVE plans.

Twenty random transports of ``random_transport.yaml`` (seeded): the object
is put at a sampled start pose, then APPROACH from home, REACH, and MOVE to a
sampled goal pose are planned; a phase's time is the sum of its stages
(scene update, IK, RRT-Connect, shortcut, spline fit, dense check). The four
objects of ``stack_four_objects.yaml`` follow, in stacking order.

Each query is planned ``--repeats`` times (the planner is deterministic, so
the paths are identical) and its fastest time kept: on a shared machine that
filters out time stolen by other processes. Reported: median (min, max) over
queries, and the MOVE stages' medians. Last, how long a failing query takes
to raise its typed error against the planner's budget (an unreachable object).

Run: ``python benchmarks/bench_planning.py [--queries N] [--seed S] [--repeats R]``.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

try:
    import rt_drake  # noqa: F401
except ImportError:  # a source checkout without `pip install -e .`
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from pydrake.math import RigidTransform  # noqa: E402

from rt_drake.model.resources import scenarios_dir  # noqa: E402
from rt_drake.model.scenario import load_scenario  # noqa: E402
from rt_drake.planning import (  # noqa: E402
    CyclePlanner,
    UnreachablePoseError,
    sample_transports,
)

PHASES = ("APPROACH", "REACH", "MOVE")
STAGES = ("scene", "ik", "rrt", "shortcut", "spline", "check")


def plan_cycle(planner, name, q_start, X_goal=None) -> list:
    """APPROACH, REACH, MOVE plans of one object."""
    approach = planner.plan_approach(q_start, name)
    reach = planner.plan_reach(approach.q_goal, name)
    return [approach, reach, planner.plan_move(reach.q_goal, name, X_goal, reach)]


def fastest(plans_per_repeat: list[list]) -> list:
    """Per phase, the timing of the fastest repeat."""
    return [
        min((plans[k].timing for plans in plans_per_repeat), key=lambda t: t.total_s)
        for k in range(len(PHASES))
    ]


def bench_transport(queries: int, seed: int, repeats: int) -> list[list]:
    scenario = load_scenario(scenarios_dir() / "random_transport.yaml")
    name = scenario.random_transport.object
    planner = CyclePlanner(scenario, seed=seed)
    timings = []
    for X_start, X_goal in sample_transports(scenario, queries, seed):
        planner.set_object_pose(name, X_start)
        q_home = planner.q_home
        runs = [plan_cycle(planner, name, q_home, X_goal) for _ in range(repeats)]
        timings.append(fastest(runs))
    return timings


def bench_stack(seed: int, repeats: int) -> list[list]:
    scenario = load_scenario(scenarios_dir() / "stack_four_objects.yaml")
    planner = CyclePlanner(scenario, seed=seed)
    timings = []
    q = planner.q_home
    for obj in scenario.objects:
        runs = [plan_cycle(planner, obj.name, q) for _ in range(repeats)]
        timings.append(fastest(runs))
        planner.set_object_pose(obj.name, obj.goal.GetDeterministicValue())
        q = runs[0][-1].q_goal
    return timings


def report(title: str, timings: list[list]) -> None:
    print(title)
    for k, phase in enumerate(PHASES):
        ms = 1e3 * np.array([t[k].total_s for t in timings])
        print(
            f"  {phase:<9} median {np.median(ms):6.1f} ms  "
            f"(min {ms.min():6.1f}, max {ms.max():6.1f}, n = {len(ms)})"
        )
    medians = [
        1e3 * np.median([getattr(t[-1], f"{stage}_s") for t in timings])
        for stage in STAGES
    ]
    stages = ", ".join(f"{s} {m:.1f}" for s, m in zip(STAGES, medians, strict=True))
    print(f"  MOVE stage medians (ms): {stages}")


def bench_failure(repeats: int) -> None:
    """Wall time to raise UnreachablePoseError for an object out of reach."""
    scenario = load_scenario(scenarios_dir() / "random_transport.yaml")
    planner = CyclePlanner(scenario, seed=0)
    planner.set_object_pose("notebook", RigidTransform([1.5, 0.0, 0.0]))
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        try:
            planner.plan_approach(planner.q_home, "notebook")
        except UnreachablePoseError:
            times.append(time.perf_counter() - start)
    print(
        f"unreachable object: UnreachablePoseError after {1e3 * min(times):.0f} ms "
        f"(fastest of {len(times)}; budget {1e3 * planner.budget_s:.0f} ms)"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--queries", type=int, default=20)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    start = time.perf_counter()
    report(
        f"random_transport.yaml, {args.queries} queries (fastest of {args.repeats})",
        bench_transport(args.queries, args.seed, args.repeats),
    )
    report(
        f"stack_four_objects.yaml, 4 objects (fastest of {args.repeats})",
        bench_stack(args.seed, args.repeats),
    )
    bench_failure(args.repeats)
    print(f"(benchmark wall time {time.perf_counter() - start:.1f} s)")


if __name__ == "__main__":
    main()
