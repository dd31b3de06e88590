"""Where the pick's jerk cost comes from: the retimer against references (issue 27).

    python tools/pick_jerk_cost.py [SCENARIO] [--seed N] [--grids 100 400]

For each object of the cycle, the blended pick the planner gives (retreat,
transit and descent in one path, as ``rt-drake run`` plays every pick but
the staged first) is retimed without grasp (no object is held):

- ``no jerk``: TOPP-RA at the joint velocity and acceleration limits;
- ``jerk``: the jerk-limited retime as the cycle runs it (the scenario's
  jerk limits, ``--grids``' first size);
- ``finer``: the same on each further grid size (more points, the same LPs;
  nan where the retimer refuses the grid);
- ``adaptive``: the first grid's number of points placed by the path's
  acceleration-limited profile (:func:`rt_drake.shaping.adaptive_grid`, as
  the cycle's shaped MOVE is retimed), the profile's CPU counted;
- ``strict``: the first grid with the LP sequence run to a relative change
  of 1e-6 (at most 60 LPs per round) instead of the retimer's 1e-3 and 12;
- ``floor`` and ``floor no jerk``: the cycle's floor over the pick's
  segments (retreat, transit, descent: :mod:`rt_drake.experiments.cycle_floor`),
  with and without the jerk limits.

``jerk - no jerk`` is the pick's jerk cost; ``floor - floor no jerk`` the
part of it any motion through the same lines pays; a drop from ``jerk`` to
``finer`` or ``strict`` would be the retimer's own share. CPU times
(``time.process_time``) per retime are printed beside.
"""

from __future__ import annotations

import argparse
import time
from unittest import mock

import numpy as np
from _cycle_picks import cycle_picks, jerk_cell

from rt_drake.experiments import cycle_floors
from rt_drake.retiming import RetimeError, retime
from rt_drake.retiming import _jerk as jerk_module
from rt_drake.shaping import ADAPTIVE_WEIGHT, adaptive_grid, retime_adaptive


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenario", nargs="?", default="stack_four_objects")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--grids", type=int, nargs="+", default=[100, 400])
    args = parser.parse_args()
    scenario, plant, limits = jerk_cell(parser, args.scenario)
    no_jerk = limits.without_jerk()
    jerk = np.array(scenario.robot.jerk_limits)
    shaped = scenario.planning.optimize_move
    floors = cycle_floors(scenario, args.seed, jerk=jerk, shaped=shaped)
    bare = cycle_floors(scenario, args.seed, shaped=shaped)
    grid = args.grids[0]
    head = ["object", "no jerk", *(f"jerk ({n})" for n in args.grids)]
    head += [f"adaptive ({grid})", f"strict ({grid})", "floor", "floor no jerk"]
    head += ["CPU jerk / adaptive / strict"]
    print("| " + " | ".join(head) + " |")
    print("|---|" + "---:|" * (len(head) - 1))
    for index, (obj, pick) in enumerate(cycle_picks(scenario, args.seed)):
        path = pick.path.path
        times = [retime(plant, path, no_jerk, gridpoints=grid).duration]
        cpu = []
        for n in args.grids:
            start = time.process_time()
            try:
                times.append(retime(plant, path, limits, gridpoints=n).duration)
            except RetimeError as error:  # said in the table, not hidden
                print(f"{obj.name}, {n} points: {error}")
                times.append(np.nan)
            cpu.append(time.process_time() - start)
        start = time.process_time()
        profile = retime_adaptive(plant, path, no_jerk, None)
        adaptive = adaptive_grid(profile.gridpoints, profile.sd, grid, ADAPTIVE_WEIGHT)
        times.append(retime(plant, path, limits, gridpoints=adaptive).duration)
        cpu.append(time.process_time() - start)
        with (
            mock.patch.object(jerk_module, "CONVERGED", 1e-6),
            mock.patch.object(jerk_module, "MAX_LPS", 60),
        ):
            start = time.process_time()
            times.append(retime(plant, path, limits, gridpoints=grid).duration)
            strict_cpu = time.process_time() - start
        floor, floor_bare = floors[index], bare[index]
        times.append(floor.retreat_s + floor.transit_s + floor.descent_s)
        times.append(floor_bare.retreat_s + floor_bare.transit_s + floor_bare.descent_s)
        spent = f"{cpu[0]:.2f} / {cpu[-1]:.2f} / {strict_cpu:.2f} s"
        cells = [f"{t:.3f}" for t in times] + [spent]
        print(f"| {obj.name} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
