"""The shaped pick against the blended pick and the floor, per object (issue 27).

    python tools/pick_shape.py [SCENARIO] [--seed N] [--evaluations N]

For each object of the cycle, the blended pick the planner gives (retreat,
transit and descent in one path, as ``rt-drake run`` plays every pick but
the staged first; the first object's from home, without a retreat) is
shaped by :func:`rt_drake.shaping.shape_pick` (the MOVE's optimiser, no
grasp) and both paths are retimed as the cycle retimes a pick
(``OnlineMotions.retime_free``: the acceleration limits on the adaptive
grid, then, with the scenario's jerk limits, 100 points placed by that
profile). Printed per object (s): the blended and shaped durations without
and with jerk (the finish kept the fastest at the acceleration limits),
the shaped pick as the cycle shapes it (``played``: the finish keeps the
fastest as played, under the jerk limits), their ratios, the floor of the
pick's segments (retreat,
transit, descent: :mod:`rt_drake.experiments.cycle_floor`) with and without
jerk, the shaping's CPU (``time.process_time``), the candidates scored and
why better ones were turned down.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import time

import numpy as np

from rt_drake.experiments import cycle_floors
from rt_drake.model.resources import resolve_scenario_path
from rt_drake.model.scenario import load_scenario
from rt_drake.shaping import MoveOptimizer, MoveOptimizerOptions, shape_pick
from rt_drake.simulation import OnlineMotions


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenario", nargs="?", default="stack_four_objects")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--evaluations", type=int, default=None)
    parser.add_argument("--options", default="{}", help="MoveOptimizerOptions (JSON)")
    args = parser.parse_args()
    scenario = load_scenario(resolve_scenario_path(args.scenario))
    jerk = np.array(scenario.robot.jerk_limits) if scenario.robot.jerk_limits else None
    floors = cycle_floors(scenario, args.seed, jerk=jerk, shaped=True)
    bare = cycle_floors(scenario, args.seed, shaped=True)
    motions = OnlineMotions(
        scenario, seed=args.seed, optimize=False, jerk_limits=jerk is not None
    )
    planner = motions.planner
    options = MoveOptimizerOptions.from_config(scenario.planning)
    if args.evaluations is not None:
        options = dataclasses.replace(options, max_evaluations=args.evaluations)
    options = dataclasses.replace(options, **json.loads(args.options))
    plant = motions._plant  # noqa: SLF001 - a study of the cycle's own retimer
    optimizer = MoveOptimizer(
        plant,
        motions._limits.without_jerk(),
        options,
        motions._cup,  # noqa: SLF001
    )
    head = "| object | blended | shaped | ratio | blended jerk | shaped jerk | ratio "
    head += "| shaped as played | ratio | floor | floor no jerk | CPU | paths "
    head += "| rejected |"
    print(head)
    print("|---|" + "---:|" * 12 + "---|")

    def replay(path, profile):
        return motions.retime_free(path, profile=profile)

    q = planner.q_home
    ratios = []
    for index, obj in enumerate(scenario.objects):
        motions._place_objects_for(obj)  # noqa: SLF001
        pick = planner.plan_pick(q, obj.name, index > 0)
        shaped = shape_pick(optimizer, planner, pick)  # acceleration-limited finish
        found = shaped.optimized
        times = [found.spline_duration, found.duration]
        for planned in (pick, shaped.pick):
            times.append(motions.retime_free(planned.path.path).duration)
        start = time.process_time()  # the finish as the cycle runs it
        played = shape_pick(optimizer, planner, pick, played=replay).optimized
        cpu = time.process_time() - start
        times.append((played.played or played.spline_played).duration)
        floor, floor_bare = floors[index], bare[index]
        floor_s = floor.retreat_s + floor.transit_s + floor.descent_s
        bare_s = floor_bare.retreat_s + floor_bare.transit_s + floor_bare.descent_s
        ratios.append(times[4] / times[2])
        cells = [
            f"{times[0]:.3f}",
            f"{times[1]:.3f}",
            f"{times[1] / times[0]:.3f}",
            f"{times[2]:.3f}",
            f"{times[3]:.3f}",
            f"{times[3] / times[2]:.3f}",
            f"{times[4]:.3f}",
            f"{times[4] / times[2]:.3f}",
            f"{floor_s:.3f}",
            f"{bare_s:.3f}",
            f"{cpu:.2f} s",
            str(played.evaluations),
            "; ".join(played.rejected) or "-",
        ]
        print(f"| {obj.name} | " + " | ".join(cells) + " |")
        q = planner.plan_move(pick.path.q_goal, obj.name, reach=pick.path).q_goal
    median = np.median(ratios[1:])
    print(f"as played, median over the picks after a place: {median:.3f}")


if __name__ == "__main__":
    main()
