"""Retime time and durations of two commits, side by side in one run.

Run: ``python benchmarks/bench_retime_commits.py BEFORE AFTER [--rounds 4]``,
e.g. ``e2cd504 HEAD``. Each commit is checked out into a temporary git
worktree; one process per commit retimes the 5 MOVE paths of
``bench_retime.py`` (notebook, exact grasp polytope, 100 grid points), 10
repeats each, and the two alternate ``--rounds`` times so that both see the
same machine load. Printed: median and p10/p90 wall time per retime, the
durations, and each trajectory's worst excess over its limits sampled at
1 kHz (``check_trajectory``). ``OPENBLAS_NUM_THREADS=1``.
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
from rt_drake.planning.path import GeometricPath
from rt_drake.plant import make_arm_plant
from rt_drake.resources import scenarios_dir
from rt_drake.scenario import load_scenario
from rt_drake.dynamics import HeldObject
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
held = HeldObject.from_scenario_object(scenario.object("notebook"))
grasp = GraspConstraint.for_cup(held, scenario.cup)
options = {}
if "cup" in inspect.signature(retime).parameters:
    from rt_drake.cup_frame import CupFrame
    options["cup"] = CupFrame.of(plant)
out = {"times": [], "durations": [], "excess": []}
for path in paths:
    result = retime(plant, path, limits, grasp, 100, context=context, **options)
    out["durations"].append(result.duration)
    check = check_trajectory(plant, result.trajectory, limits, grasp)
    out["excess"].append({k: e.value for k, e in check.excess.items()})
for _ in range(int(sys.argv[1])):
    for path in paths:
        start = time.perf_counter()
        retime(plant, path, limits, grasp, 100, context=context, **options)
        out["times"].append(time.perf_counter() - start)
print(json.dumps(out))
"""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("before")
    parser.add_argument("after")
    parser.add_argument("--rounds", type=int, default=4)
    parser.add_argument("--repeats", type=int, default=10)
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
            results = _run(trees, args.rounds, args.repeats)
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
        print(
            f"{label} ({ref}): median {statistics.median(times):.2f} ms "
            f"(p10 {deciles[0]:.2f}, p90 {deciles[-1]:.2f}); durations "
            + " ".join(f"{d:.4f}" for d in r["durations"])
        )
        worst = {k: max(e[k] for e in r["excess"]) for k in r["excess"][0]}
        print(
            "  worst excess at 1 kHz: "
            + ", ".join(f"{k} {100 * v:+.3f} %" for k, v in worst.items())
        )
    before, after = results["before"], results["after"]
    ratio = statistics.median(after["times"]) / statistics.median(before["times"])
    durations = [
        a / b for a, b in zip(after["durations"], before["durations"], strict=True)
    ]
    print(
        f"after / before: time {ratio:.3f}; durations "
        + " ".join(f"{d:.4f}" for d in durations)
    )


def _run(trees: dict[str, Path], rounds: int, repeats: int) -> dict:
    results: dict[str, dict] = {label: {"times": []} for label in trees}
    for _ in range(rounds):
        for label, tree in trees.items():
            env = {**os.environ, "PYTHONPATH": str(tree), "OPENBLAS_NUM_THREADS": "1"}
            out = subprocess.run(
                [sys.executable, "-c", WORKER, str(repeats)],
                capture_output=True,
                text=True,
                env=env,
                cwd=tree,
                check=True,
            )
            data = json.loads(out.stdout.strip().splitlines()[-1])
            results[label]["times"] += data["times"]
            results[label]["durations"] = data["durations"]
            results[label]["excess"] = data["excess"]
    return results


if __name__ == "__main__":
    main()
