"""MOVE path optimisation on Table I's random transports (issue 13).

For each of n transports sampled from a scenario's ``random_transport``
regions (``sample_transports(scenario, n, seed)``), the grasp configuration
comes from APPROACH and REACH from home and the MOVE lifts along the REACH,
as in ``rt_drake.experiments.transport_trial`` (planner seed ``seed +
index``); for a scenario whose ``random_transport.start_on_cup`` is set,
from IK at the start pose with the object already on the cup (the grasp yaw
flip whose MOVE plans). Then the planner's spline MOVE is planned and
:class:`rt_drake.shaping.MoveOptimizer` shortens it.

Printed per transport (durations in s, all under the exact grasp
constraint, all by ``rt_drake.retime``): ``spline100`` the spline path
retimed as the cycle retimes it without the optimiser (100 uniform points),
``spline`` the spline path on the optimiser's grid scheme (adaptive, 500
points: the fair baseline), ``optimised`` the returned path; the ratios
``opt/spl`` (fair) and ``opt/100``; the optimiser's wall ms and the calling
thread's CPU ms (spline planning excluded; ``plan`` is that), the paths
scored, the largest cup tilt and, with ``--discretization``, the loss of the
optimised and the spline path's retimes against 1000 uniform points (%).
``--evaluations N`` sets the search's budget in paths scored (default: the
options' ``max_evaluations``); no clock enters the search. ``--sigma``
sets CMA-ES's initial step size. ``--kto FILE`` compares with the offline
KTO reference's JSON (``tools/kto_reference.py --json``, same scenario, n
and seed): the medians of ``opt/100`` and of the KTO's ``kto/100`` over the
transports whose KTO path is valid, and the gap (shaped / KTO - 1).

    OPENBLAS_NUM_THREADS=1 python benchmarks/bench_optimize.py --n 20 --seed 0
    OPENBLAS_NUM_THREADS=1 python benchmarks/bench_optimize.py \\
        --scenario random_transport_paper --n 20 --seed 0
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import time
from pathlib import Path

import numpy as np
from pydrake.common.schema import Transform

from rt_drake import (
    CupFrame,
    CyclePlanner,
    GraspConstraint,
    JointLimits,
    PlanningError,
    cached_wrench_polytope,
    load_scenario,
    make_arm_plant,
    retime,
)
from rt_drake.model.held import held_object_of
from rt_drake.model.resources import resolve_scenario_path
from rt_drake.planning import sample_transports
from rt_drake.shaping import (
    MoveOptimizer,
    MoveOptimizerOptions,
    warm_up,
)
from rt_drake.types.phase import Phase


class Setup:
    """A scenario's arm, limits, grasp polytope and planner."""

    def __init__(self, scenario: str, seed: int) -> None:
        self.path = resolve_scenario_path(scenario)
        self.scenario = load_scenario(self.path)
        transport = self.scenario.random_transport
        assert transport is not None
        self.name = transport.object
        self.free_space = transport.start_on_cup
        self.seed = seed
        self.plant = make_arm_plant(self.scenario)
        self.context = self.plant.CreateDefaultContext()
        self.cup = CupFrame.of(self.plant)
        self.limits = JointLimits.from_plant(self.plant, self.scenario.robot)
        self.polytope = cached_wrench_polytope(self.scenario.cup)
        self.planner = CyclePlanner(self.scenario, seed=seed)
        warm_up()

    def optimize(self, optimizer: MoveOptimizer, index: int, X_start, X_goal):
        """Transport ``index``: its spline MOVE (planner seeded ``seed + index``),
        grasp and optimised MOVE, and the spline MOVE's planning time (s)."""
        move, plan_s = self.spline_move(index, X_start, X_goal)
        grasp = self.grasp(move)
        return move, grasp, optimizer.optimize(self.planner, move, grasp), plan_s

    def spline_move(self, index: int, X_start, X_goal):
        """Transport ``index``'s spline MOVE (planner seeded ``seed + index``)
        and the time (s) spent planning it (for free space, every flip's)."""
        self.planner.seed = self.seed + index
        return spline_move(
            self.planner, self.name, X_start, X_goal, self.free_space, self.duration
        )

    def duration(self, move) -> float:
        """s, ``move`` retimed as Table I retimes it (100 points, its grasp)."""
        grasp, kw = self.grasp(move), {"context": self.context, "cup": self.cup}
        return retime(self.plant, move.path, self.limits, grasp, 100, **kw).duration

    def transports(self, n: int):
        return sample_transports(self.scenario, n, self.seed)

    def grasp(self, move) -> GraspConstraint:
        obj = self.scenario.object(self.name)
        held = held_object_of(dataclasses.replace(obj, grasp=Transform(move.X_OC)))
        return GraspConstraint.for_cup(held, self.scenario.cup)


def spline_move(planner, name, X_start, X_goal, free_space, duration):
    """(spline MOVE, plan s) for one transport, as the experiment plans it.

    From the bin: APPROACH and REACH from home, then the MOVE. In free space:
    the MOVE of every grasp yaw flip whose start has an IK solution, and the
    one whose ``duration(move)`` is shortest
    (``rt_drake.experiments._transport_experiment.move_from_the_cup``); plan s counts
    every flip's MOVE planning.
    """
    planner.set_object_pose(name, X_start)
    if not free_space:
        approach = planner.plan_approach(planner.q_home, name)
        reach = planner.plan_reach(approach.q_goal, name)
        start = time.perf_counter()
        move = planner.plan_move(reach.q_goal, name, X_goal, reach=reach)
        return move, time.perf_counter() - start
    error, best, plan_s = None, None, 0.0
    for X_OC in planner.grasps(name):
        try:
            planner.prepare(Phase.MOVE, name, planner.q_home, X_OC)
            q = planner.configuration_for(X_start @ X_OC, planner.q_home, name)
            start = time.perf_counter()
            move = planner.plan_move(q, name, X_goal)
            plan_s += time.perf_counter() - start
        except PlanningError as exc:
            error = exc
            continue
        seconds = duration(move)
        if best is None or seconds < best[0]:
            best = (seconds, move)
    if best is None:
        assert error is not None
        raise error
    # The optimiser prepares the scene for the chosen flip itself.
    return best[1], plan_s


SUMMARY_KEYS = (
    "spline100_s", "spline_s", "optimised_s", "ratio_same_grid", "ratio_100",
    "wall_ms", "cpu_ms", "plan_ms", "evaluations", "max_tilt_deg",
)  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenario", default="random_transport")
    parser.add_argument("--n", type=int, default=20)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--max-tilt", type=float, default=None)
    parser.add_argument("--evaluations", type=int, default=None)
    parser.add_argument("--starts", type=int, default=None)
    parser.add_argument("--search-gridpoints", type=int, default=None)
    parser.add_argument("--discretization", action="store_true")
    parser.add_argument("--sigma", type=float, default=None)
    parser.add_argument("--kto", type=Path, default=None)
    parser.add_argument("--json", type=Path, default=None)
    args = parser.parse_args()

    setup = Setup(args.scenario, args.seed)
    defaults = MoveOptimizerOptions()
    options = dataclasses.replace(
        defaults,
        max_tilt_deg=defaults.max_tilt_deg if args.max_tilt is None else args.max_tilt,
        max_evaluations=args.evaluations or defaults.max_evaluations,
        starts=defaults.starts if args.starts is None else args.starts,
        search_gridpoints=args.search_gridpoints or defaults.search_gridpoints,
        sigma=args.sigma or defaults.sigma,
    )
    optimizer = MoveOptimizer(setup.plant, setup.limits, options, setup.cup)
    plant, limits = setup.plant, setup.limits
    transports = setup.transports(args.n)

    def run(index, X_start, X_goal):
        return setup.optimize(optimizer, index, X_start, X_goal)

    run(0, *transports[0])  # compile and load caches before anything is timed
    print(f"{setup.path.name}, n={args.n}, seed={args.seed}, {options}")
    header = (
        "  # spline100   spline  optimised  opt/spl  opt/100   wall ms   cpu ms"
        "  plan ms  paths  tilt deg  improved"
    )
    print(header + ("  loss opt %  loss spl %" if args.discretization else ""))
    rows = []
    for index, (X_start, X_goal) in enumerate(transports):
        try:
            move, grasp, result, plan_s = run(index, X_start, X_goal)
        except PlanningError as error:
            print(f"{index:3d} planning failed: {error}")
            continue
        kw = {"context": setup.context, "cup": setup.cup}
        spline100 = setup.duration(move)
        row = {
            "index": index,
            "spline100_s": spline100,
            "spline_s": result.spline_duration,
            "optimised_s": result.duration,
            "ratio_same_grid": result.duration / result.spline_duration,
            "ratio_100": result.duration / spline100,
            "wall_ms": 1e3 * result.wall_s,
            "cpu_ms": 1e3 * result.cpu_s,
            "plan_ms": 1e3 * plan_s,
            "evaluations": result.evaluations,
            "max_tilt_deg": result.max_tilt_deg,
            "improved": result.improved,
            "timings_ms": {k: 1e3 * v for k, v in result.timings.items()},
            "rejected": list(result.rejected),
        }
        line = (
            f"{index:3d} {spline100:9.3f} {result.spline_duration:8.3f} "
            f"{result.duration:10.3f} {row['ratio_same_grid']:8.3f} "
            f"{row['ratio_100']:8.3f} {row['wall_ms']:9.1f} "
            f"{row['cpu_ms']:8.1f} {row['plan_ms']:8.1f} {result.evaluations:6d} "
            f"{result.max_tilt_deg:9.1f}  {result.improved!s:>8}"
        )
        if args.discretization:
            for key, path, retimed in (
                ("loss_pct", result.path, result.retimed),
                ("loss_spline_pct", move.path, result.spline_retimed),
            ):
                fine = retime(plant, path, limits, grasp, 1000, **kw)
                row[key] = 100.0 * (retimed.duration / fine.duration - 1.0)
            line += f"  {row['loss_pct']:+10.2f}  {row['loss_spline_pct']:+10.2f}"
        print(line, flush=True)
        rows.append(row)
    summary = {key: float(np.median([r[key] for r in rows])) for key in SUMMARY_KEYS}
    summary["improved"] = sum(r["improved"] for r in rows)
    summary["count"] = len(rows)
    text = (
        f"median: spline100 {summary['spline100_s']:.3f} s, spline "
        f"{summary['spline_s']:.3f} s, optimised {summary['optimised_s']:.3f} s, "
        f"ratio {summary['ratio_same_grid']:.3f} against the spline on the same "
        f"grid, {summary['ratio_100']:.3f} against spline100; wall "
        f"{summary['wall_ms']:.0f} ms, cpu {summary['cpu_ms']:.0f} ms, "
        f"{summary['evaluations']:.0f} paths, tilt {summary['max_tilt_deg']:.1f} "
        f"deg; improved {summary['improved']}/{summary['count']}"
    )
    if args.discretization:
        summary["loss_pct_max"] = max(
            max(r["loss_pct"], r["loss_spline_pct"]) for r in rows
        )
        text += f"; discretization loss max {summary['loss_pct_max']:+.2f} %"
    print(text)
    if args.kto:
        summary.update(kto_gap(rows, args.kto))
        print(
            f"against the KTO reference on its {summary['kto_count']} valid "
            f"transports: opt/100 {summary['kto_shaped_100']:.4f}, kto/100 "
            f"{summary['kto_100']:.4f}, gap {100 * summary['kto_gap']:+.2f} %"
        )
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps({"rows": rows, "summary": summary}, indent=1))


def kto_gap(rows: list[dict], path: Path) -> dict:
    """Medians of ``opt/100`` and the KTO's ``kto/100`` on the same transports.

    Over the transports of ``rows`` whose KTO path in the JSON at ``path``
    is valid; both ratios have the same denominator (the spline path at 100
    points, checked equal to 1e-9 s). ``kto_gap``: shaped median / KTO
    median - 1.
    """
    reference = {
        r["index"]: r for r in json.loads(path.read_text())["rows"] if r["valid"]
    }
    common = [r for r in rows if r["index"] in reference]
    for r in common:
        spline = reference[r["index"]]["spline100_s"]
        assert abs(r["spline100_s"] - spline) < 1e-9, (r["index"], spline)
    shaped = float(np.median([r["ratio_100"] for r in common]))
    kto = float(np.median([reference[r["index"]]["kto_ratio_100"] for r in common]))
    return {
        "kto_count": len(common),
        "kto_shaped_100": shaped,
        "kto_100": kto,
        "kto_gap": shaped / kto - 1.0,
    }


if __name__ == "__main__":
    main()
