"""The 1 kHz contract on paths whose knots bunch at their ends (the grid fix).

Each path: random joint steps from the test paths' home configuration (as
``tests/retiming/test_solve.py``'s contract test, 1 to 3 steps of up to 0.5
rad per joint, inside the position limits), its spline retimed with a held
object (100 points), that motion sampled at ``--count`` equal times: a
chord-length path whose knots bunch at both ends (from rest, q moves as t^2;
as ``tools/kto_reference.py`` sampled its KTO trajectory before it sampled by
chord length). The held object cycles through the notebook, carton box and
whetstone box of stack_four_objects_paper.yaml.

Each path is retimed three ways, with its object: ``given101`` on a given
grid of 101 uniform points, ``adaptive`` by
:func:`rt_drake.shaping.retime_adaptive` (the optimiser's final retime, on
its own grid), ``int100`` on 100 requested points; each twice, ``before``
(the grid as given: a piece of the path may keep one or two segments, as
``initial_grid`` did for explicit grids before the fix) and ``now``
(``MIN_PIECE_SEGMENTS`` segments in every piece). Every retime is checked at
1 kHz by :func:`rt_drake.check_trajectory` (Drake's route: body
accelerations + Newton-Euler). Printed per scheme and mode: paths, worst
margin (negative: over a limit), retimes over the 1e-3 contract, median grid
size, median duration against ``now`` and the mean CPU of a retime.

    OPENBLAS_NUM_THREADS=1 python tools/bunched_knots.py --paths 30 --seed 0
"""

from __future__ import annotations

import argparse
import time
from collections import defaultdict

import numpy as np

from rt_drake.model.held import held_object_of
from rt_drake.model.plant import make_arm_plant
from rt_drake.model.resources import scenarios_dir
from rt_drake.model.scenario import load_scenario
from rt_drake.retiming import (
    GraspConstraint,
    JointLimits,
    RetimeError,
    check_trajectory,
    retime,
)
from rt_drake.retiming import _solve as solve_module
from rt_drake.retiming import grid as grid_module
from rt_drake.shaping import retime_adaptive
from rt_drake.types.path import GeometricPath

HOME = np.array([0.0, 0.35, 1.75, 0.0, 1.04, 0.0])
OBJECTS = ("notebook", "carton_box", "whetstone_box")
GIVEN = np.linspace(0.0, 1.0, 101)


def as_given(gridpoints, knots):
    """``initial_grid`` as before the fix: an explicit grid's pieces unfilled."""
    if np.ndim(gridpoints) == 0:
        return grid_module.initial_grid(gridpoints, knots)
    kept = grid_module.MIN_PIECE_SEGMENTS
    grid_module.MIN_PIECE_SEGMENTS = 1  # no piece has fewer than one segment
    try:
        return grid_module.initial_grid(gridpoints, knots)
    finally:
        grid_module.MIN_PIECE_SEGMENTS = kept


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--paths", type=int, default=30)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--count", type=int, default=200)
    args = parser.parse_args()
    scenario = load_scenario(scenarios_dir() / "stack_four_objects_paper.yaml")
    plant = make_arm_plant(scenario)
    limits = JointLimits.from_plant(plant, scenario.robot)
    grasps = [
        GraspConstraint.for_cup(held_object_of(scenario.object(n)), scenario.cup)
        for n in OBJECTS
    ]
    lower, upper = plant.GetPositionLowerLimits(), plant.GetPositionUpperLimits()
    rng = np.random.default_rng(args.seed)
    schemes = {
        "given101": lambda path, grasp: retime(plant, path, limits, grasp, GIVEN),
        "adaptive": lambda path, grasp: retime_adaptive(plant, path, limits, grasp),
        "int100": lambda path, grasp: retime(plant, path, limits, grasp, 100),
    }
    # (scheme, mode) -> {path: (margin, duration, points, cpu)}
    found: dict[tuple[str, str], dict[int, tuple]] = defaultdict(dict)
    done = 0
    while done < args.paths:
        steps = rng.uniform(-0.5, 0.5, (int(rng.integers(1, 4)), 6))
        waypoints = np.cumsum(np.vstack([HOME, steps]), axis=0)
        spline = GeometricPath.from_waypoints(waypoints)
        q = spline.value(np.linspace(0.0, 1.0, 2001))
        if np.any(q < lower) or np.any(q > upper):
            continue
        grasp = grasps[done % len(grasps)]
        try:
            motion = retime(plant, waypoints, limits, grasp).trajectory
        except RetimeError:
            continue
        times = np.linspace(motion.start_time(), motion.end_time(), args.count)
        path = GeometricPath.from_waypoints(motion.sample(times, order=0)[0])
        done += 1
        for scheme, run in schemes.items():
            for mode, grid in (("before", as_given), ("now", grid_module.initial_grid)):
                solve_module.initial_grid = grid
                cpu = time.process_time()
                try:
                    result = run(path, grasp)
                except RetimeError as error:
                    print(f"path {done} {scheme} {mode}: {type(error).__name__}")
                    continue
                finally:
                    solve_module.initial_grid = grid_module.initial_grid
                cpu = time.process_time() - cpu
                check = check_trajectory(plant, result.trajectory, limits, grasp)
                margin = check.min_margin()
                found[scheme, mode][done] = (
                    margin,
                    result.duration,
                    len(result.gridpoints),
                    cpu,
                )
                if margin < -1e-3:
                    print(
                        f"path {done} ({OBJECTS[(done - 1) % 3]}, first knot "
                        f"{path.knots[1]:.1e}, last {1 - path.knots[-2]:.1e}) "
                        f"{scheme} {mode}: {check.summary().splitlines()[-1]}"
                    )
    print(
        f"{args.paths} paths, seed {args.seed}, {args.count} samples each\n"
        "scheme    mode    paths  worst margin %  over 1e-3  median points  "
        "duration/now  CPU ms"
    )
    for scheme in schemes:
        now = found[scheme, "now"]
        for mode in ("before", "now"):
            got = found[scheme, mode]
            rows = np.array(list(got.values()))
            ratio = [got[i][1] / now[i][1] for i in got if i in now]
            print(
                f"{scheme:9s} {mode:6s} {len(rows):6d} {100 * rows[:, 0].min():+15.3f}"
                f" {int(np.sum(rows[:, 0] < -1e-3)):10d} {np.median(rows[:, 2]):14.0f}"
                f" {np.median(ratio):13.5f} {1e3 * rows[:, 3].mean():7.1f}"
            )


if __name__ == "__main__":
    main()
