"""Learn the optimiser's warm starts (rt_drake/shaping/data/warm_starts.npz).

For each of n transports of a scenario (planned as in bench_optimize.py),
a long search (``--evaluations`` paths, CMA-ES, no time budget) shortens
the MOVE; the via points of the returned path become a library entry: their
cup poses as offsets from the spline path's corners in the transport's frame,
and the transport's features (rt_drake.shaping._starts).

    # round 1, from x = 0 only; round 2, from round 1's library as well
    python tools/learn_starts.py --scenario random_transport --seed 3 \\
        --starts 0 --json out/starts_rt_1.json
    python tools/learn_starts.py --write out/starts_rt_1.json ...
    python tools/learn_starts.py --scenario random_transport --seed 3 \\
        --json out/starts_rt_2.json
    python tools/learn_starts.py --write out/starts_*_[12].json

``--write`` keeps, per transport, the entry of the run that shortened it
most, and writes the package data rt_drake/shaping/data/warm_starts.npz.
Never learn on the seeds the benchmarks report.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))

from bench_optimize import Setup  # noqa: E402

from rt_drake import PlanningError  # noqa: E402
from rt_drake.shaping import (
    MoveOptimizer,
    MoveOptimizerOptions,
)  # noqa: E402
from rt_drake.shaping._starts import (
    features,
    transport_frame,
)  # noqa: E402
from rt_drake.shaping.cup_chain import _rotation_vector  # noqa: E402

LIBRARY = Path(__file__).parents[1] / "rt_drake/shaping/data/warm_starts.npz"


def learn(args: argparse.Namespace) -> None:
    setup = Setup(args.scenario, args.seed)
    options = MoveOptimizerOptions(
        max_evaluations=args.evaluations, starts=args.starts,
    )  # fmt: skip
    optimizer = MoveOptimizer(setup.plant, setup.limits, options, setup.cup)
    chain = optimizer.chain
    entries = []
    for index, (X_start, X_goal) in enumerate(setup.transports(args.n)):
        try:
            move, _ = setup.spline_move(index, X_start, X_goal)
        except PlanningError as error:
            print(f"{index:3d} planning failed: {error}")
            continue
        result = optimizer.optimize(setup.planner, move, setup.grasp(move))
        ratio = result.duration / result.spline_duration
        print(f"{index:3d} ratio {ratio:.3f} ({result.evaluations} paths)", flush=True)
        if not result.improved:
            continue
        family = optimizer._family(move, options.via_points)
        m = options.vertical_points
        via = result.path.waypoints[1 + m : 1 + m + options.via_points]
        R0, p0 = chain.cup_pose(family.reference)
        R1, p1 = chain.cup_pose(via)
        T = transport_frame(chain, move.path)
        offsets = np.hstack(
            [(p1 - p0) @ T, _rotation_vector(R1 @ np.swapaxes(R0, -1, -2)) @ T]
        )
        entries.append(
            {
                "scenario": Path(args.scenario).stem,
                "seed": args.seed,
                "index": index,
                "ratio": ratio,
                "offsets": offsets.tolist(),
                "features": features(chain, move.path, family.reference).tolist(),
            }
        )
    args.json.parent.mkdir(parents=True, exist_ok=True)
    args.json.write_text(json.dumps(entries, indent=1))


def write(files: list[Path]) -> None:
    best: dict[tuple, dict] = {}
    for file in files:
        for entry in json.loads(file.read_text()):
            key = (entry["scenario"], entry["seed"], entry["index"])
            if key not in best or entry["ratio"] < best[key]["ratio"]:
                best[key] = entry
    entries = [best[k] for k in sorted(best)]
    learned_on = ", ".join(
        sorted({f"{e['scenario']} seed {e['seed']}" for e in entries})
    )
    offsets = np.round(np.array([e["offsets"] for e in entries], dtype=float), 4)
    keys = np.round(np.array([e["features"] for e in entries], dtype=float), 4)
    np.savez(LIBRARY, offsets=offsets, features=keys, learned_on=np.array(learned_on))
    ratios = [e["ratio"] for e in entries]
    print(
        f"wrote {LIBRARY}: {len(entries)} starts, median ratio {np.median(ratios):.3f}"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenario", default="random_transport")
    parser.add_argument("--seed", type=int, default=3)
    parser.add_argument("--n", type=int, default=20)
    parser.add_argument("--evaluations", type=int, default=1500)
    parser.add_argument("--starts", type=int, default=12)
    parser.add_argument("--json", type=Path)
    parser.add_argument("--write", type=Path, nargs="+")
    args = parser.parse_args()
    if args.write:
        write(args.write)
    else:
        learn(args)


if __name__ == "__main__":
    main()
