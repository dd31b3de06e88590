"""Retime time and durations of two commits, side by side in one run.

Run: ``python benchmarks/bench_retime_commits.py BEFORE AFTER [--rounds 4]``,
e.g. ``e2cd504 HEAD``. Each commit is checked out into a temporary git
worktree, where one process retimes the 5 MOVE paths of ``bench_retime.py``
(notebook, exact grasp polytope, 100 grid points) on request: the two
processes alternate retime by retime (``--repeats`` times every path), so
both see the same machine load. Printed: median and p10/p90 wall time per
retime, the median CPU time of the retiming thread (``time.thread_time``:
on a shared machine it counts only the time the retime ran, not the time
it waited for a core), the durations, and each trajectory's worst excess
over its limits sampled at 1 kHz (``check_trajectory``).
``OPENBLAS_NUM_THREADS=1``.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: Runs inside the checked-out tree: names changed across commits.
WORKER = r"""
import inspect, json, sys, time
import numpy as np
try:  # the layout since house 2
    from rt_drake.model.held import held_object_of
    from rt_drake.model.plant import make_arm_plant
    from rt_drake.model.resources import scenarios_dir
    from rt_drake.model.scenario import load_scenario
    from rt_drake.types.path import GeometricPath
    from rt_drake.dynamics.cup_frame import CupFrame
except ImportError:  # before: root modules
    from rt_drake.dynamics import HeldObject
    from rt_drake.planning.path import GeometricPath
    from rt_drake.plant import make_arm_plant
    from rt_drake.resources import scenarios_dir
    from rt_drake.scenario import load_scenario
    held_object_of = HeldObject.from_scenario_object
    try:
        from rt_drake.cup_frame import CupFrame
    except ImportError:
        CupFrame = None
try:
    from rt_drake.retiming import GraspConstraint, JointLimits, check_trajectory, retime
except ImportError:
    from rt_drake.retime import GraspConstraint, JointLimits, check_trajectory, retime
HOME = np.array([0.0, 0.35, 1.75, 0.0, 1.04, 0.0])
paths = []
for swing in np.linspace(0.6, 1.8, 5):
    lift = HOME + [0.0, -0.25, -0.3, 0.0, 0.45, 0.0]
    waypoints = [HOME, lift, lift + [0.5 * swing, 0.05, 0.1, 0.1, -0.1, 0.3 * swing],
                 lift + [swing, 0, 0, 0, 0, 0.6 * swing],
                 HOME + [swing, 0, 0, 0, 0, 0.6 * swing]]
    paths.append(GeometricPath.from_waypoints(np.array(waypoints)))
scenario = load_scenario(scenarios_dir() / "stack_four_objects.yaml")
plant = make_arm_plant(scenario)
context = plant.CreateDefaultContext()
limits = JointLimits.from_plant(plant, scenario.robot)
held = held_object_of(scenario.object("notebook"))
grasp = GraspConstraint.for_cup(held, scenario.cup)
options = {}
if "cup" in inspect.signature(retime).parameters:
    options["cup"] = CupFrame.of(plant)
out = {"times": [], "durations": [], "excess": []}
for path in paths:
    result = retime(plant, path, limits, grasp, 100, context=context, **options)
    out["durations"].append(result.duration)
    check = check_trajectory(plant, result.trajectory, limits, grasp)
    out["excess"].append({k: e.value for k, e in check.excess.items()})
print(json.dumps(out), flush=True)
for line in sys.stdin:  # one retime per request: the path's index
    path = paths[int(line)]
    start, cpu = time.perf_counter(), time.thread_time()
    retime(plant, path, limits, grasp, 100, context=context, **options)
    print(time.perf_counter() - start, time.thread_time() - cpu, flush=True)
"""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("before")
    parser.add_argument("after")
    parser.add_argument("--repeats", type=int, default=40)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as scratch:
        trees = {}
        for label, ref in (("before", args.before), ("after", args.after)):
            tree = Path(scratch) / label
            subprocess.run(
                ["git", "-C", str(ROOT), "worktree", "add", "--detach", str(tree), ref],
                check=True,
                capture_output=True,
            )
            trees[label] = tree
        try:
            results = _run(trees, args.repeats)
        finally:
            for tree in trees.values():
                subprocess.run(
                    [
                        "git",
                        "-C",
                        str(ROOT),
                        "worktree",
                        "remove",
                        "--force",
                        str(tree),
                    ],
                    check=False,
                    capture_output=True,
                )
    for label, ref in (("before", args.before), ("after", args.after)):
        r = results[label]
        times = sorted(1e3 * t for t in r["times"])
        deciles = statistics.quantiles(times, n=10)
        cpu = statistics.median(1e3 * t for t in r["cpu"])
        print(
            f"{label} ({ref}): median {statistics.median(times):.2f} ms wall "
            f"(p10 {deciles[0]:.2f}, p90 {deciles[-1]:.2f}), {cpu:.2f} ms CPU; "
            "durations " + " ".join(f"{d:.4f}" for d in r["durations"])
        )
        worst = {k: max(e[k] for e in r["excess"]) for k in r["excess"][0]}
        print(
            "  worst excess at 1 kHz: "
            + ", ".join(f"{k} {100 * v:+.3f} %" for k, v in worst.items())
        )
    before, after = results["before"], results["after"]
    ratio = statistics.median(after["times"]) / statistics.median(before["times"])
    cpu_ratio = statistics.median(after["cpu"]) / statistics.median(before["cpu"])
    durations = [
        a / b for a, b in zip(after["durations"], before["durations"], strict=True)
    ]
    print(
        f"after / before: wall {ratio:.3f}, CPU {cpu_ratio:.3f}; durations "
        + " ".join(f"{d:.4f}" for d in durations)
    )


def _run(trees: dict[str, Path], repeats: int) -> dict:
    workers = {}
    for label, tree in trees.items():
        env = {**os.environ, "PYTHONPATH": str(tree), "OPENBLAS_NUM_THREADS": "1"}
        workers[label] = subprocess.Popen(
            [sys.executable, "-c", WORKER],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            text=True,
            env=env,
            cwd=tree,
        )
    results = {}
    for label, worker in workers.items():
        assert worker.stdout is not None
        results[label] = {
            **json.loads(worker.stdout.readline()),
            "times": [],
            "cpu": [],
        }
    for _ in range(repeats):
        for index in range(5):
            for label, worker in workers.items():
                assert worker.stdin is not None and worker.stdout is not None
                worker.stdin.write(f"{index}\n")
                worker.stdin.flush()
                wall, cpu = map(float, worker.stdout.readline().split())
                results[label]["times"].append(wall)
                results[label]["cpu"].append(cpu)
    for worker in workers.values():
        assert worker.stdin is not None
        worker.stdin.close()
        worker.wait()
    return results


if __name__ == "__main__":
    main()
