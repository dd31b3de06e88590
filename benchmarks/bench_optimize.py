"""MOVE path optimisation on Table I's random transports (issue 13).

For each of n transports sampled from a scenario's ``random_transport``
regions (``sample_transports(scenario, n, seed)``), the grasp configuration
comes from APPROACH and REACH from home, as in
``rt_drake.experiments.transport_trial`` (planner seed ``seed + index``), or,
with ``--free-space``, from IK at the start pose with the object already on
the cup (the grasp yaw flip whose MOVE plans). Then the planner's spline MOVE
is planned and :func:`rt_drake.planning.shape.optimize_move` shortens it.

Printed per transport (durations in s, under the exact grasp constraint):
``spline100`` the spline path retimed as today (100 uniform points),
``spline`` the same on the optimiser's adaptive grid, ``optimised`` the
returned path, the ratios ``opt/100`` and ``opt/spl`` of the two, the
optimiser's wall and CPU ms (spline planning excluded; ``plan`` is that), the
paths scored, the largest cup tilt and, with ``--discretization``, the loss of
the optimised path's retime against 1000 uniform points (%).

    OPENBLAS_NUM_THREADS=1 python benchmarks/bench_optimize.py --n 20 --seed 0
    OPENBLAS_NUM_THREADS=1 python benchmarks/bench_optimize.py \\
        --scenario random_transport_paper --free-space --n 20 --seed 0
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
    HeldObject,
    JointLimits,
    PlanningError,
    cached_wrench_polytope,
    load_scenario,
    make_arm_plant,
    retime,
)
from rt_drake.phase import Phase
from rt_drake.planning import sample_transports
from rt_drake.planning.shape import (
    Clock,
    MoveOptimizerOptions,
    optimize_move,
    warm_up,
)
from rt_drake.resources import scenarios_dir


def grasp_configuration(planner, name, X_start, X_goal, free_space):
    """(q_grasp, spline MOVE, plan s) for one transport."""
    planner.set_object_pose(name, X_start)
    if not free_space:
        approach = planner.plan_approach(planner.q_home, name)
        reach = planner.plan_reach(approach.q_goal, name)
        q_grasp = reach.q_goal
        start = time.perf_counter()
        move = planner.plan_move(q_grasp, name, X_goal, reach=reach)
        return q_grasp, move, time.perf_counter() - start
    error = None
    for X_OC in planner.grasps(name):
        try:
            planner.prepare(Phase.MOVE, name, planner.q_home, X_OC)
            q = planner.configuration_for(X_start @ X_OC, planner.q_home, name)
            start = time.perf_counter()
            move = planner.plan_move(q, name, X_goal)
            return q, move, time.perf_counter() - start
        except PlanningError as exc:
            error = exc
    raise error


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenario", default="random_transport")
    parser.add_argument("--n", type=int, default=20)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--max-tilt", type=float, default=None)
    parser.add_argument("--budget", type=float, default=None)
    parser.add_argument("--clock", choices=["wall", "process"], default="wall")
    parser.add_argument("--evaluations", type=int, default=None)
    parser.add_argument("--free-space", action="store_true")
    parser.add_argument("--discretization", action="store_true")
    parser.add_argument("--json", type=Path, default=None)
    args = parser.parse_args()

    path = Path(args.scenario)
    if not path.exists():
        path = scenarios_dir() / f"{args.scenario}.yaml"
    scenario = load_scenario(path)
    name = scenario.random_transport.object
    obj = scenario.object(name)
    plant = make_arm_plant(scenario)
    context = plant.CreateDefaultContext()
    cup = CupFrame.of(plant)
    limits = JointLimits.from_plant(plant, scenario.robot)
    polytope = cached_wrench_polytope(scenario.cup)
    defaults = MoveOptimizerOptions()
    options = dataclasses.replace(
        defaults,
        max_tilt_deg=defaults.max_tilt_deg if args.max_tilt is None else args.max_tilt,
        budget_s=defaults.budget_s if args.budget is None else args.budget,
        clock=Clock(args.clock),
        max_evaluations=args.evaluations,
    )
    planner = CyclePlanner(scenario, seed=args.seed)
    warm_up()
    transports = sample_transports(scenario, args.n, args.seed)

    def run(index, X_start, X_goal):
        planner.seed = args.seed + index
        q_grasp, move, plan_s = grasp_configuration(
            planner, name, X_start, X_goal, args.free_space
        )
        held = HeldObject.from_scenario_object(
            dataclasses.replace(obj, grasp=Transform(move.X_OC))
        )
        grasp = GraspConstraint(held, polytope.F, polytope.g, scenario.cup)
        result = optimize_move(
            planner, plant, q_grasp, name, grasp, limits, options, X_goal,
            spline=move, context=context, cup=cup,
        )  # fmt: skip
        return move, grasp, result, plan_s

    run(0, *transports[0])  # compile and load caches before anything is timed
    print(f"{path.name}, n={args.n}, seed={args.seed}, {options}")
    header = (
        "  # spline100   spline  optimised  opt/100  opt/spl   wall ms   cpu ms"
        "  plan ms  paths  tilt deg  improved"
    )
    print(header + ("  loss %" if args.discretization else ""))
    rows = []
    for index, (X_start, X_goal) in enumerate(transports):
        try:
            move, grasp, result, plan_s = run(index, X_start, X_goal)
        except PlanningError as error:
            print(f"{index:3d} planning failed: {error}")
            continue
        today = retime(plant, move.path, limits, grasp, 100, context=context, cup=cup)
        row = {
            "index": index,
            "spline100_s": today.duration,
            "spline_s": result.spline_duration,
            "optimised_s": result.duration,
            "ratio_100": result.duration / today.duration,
            "ratio_same_grid": result.duration / result.spline_duration,
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
            f"{index:3d} {today.duration:9.3f} {result.spline_duration:8.3f} "
            f"{result.duration:10.3f} {row['ratio_100']:8.3f} "
            f"{row['ratio_same_grid']:8.3f} {row['wall_ms']:9.1f} "
            f"{row['cpu_ms']:8.1f} {row['plan_ms']:8.1f} {result.evaluations:6d} "
            f"{result.max_tilt_deg:9.1f}  {result.improved!s:>8}"
        )
        if args.discretization:
            fine = retime(
                plant, result.path, limits, grasp, 1000, context=context, cup=cup
            )
            row["loss_pct"] = 100.0 * (result.duration / fine.duration - 1.0)
            line += f"  {row['loss_pct']:+6.2f}"
        print(line, flush=True)
        rows.append(row)
    summary = {
        key: float(np.median([r[key] for r in rows]))
        for key in (
            "spline100_s", "spline_s", "optimised_s", "ratio_100",
            "ratio_same_grid", "wall_ms", "cpu_ms", "plan_ms", "evaluations",
            "max_tilt_deg",
        )
    }  # fmt: skip
    summary["improved"] = sum(r["improved"] for r in rows)
    summary["count"] = len(rows)
    if args.discretization:
        summary["loss_pct_max"] = max(r["loss_pct"] for r in rows)
    print(
        f"median: spline100 {summary['spline100_s']:.3f} s, optimised "
        f"{summary['optimised_s']:.3f} s, ratio {summary['ratio_100']:.3f} "
        f"(same grid {summary['ratio_same_grid']:.3f}), wall "
        f"{summary['wall_ms']:.0f} ms, cpu {summary['cpu_ms']:.0f} ms, "
        f"{summary['evaluations']:.0f} paths, tilt {summary['max_tilt_deg']:.1f} deg; "
        f"improved {summary['improved']}/{summary['count']}"
        + (
            f"; discretization loss max {summary['loss_pct_max']:+.2f} %"
            if args.discretization
            else ""
        )
    )
    if args.json:
        args.json.write_text(json.dumps({"rows": rows, "summary": summary}, indent=1))


if __name__ == "__main__":
    main()
