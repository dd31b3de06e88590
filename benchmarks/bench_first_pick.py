"""The first pick's planning, as the cycle's critical path sees it.

    python benchmarks/bench_first_pick.py [--scenario FILE] [--repeats 5]
        [--no-jerk-limits]
    python benchmarks/bench_first_pick.py --compare OLD_TREE NEW_TREE [--rounds 5]
    python benchmarks/bench_first_pick.py --grids 100 60 30 20 [--repeats 3]

One process per measurement: ``OnlineMotions`` is built as ``rt-drake run``
builds it (the scenario's jerk limits unless --no-jerk-limits; the retimer
and optimiser kernels warmed up, as the cycle does before its clock
starts). Then, timed with ``time.process_time`` (CPU):

- ``critical_first_cpu_s``: what the cycle's first APPROACH waits for, on
  the first call in the process: the whole first pick (plan and retime)
  where it is one blended motion; the straight APPROACH (IK, the line's
  dense check, Ruckig) where the pick is staged
  (``OnlineMotions.straight_approach``; its REACH is planned behind it);
- ``critical_warm_cpu_s``: the same, repeated (``--repeats``, median);
- ``pick_warm_cpu_s``: the whole first pick, REACH included (median);
- ``charged_warm_s``: the wait the sequencer charges the first APPROACH
  (wall seconds: ``PendingMotion.wait_s``, load-dependent), median;
- ``duration_s``, ``approach_s``: the pick's motion and its APPROACH part;
- ``blended_{plan,retime,split}_cpu_s``: the blended pick's stages (the
  planner's ``plan_pick``, its retime, the time at which the retimed pick
  passes the approach pose; medians), the route of every later pick.

Prints one JSON line. A tree without the staged pick reports the blended
pick as its critical path.

``--grids`` retimes the first pick's blended path (planned once) on uniform
grids of those sizes instead (the retimer adds the knots and refines each,
so every grid keeps the limits between its points): the least CPU over
``--repeats`` and the pick's duration, one JSON line per size.

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
    """CPU seconds of the first pick's critical path, and more (module doc)."""
    from rt_drake.model.scenario import load_scenario
    from rt_drake.simulation.motion import PendingMotion
    from rt_drake.simulation.online_motions import OnlineMotions, time_at
    from rt_drake.types.phase import Phase

    repeats = max(repeats, 1)
    sc = load_scenario(scenario)
    motions = OnlineMotions(sc, jerk_limits=jerk_limits)
    obj = sc.objects[0]
    # The staged route's first part, if this tree has one (else the pick).
    straight = getattr(motions, "straight_approach", None)

    def critical() -> float:
        cpu = time.process_time()
        if straight is None or straight(motions.q_home, obj) is None:
            motions.pick(motions.q_home, obj)
        return time.process_time() - cpu

    first_cpu = critical()
    warm_critical = [critical() for _ in range(repeats)]
    warm_pick, charged = [], []
    for _ in range(repeats):
        cpu = time.process_time()
        pick = motions.pick(motions.q_home, obj)
        warm_pick.append(time.process_time() - cpu)
        charged.append(PendingMotion(pick, 0.0).wait_s(0.0))
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

    def median(values: list[float]) -> float | None:
        return statistics.median(values) if values else None

    return {
        "critical_first_cpu_s": first_cpu,
        "critical_warm_cpu_s": median(warm_critical),
        "pick_warm_cpu_s": median(warm_pick),
        "charged_warm_s": median(charged),
        "duration_s": pick.duration,
        "approach_s": pick.phase_end(Phase.APPROACH),
        **{f"blended_{k}_cpu_s": median(v) for k, v in stages.items()},
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
