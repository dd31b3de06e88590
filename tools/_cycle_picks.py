"""The cycle's blended picks, planned in order as ``rt-drake run`` plans them.

Also :func:`jerk_cell`, the scenario, arm and jerk limits the pick studies
(``pick_jerk_cost.py``, ``jerk_grid_study.py``) read from their arguments.
"""

from __future__ import annotations

import argparse
from collections.abc import Iterator

from rt_drake.errors import RtDrakeError
from rt_drake.model.plant import make_arm_plant
from rt_drake.model.resources import resolve_scenario_path
from rt_drake.model.scenario import load_scenario
from rt_drake.planning import CyclePlanner
from rt_drake.retiming import JointLimits


def jerk_cell(parser: argparse.ArgumentParser, name: str):  # noqa: ANN201
    """``(scenario, plant, limits)`` of the scenario ``name``, limits with jerk.

    A scenario that does not load, or has no ``robot.jerk_limits``, ends the
    tool in one line (``parser.error``, exit 2).
    """
    try:
        scenario = load_scenario(resolve_scenario_path(name))
    except RtDrakeError as error:
        parser.error(str(error))
    if not scenario.robot.jerk_limits:
        parser.error(f"{name}: robot.jerk_limits is empty (no jerk cost)")
    plant = make_arm_plant(scenario)
    return scenario, plant, JointLimits.from_plant(plant, scenario.robot, jerk=True)


def cycle_picks(scenario, seed: int) -> Iterator[tuple[object, object]]:  # noqa: ANN001
    """``(object, pick)`` for each object of ``scenario``, in order.

    The objects already placed stand at their goals, the others at their
    starts; each pick starts where the last MOVE ended (the first from
    home). ``pick`` is ``CyclePlanner.plan_pick``'s (its ``path.path`` the
    blended pick's geometric path).
    """
    planner = CyclePlanner(scenario, seed=seed)
    q = planner.q_home
    for index, obj in enumerate(scenario.objects):
        for k, other in enumerate(scenario.objects):
            pose = other.goal if k < index else other.start
            planner.set_object_pose(other.name, pose.GetDeterministicValue())
        pick = planner.plan_pick(q, obj.name, index > 0)
        yield obj, pick
        q = planner.plan_move(pick.path.q_goal, obj.name, reach=pick.path).q_goal
