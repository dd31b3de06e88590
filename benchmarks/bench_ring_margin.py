"""What the ring margin costs per MOVE: its search against one plain retime.

    python benchmarks/bench_ring_margin.py [SCENARIO] [--seed 0]
        [--trials 0 1 ...] [--fixed 0.397] [--repeats 3]

For each trial of ``experiment transport`` (the MOVE from the cup, or after
APPROACH and REACH from home, planned as the experiment plans it with the
grasp margin ``--fixed``), the MOVE's path is retimed, in the same process,
on the same retimer (jerk limits and ``planning.grasp_ramp_s`` as the
scenario gives them):

- ``plain``: once under the set shrunk by ``--fixed`` (the derived margin:
  0.397 for ``carton_two_cups_bellows_20n_stiffness``);
- ``ring``: by :func:`rt_drake.retiming.retime_for_ring` (``planning.
  grasp_margin: ring``): its retimes and the ring of each.

Timed with ``time.process_time`` (CPU), the least of ``--repeats``. Prints
one line per trial (CPU of each, their ratio, the ring's retimes, margin
and MOVE duration beside the fixed margin's) and the medians.
"""

from __future__ import annotations

import argparse
import dataclasses
import statistics
import time

from rt_drake.experiments._transport_experiment import (
    played_move,
    transport_inputs,
    transport_scenario,
)
from rt_drake.model.resources import resolve_scenario_path
from rt_drake.planning import sample_transports
from rt_drake.retiming import retime_for_ring
from rt_drake.simulation import OnlineMotions
from rt_drake.simulation.move_grasp import grasp_for, ring_tool


def main() -> None:
    """Print one line per trial, then the medians."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "scenario", nargs="?", default="carton_two_cups_bellows_20n_stiffness"
    )
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--trials", type=int, nargs="+", default=list(range(10)))
    parser.add_argument("--fixed", type=float, default=0.397)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    path = resolve_scenario_path(args.scenario)
    scenario, name = transport_inputs(path, max(args.trials) + 1, 1, None)

    def with_margin(margin: float | str):
        planning = dataclasses.replace(scenario.planning, grasp_margin=margin)
        return dataclasses.replace(scenario, planning=planning)

    fixed, ring = with_margin(args.fixed), with_margin("ring")
    tool = ring_tool(ring)
    assert tool is not None
    pairs = sample_transports(scenario, max(args.trials) + 1, args.seed)
    jerk = bool(scenario.robot.jerk_limits)
    rows = []
    for i in args.trials:
        X_start, X_goal = pairs[i]
        planned = transport_scenario(fixed, name, X_start, X_goal)
        motions = OnlineMotions(
            planned, seed=args.seed + i, optimize=False, jerk_limits=jerk
        )
        obj = planned.objects[0]
        try:
            move = played_move(fixed, motions, obj, X_start)
        except Exception as error:  # noqa: BLE001 (a benchmark: report and go on)
            print(f"trial {i}: no MOVE: {type(error).__name__}", flush=True)
            continue
        assert move.planned is not None and move.retimed is not None
        path, X_OC = move.planned.path, move.planned.X_OC
        grasp = grasp_for(ring, obj, X_OC, robust=False)  # unshrunk
        plant, context, cup = motions._plant, motions._context, motions._cup  # noqa: SLF001
        plain_cpu, ring_cpu = [], []
        for _ in range(args.repeats):
            start = time.process_time()
            plain = motions.retime_path(path, grasp.with_margin(args.fixed))
            plain_cpu.append(time.process_time() - start)
            start = time.process_time()
            found = retime_for_ring(
                lambda g: motions.retime_path(path, g),  # noqa: B023
                path, grasp, tool, plant, context, cup,
            )  # fmt: skip
            ring_cpu.append(time.process_time() - start)
        row = (min(plain_cpu), min(ring_cpu), found, plain.duration)
        rows.append(row)
        print(
            f"trial {i}: plain {row[0]:.3f} s CPU ({args.fixed:g}: MOVE "
            f"{plain.duration:.3f} s), ring {row[1]:.3f} s CPU = "
            f"{row[1] / row[0]:.1f}x ({found.retimes} retimes, margin "
            f"{found.margin:.3f}, ring rows {found.load.ring:.3f}, D "
            f"{found.load.factor:.2f}, MOVE {found.result.duration:.3f} s)",
            flush=True,
        )
    if rows:

        def median(values) -> float:
            return statistics.median(values)

        print(
            f"median over {len(rows)}: plain {median(r[0] for r in rows):.3f} s "
            f"CPU, ring {median(r[1] for r in rows):.3f} s CPU, ratio "
            f"{median(r[1] / r[0] for r in rows):.1f}x, retimes "
            f"{median(r[2].retimes for r in rows):g}, margin "
            f"{median(r[2].margin for r in rows):.3f}, MOVE ring "
            f"{median(r[2].result.duration for r in rows):.3f} s vs "
            f"{median(r[3] for r in rows):.3f} s at {args.fixed:g}"
        )


if __name__ == "__main__":
    main()
