"""The retimer's contract on coarse grids: every limit within 1e-3 at 1 kHz.

Retimes the three paths of ``tests/retiming/test_solve.py`` and 12 seeded
random paths (as in its contract test: HOME plus 1-4 steps of up to 0.5 rad
per joint, inside the position limits), each with the notebook, the carton
box and the whetstone box, on grids of the given sizes, and checks each
trajectory at 1 kHz by ``check_trajectory`` (its own route: body
accelerations and Newton-Euler). Prints per grid size how many of the
retimes exceed the 1e-3 contract and the worst excess per constraint.

    OPENBLAS_NUM_THREADS=1 python tools/coarse_grid_contract.py 8 12 20 30 100
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from rt_drake import CupFrame, load_scenario, make_arm_plant
from rt_drake.model.held import held_object_of
from rt_drake.model.resources import resolve_scenario_path
from rt_drake.retiming import (
    GraspConstraint,
    JointLimits,
    Margin,
    RetimeError,
    check_trajectory,
    retime,
)

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "retiming"))
from test_solve import HOME, OBJECTS, PATHS  # noqa: E402

RANDOM_PATHS = 12


def paths(plant) -> list[np.ndarray]:
    """The test paths, then seeded random ones inside the position limits."""
    rng = np.random.default_rng(0)
    out = [np.array(p) for p in PATHS.values()]
    low, high = plant.GetPositionLowerLimits(), plant.GetPositionUpperLimits()
    while len(out) < len(PATHS) + RANDOM_PATHS:
        steps = rng.uniform(-0.5, 0.5, (int(rng.integers(1, 5)), 6))
        path = np.cumsum(np.vstack([HOME, steps]), axis=0)
        if np.all(path > low + 0.1) and np.all(path < high - 0.1):
            out.append(path)
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("gridpoints", type=int, nargs="+")
    args = parser.parse_args()
    scenario = load_scenario(resolve_scenario_path("stack_four_objects"))
    plant = make_arm_plant(scenario)
    limits = JointLimits.from_plant(plant, scenario.robot)
    cup, context = CupFrame.of(plant), plant.CreateDefaultContext()
    grasps = [
        GraspConstraint.for_cup(held_object_of(scenario.object(name)), scenario.cup)
        for name in OBJECTS
    ]
    for count in args.gridpoints:
        worst = {"velocity": 0.0, "acceleration": 0.0, "grasp": 0.0}
        over = total = 0
        for path in paths(plant):
            for grasp in grasps:
                try:
                    result = retime(
                        plant, path, limits, grasp, count, context=context, cup=cup
                    )
                except RetimeError:
                    continue
                check = check_trajectory(
                    plant, result.trajectory, limits, grasp, context=context
                )
                total += 1
                over += -check.min_margin() > 1e-3
                for key in worst:
                    worst[key] = max(worst[key], -check.margins[Margin(key)].value)
        text = ", ".join(f"{k} {100 * v:+.3f} %" for k, v in worst.items())
        print(f"{count} points: {over} of {total} over the contract; worst {text}")


if __name__ == "__main__":
    main()
