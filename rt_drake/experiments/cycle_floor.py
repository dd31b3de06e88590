"""The cycle's floor: how fast the arm's joint limits let any cycle go (issue 27).

For each object, in the cycle's order, the planner
(:class:`~rt_drake.planning.CyclePlanner`, the run's seed, the objects
before it at their goals) gives the configurations every cycle of the
scenario passes through, whatever its path shaping or retiming: the rest
configuration it starts from (home, or the last place), the top of the
retreat line above a placed object, the approach pose, the grasp at the
bottom of the descent line and the place. The object's motion floor is a
sum of segments in sequence, each bounded on its own by
:func:`rt_drake.retiming.segment_floor` (joint limits alone, no grasp):

- the retreat, from rest up to the top of its line (the top free);
- the transit from the top (or from rest) to the approach pose, each
  joint's speed at either end bounded by the line's tangent there
  (:func:`rt_drake.retiming.junction_speeds`: nearly at rest if it hardly
  moves on the line, at rest if it moves there against the transit);
- the descent, from the approach pose (free) to rest at the grasp;
- the MOVE, rest to rest from grasp to place (its vertical ends left out,
  so the bound is lower still).

The report adds the object's ATTACH and DETACH times as run (the vacuum's,
which no motion changes) to make ``floor_s``, the fastest that object's
cycle could be with these configurations and limits.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from rt_drake.model.plant import make_arm_plant
from rt_drake.model.scenario import Scenario
from rt_drake.planning import CyclePlanner
from rt_drake.retiming import JointLimits, junction_speeds, segment_floor


@dataclasses.dataclass(frozen=True)
class ObjectFloor:
    """The motion floor of one object (s), by segment (see the module docstring).

    Attributes:
        name: The object.
        retreat_s: The retreat up its line (0 for the first object).
        transit_s: From the retreat's top (or home) to the approach pose.
        descent_s: Down the descent line to the grasp.
        move_s: The MOVE, grasp to place.
    """

    name: str
    retreat_s: float
    transit_s: float
    descent_s: float
    move_s: float

    @property
    def motion_s(self) -> float:
        """The sum of the segments, s."""
        return self.retreat_s + self.transit_s + self.descent_s + self.move_s


def cycle_floors(
    scenario: Scenario, seed: int = 0, jerk: np.ndarray | None = None
) -> tuple[ObjectFloor, ...]:
    """The motion floor of each object of ``scenario``'s cycle (module docstring).

    Args:
        scenario: The cell.
        seed: The planner's seed (the run's).
        jerk: Joint jerk limits (rad/s^3) for the rest-to-rest segments, or
            None (velocity and acceleration only).

    Raises:
        PlanningError: a pick or MOVE could not be planned.
    """
    plant = make_arm_plant(scenario)
    limits = JointLimits.from_plant(plant, scenario.robot)
    planner = CyclePlanner(scenario, seed=seed)
    q_from = planner.q_home
    floors = []
    for index, obj in enumerate(scenario.objects):
        for k, other in enumerate(scenario.objects):
            pose = other.goal if k < index else other.start
            planner.set_object_pose(other.name, pose.GetDeterministicValue())
        retreat = index > 0
        pick = planner.plan_pick(q_from, obj.name, retreat)
        path = pick.path.path
        descent = np.asarray(pick.path.descent)
        q_top = path.value(pick.s_retreat).ravel()
        q_approach = descent[0]
        q_grasp = descent[-1]
        transit = q_approach - q_top
        speed_end = junction_speeds(-(descent[1] - descent[0]), -transit, limits)
        if retreat:
            line = path.value(np.linspace(0.0, pick.s_retreat, 20))
            speed_start = junction_speeds(line[-1] - line[-2], transit, limits)
            retreat_s = segment_floor(q_from, q_top, limits, 0.0, np.inf, jerk)
        else:
            speed_start, retreat_s = np.zeros(len(transit)), 0.0
        transit_s = segment_floor(
            q_top, q_approach, limits, speed_start, speed_end, jerk
        )
        descent_s = segment_floor(q_approach, q_grasp, limits, np.inf, 0.0, jerk)
        move = planner.plan_move(q_grasp, obj.name, reach=pick.path)
        move_s = segment_floor(q_grasp, move.q_goal, limits, 0.0, 0.0, jerk)
        floors.append(ObjectFloor(obj.name, retreat_s, transit_s, descent_s, move_s))
        q_from = move.q_goal
    return tuple(floors)


__all__ = ["ObjectFloor", "cycle_floors"]
