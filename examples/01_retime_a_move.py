"""Retime a MOVE of the shipped cell under the suction cup's grasp constraint.

What it shows: the offline pipeline on the paper's cell
(``scenarios/random_transport.yaml``: the Denso VS-060, the paper's cup and
the notebook, 0.55 kg). The planner finds a collision-free MOVE carrying the
notebook from the bin to the destination zone; the retimer makes it
time-optimal under the joint limits and the cup's exact wrench polytope
``F w <= g``; the trajectory is re-checked at 1 kHz by another route and
saved in rt-drake's ``.npz`` format, which anyone can re-check with
``load_trajectory``.

What it prints (one ``key: value`` per line):

- ``object``: the carried object;
- ``grasp rows``: the rows of ``F w <= g``;
- ``duration with grasp``, ``duration without grasp``: the MOVE's duration
  in s under joint limits and grasp, and under the joint limits alone;
- ``min margin``: the smallest margin to any limit found by the 1 kHz
  check, as a fraction of the limit (positive is room, negative over the
  limit; the contract is >= -0.001);
- ``check passed``: True when every limit and the grasp hold;
- ``min margin without grasp``: the same check of the faster motion
  retimed without the grasp: it asks more of the cup than it can give
  (< 0), the notebook would slip;
- ``saved``: the ``.npz`` file written, and its samples.

How to run it, from anywhere::

    python examples/01_retime_a_move.py            # writes ./move.npz
    python examples/01_retime_a_move.py out.npz    # or the file you name

It takes about 10 s on a busy 2-core machine (4 s of CPU).
"""

from __future__ import annotations

import sys

import numpy as np

from rt_drake import (
    CyclePlanner,
    GraspConstraint,
    JointLimits,
    check_trajectory,
    held_object_of,
    load_scenario,
    load_trajectory,
    make_arm_plant,
    retime,
    sample_trajectory,
    save_trajectory,
    scenarios_dir,
)

#: The scenarios shipped beside this folder in a checkout of rt-drake.
#: The object carried, and the seed of the planner's random search.
OBJECT, SEED = "notebook", 0


def main(out: str = "move.npz") -> None:
    """Plan, retime, check and save the MOVE of :data:`OBJECT`."""
    scenario = load_scenario(scenarios_dir() / "random_transport.yaml")
    obj = scenario.object(OBJECT)

    # The cycle up to the MOVE: approach above the box, reach down to
    # the grasp, then the MOVE carrying it to its goal on the stack.
    planner = CyclePlanner(scenario, seed=SEED)
    approach = planner.plan_approach(planner.q_home, obj.name)
    reach = planner.plan_reach(approach.q_goal, obj.name)
    move = planner.plan_move(reach.q_goal, obj.name, reach=reach)

    # The retimer's plant holds the arm and the tool (the path's joints);
    # the object's inertia is expressed in the cup frame C.
    plant = make_arm_plant(scenario)
    limits = JointLimits.from_plant(plant, scenario.robot)
    held = held_object_of(obj)
    grasp = GraspConstraint.for_cup(held, scenario.cup)
    result = retime(plant, move.path, limits, grasp)
    free = retime(plant, move.path, limits)

    check = check_trajectory(plant, result.trajectory, limits, grasp)
    free_check = check_trajectory(plant, free.trajectory, limits, grasp)
    saved = sample_trajectory(
        plant, result, held, grasp, scenario.cup, obj.name,
        move.path.waypoints, move.path.knots,
    )  # fmt: skip
    save_trajectory(out, saved)
    assert np.array_equal(load_trajectory(out).q, saved.q)

    print(f"object: {obj.name}")
    print(f"grasp rows: {len(grasp.g)}")
    print(f"duration with grasp: {result.duration:.4f} s")
    print(f"duration without grasp: {free.duration:.4f} s")
    print(f"min margin: {check.min_margin():+.2e}")
    print(f"check passed: {check.passed()}")
    print(f"min margin without grasp: {free_check.min_margin():+.2e}")
    print(f"saved: {out} ({len(saved.t)} samples)")


if __name__ == "__main__":
    main(*sys.argv[1:2])
