"""Carry a carton that one suction cup cannot hold, with a tool of two cups.

What it shows: ``scenarios/carton_two_cups.yaml``, the paper's cell with a
tool of two paper cups 12 cm apart (20 N of suction each) and a 2.2 kg
carton, whose 21.6 N of weight is more than one cup's suction. The planner
finds the MOVE carrying the carton from the bin to the destination zone;
one cup is refused by the retimer before it moves (the carton slips even
at rest), and the tool's wrench set W_T (``GraspConstraint.for_tool``: the
cups' rims share the load as equal springs, as on a rigid tool) gives a
time-optimal MOVE that holds it. That MOVE is re-checked at 1 kHz and saved
as an ``.npz`` file recording both cups.

What it prints (one ``key: value`` per line):

- ``object``: the carton, its ``weight`` in N and the ``suction per cup``;
- ``one cup``: the retimer's refusal (a ``RetimeError``);
- ``tool rows``: the rows of the tool's set ``F w <= g``;
- ``duration with two cups``: the MOVE's duration, s;
- ``min margin``: the smallest margin to any limit found by the 1 kHz
  check, as a fraction of the limit (positive is room, negative over the
  limit; the contract is >= -0.001);
- ``check passed``: True when every limit and the tool's set hold;
- ``saved``: the ``.npz`` file written, and its samples.

How to run it::

    python examples/03_two_cup_tool.py             # writes ./two_cups.npz
    python examples/03_two_cup_tool.py out.npz     # or the file you name

It takes about 15 s on a busy 2-core machine (5 s of CPU).
"""

from __future__ import annotations

import sys

from rt_drake import (
    CyclePlanner,
    GraspConstraint,
    JointLimits,
    RetimeError,
    check_trajectory,
    held_object_of,
    load_scenario,
    make_arm_plant,
    retime,
    sample_trajectory,
    save_trajectory,
    scenarios_dir,
)

#: The scenarios shipped beside this folder in a checkout of rt-drake.
#: m/s^2, the plant's gravity.
GRAVITY = 9.81


def main(out: str = "two_cups.npz") -> None:
    """Plan the carton's MOVE, try one cup, retime under two, check and save."""
    scenario = load_scenario(scenarios_dir() / "carton_two_cups.yaml")
    (obj,) = scenario.objects
    tool = scenario.tool_parameters()  # two CupMounts: cup, R_TC, p_TC
    held = held_object_of(obj)  # its inertia in T
    print(f"object: {obj.name}")
    print(f"weight: {held.mass * GRAVITY:.2f} N")
    print(
        f"suction per cup: {', '.join(f'{m.cup.suction_force:g} N' for m in tool.cups)}"
    )

    planner = CyclePlanner(scenario, seed=0)
    approach = planner.plan_approach(planner.q_home, obj.name)
    reach = planner.plan_reach(approach.q_goal, obj.name)
    move = planner.plan_move(reach.q_goal, obj.name, reach=reach)

    # The plant's cup frame is the tool frame T, where held is expressed.
    plant = make_arm_plant(scenario)
    limits = JointLimits.from_plant(plant, scenario.robot)

    one_cup = GraspConstraint.for_cup(held, tool.cups[0].cup)
    try:
        retime(plant, move.path, limits, one_cup)
    except RetimeError as error:
        print(f"one cup: {type(error).__name__}: {error}")
    else:
        raise AssertionError("one cup held the carton")

    two_cups = GraspConstraint.for_tool(held, tool)
    result = retime(plant, move.path, limits, two_cups)
    check = check_trajectory(plant, result.trajectory, limits, two_cups)
    saved = sample_trajectory(
        plant, result, held, two_cups, tool, obj.name,
        move.path.waypoints, move.path.knots,
    )  # fmt: skip
    save_trajectory(out, saved)

    print(f"tool rows: {len(two_cups.g)}")
    print(f"duration with two cups: {result.duration:.4f} s")
    print(f"min margin: {check.min_margin():+.2e}")
    print(f"check passed: {check.passed()}")
    print(f"saved: {out} ({len(saved.t)} samples)")


if __name__ == "__main__":
    main(*sys.argv[1:2])
