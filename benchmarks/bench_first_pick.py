"""The first pick's planning, as the cycle's critical path sees it.

    python benchmarks/bench_first_pick.py [--scenario FILE] [--repeats 5]
        [--no-jerk-limits]
    python benchmarks/bench_first_pick.py --compare OLD_TREE NEW_TREE [--rounds 5]
    python benchmarks/bench_first_pick.py --grids 100 60 30 20 [--repeats 3]

One process per measurement: ``OnlineMotions`` is built as ``rt-drake run``
builds it (the scenario's jerk limits unless --no-jerk-limits; the retimer
and optimiser kernels warmed up, as the cycle does before its clock
starts), then the first object's pick from home is planned and retimed,
timed with ``time.process_time`` (CPU) and ``time.perf_counter`` (wall):
that call is what the cycle's first APPROACH waits for. The same pick
repeated in the same process (``--repeats``) gives the warm cost, and its
stages apart (``warm_*_cpu_s``: the planner's ``plan_pick``, the retime,
the time at which the retimed pick passes the approach pose). Prints one
JSON line.

``--grids`` retimes the first pick's path (planned once) on uniform grids
of those sizes instead (the retimer adds the knots and refines each, so
every grid keeps the limits between its points): the least CPU over
``--repeats`` and the pick's duration, one JSON line per size. A cheaper
first retime pays for itself only if it costs less CPU than it adds motion.

``--compare`` runs this script alternately with ``PYTHONPATH`` set to two
source trees (e.g. an export of the previous commit and the worktree),
``--rounds`` processes each, and prints both side by side (median and
minimum over the processes: the minimum is the least disturbed by other
load).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time


def measure(scenario: str, repeats: int, jerk_limits: bool = True) -> dict:
    """CPU and wall seconds of the first pick, and of ``repeats`` more."""
    from rt_drake.model.scenario import load_scenario
    from rt_drake.simulation.online_motions import OnlineMotions, time_at

    sc = load_scenario(scenario)
    motions = OnlineMotions(sc, jerk_limits=jerk_limits)
    obj = sc.objects[0]
    cpu, wall = time.process_time(), time.perf_counter()
    first = motions.pick(motions.q_home, obj)
    first_cpu, first_wall = time.process_time() - cpu, time.perf_counter() - wall
    warm_cpu, warm_wall = [], []
    for _ in range(repeats):
        cpu, wall = time.process_time(), time.perf_counter()
        motions.pick(motions.q_home, obj)
        warm_cpu.append(time.process_time() - cpu)
        warm_wall.append(time.perf_counter() - wall)
    stages: dict[str, list[float]] = {"plan": [], "retime": [], "split": []}
    for _ in range(repeats):
        cpu = time.process_time()
        planned = motions.planner.plan_pick(motions.q_home, obj.name, False)
        stages["plan"].append(time.process_time() - cpu)
        cpu = time.process_time()
        result = motions.retime_free(planned.path.path)
        stages["retime"].append(time.process_time() - cpu)
        cpu = time.process_time()
        time_at(result, planned.s_approach)
        stages["split"].append(time.process_time() - cpu)
    return {
        "first_cpu_s": first_cpu,
        "first_wall_s": first_wall,
        "first_charged_s": first.times.total_s,
        "warm_cpu_s": statistics.median(warm_cpu) if warm_cpu else None,
        "warm_wall_s": statistics.median(warm_wall) if warm_wall else None,
        **{
            f"warm_{k}_cpu_s": statistics.median(v) if v else None
            for k, v in stages.items()
        },
    }


def grids(scenario: str, sizes: list[int], repeats: int) -> None:
    """Print the first pick's retime CPU (s) and duration (s) per grid size."""
    from rt_drake.model.plant import make_arm_plant
    from rt_drake.model.scenario import load_scenario
    from rt_drake.retiming import JointLimits, retime
    from rt_drake.simulation.online_motions import OnlineMotions

    sc = load_scenario(scenario)
    motions = OnlineMotions(sc, jerk_limits=True)
    planned = motions.planner.plan_pick(motions.q_home, sc.objects[0].name, False)
    plant = make_arm_plant(sc)
    limits = JointLimits.from_plant(plant, sc.robot, jerk=True)
    for size in sizes:
        cpu = []
        for _ in range(max(repeats, 1)):
            start = time.process_time()
            result = retime(plant, planned.path.path, limits, None, gridpoints=size)
            cpu.append(time.process_time() - start)
        print(
            json.dumps(
                {
                    "gridpoints": size,
                    "grid_after_refinement": len(result.gridpoints),
                    "retime_cpu_s": min(cpu),
                    "duration_s": result.duration,
                }
            )
        )


def compare(
    trees: list[str], rounds: int, scenario: str, repeats: int, flags: list[str]
) -> None:
    """Alternate processes on each tree; print medians side by side."""
    results: dict[str, list[dict]] = {tree: [] for tree in trees}
    for _ in range(rounds):
        for tree in trees:
            env = dict(os.environ, PYTHONPATH=tree, OPENBLAS_NUM_THREADS="1")
            out = subprocess.run(
                [sys.executable, __file__, "--scenario", scenario]
                + ["--repeats", str(repeats), *flags],
                env=env,
                capture_output=True,
                text=True,
                check=True,
            )
            results[tree].append(json.loads(out.stdout.strip().splitlines()[-1]))
    keys = list(results[trees[0]][0])
    names = [os.path.basename(t.rstrip("/")) for t in trees]
    print(
        f"{str(rounds) + ' processes each':<28}"
        + "".join(f"{n + ' median':>16}{n + ' min':>14}" for n in names)
    )
    for key in keys:
        row = []
        for t in trees:
            values = [r[key] for r in results[t]]
            row += [statistics.median(values), min(values)]
        print(f"{key:<28}" + "".join(f"{v:>16.4f}" for v in row))


def main() -> None:
    """Parse the arguments and measure or compare."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenario", default="scenarios/stack_four_objects.yaml")
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--compare", nargs=2, metavar=("OLD", "NEW"))
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--no-jerk-limits", action="store_true")
    parser.add_argument("--grids", nargs="+", type=int, metavar="N")
    args = parser.parse_args()
    if args.grids:
        grids(args.scenario, args.grids, args.repeats)
    elif args.compare:
        flags = ["--no-jerk-limits"] if args.no_jerk_limits else []
        compare(args.compare, args.rounds, args.scenario, args.repeats, flags)
    else:
        result = measure(args.scenario, args.repeats, not args.no_jerk_limits)
        print(json.dumps(result))


if __name__ == "__main__":
    main()
