"""The cycle's blended picks, planned in order as ``rt-drake run`` plans them."""

from __future__ import annotations

from collections.abc import Iterator

from rt_drake.planning import CyclePlanner


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
