"""The shaped MOVE under several optimiser settings, on the same planned MOVEs.

Plans a seed's ``--n`` transports once, as ``benchmarks/bench_optimize.py``
does (planner seeded ``seed + index``), then shapes each MOVE with every
setting given as JSON, ``{"name": {MoveOptimizerOptions field: value}}``
(``{}``: the defaults), in the same process. Per setting: the median of
``opt/100`` (the shaped MOVE's duration over the spline path's at 100
uniform points, both under the grasp constraint), the optimiser's CPU ms
(median, max; ``time.process_time``), and with ``--kto FILE`` (a
``tools/kto_reference.py --json`` of the same seed) the medians over the
transports whose KTO path is valid and the gap, shaped / KTO - 1.

The reserved key ``"final_score": true`` in a setting makes its search
score each candidate by the final retime itself (``MoveOptimizer.retime``,
the adaptive 400-point grid the shaped and the KTO medians use) instead of
the coarse 24-point retimer: a search that ranks its candidates exactly as
the final retime does, at about 40 times the CPU. Its gap bounds what any
better search score can give with the same path family and effort.

    OPENBLAS_NUM_THREADS=1 python tools/shape_variants.py --seed 1 \\
        --kto out/kto_1.json '{"default": {}, "uniform grid": \\
        {"search_grid_weight": null}, "final score": {"final_score": true}}'
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
from bench_optimize import Setup  # noqa: E402

import rt_drake.shaping._optimizer as optimizer_module  # noqa: E402
from rt_drake import GeometricPath, PlanningError, RetimeError  # noqa: E402
from rt_drake.shaping import MoveOptimizer, MoveOptimizerOptions  # noqa: E402
from rt_drake.shaping._surrogate import CoarseRetimer  # noqa: E402


def final_scores(optimizer: MoveOptimizer) -> type[CoarseRetimer]:
    """A CoarseRetimer whose durations are ``optimizer.retime``'s (inf: refused)."""

    class FinalScores(CoarseRetimer):
        def evaluate(self, waypoints, bound=np.inf):
            durations = np.empty(len(waypoints))
            for p, w in enumerate(waypoints):
                try:
                    path = GeometricPath.from_waypoints(w)
                    durations[p] = optimizer.retime(path, self.grasp).duration
                except RetimeError:
                    durations[p] = np.inf
            used = np.broadcast_to(self.rows, (len(waypoints), len(self.rows)))
            return durations, np.ones(len(waypoints), bool), used.copy()

    return FinalScores


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("settings", type=json.loads)
    parser.add_argument("--scenario", default="random_transport")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--n", type=int, default=20)
    parser.add_argument("--kto", type=Path, default=None)
    args = parser.parse_args()
    setup = Setup(args.scenario, args.seed)
    transports = setup.transports(args.n)
    moves = {}
    for index, (X_start, X_goal) in enumerate(transports):
        try:
            move, _ = setup.spline_move(index, X_start, X_goal)
        except PlanningError as error:
            print(f"{index:3d} planning failed: {error}")
            continue
        moves[index] = (move, setup.grasp(move), setup.duration(move))
    reference = {}
    if args.kto is not None:
        rows = json.loads(args.kto.read_text())["rows"]
        reference = {r["index"]: r["kto_ratio_100"] for r in rows if r["valid"]}
    for name, fields in args.settings.items():
        fields = dict(fields)
        final_score = bool(fields.pop("final_score", False))
        options = dataclasses.replace(MoveOptimizerOptions(), **fields)
        optimizer = MoveOptimizer(setup.plant, setup.limits, options, setup.cup)
        optimizer_module.CoarseRetimer = (  # type: ignore[misc]
            final_scores(optimizer) if final_score else CoarseRetimer
        )
        first = next(iter(moves.values()))
        optimizer.optimize(setup.planner, first[0], first[1])  # caches
        ratio, cpu = {}, []
        for index, (move, grasp, spline100) in moves.items():
            result = optimizer.optimize(setup.planner, move, grasp)
            ratio[index] = result.duration / spline100
            cpu.append(1e3 * result.cpu_s)
        line = (
            f"seed {args.seed} {name}: opt/100 {np.median(list(ratio.values())):.4f}"
            f" over {len(ratio)}; CPU ms {np.median(cpu):.0f} (max {max(cpu):.0f})"
        )
        common = [i for i in ratio if i in reference]
        if common:
            shaped = float(np.median([ratio[i] for i in common]))
            kto = float(np.median([reference[i] for i in common]))
            line += (
                f"; on the {len(common)} valid KTO transports: shaped {shaped:.4f},"
                f" KTO {kto:.4f}, gap {100 * (shaped / kto - 1):+.2f} %"
            )
        print(line, flush=True)


if __name__ == "__main__":
    main()
