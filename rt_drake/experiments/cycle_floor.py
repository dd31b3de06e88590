"""The cycle's floor: how fast the arm's joint limits let any cycle go (issue 27).

For each object, in the cycle's order, the planner
(:class:`~rt_drake.planning.CyclePlanner`, the run's seed, the objects
before it at their goals) gives the configurations and vertical lines every
cycle of the scenario passes through, whatever its path shaping or
retiming: the rest configuration it starts from (home, or the last place),
the top of the retreat line above a placed object, the approach pose, the
grasp at the bottom of the descent line, the tops of the MOVE's lift and
set-down lines and the place. The object's motion floor is a sum of
segments in sequence, each bounded on its own by
:func:`rt_drake.retiming.segment_floor` (joint limits alone, no grasp):

- the retreat, from rest up to the top of its line (the top free);
- the transit from the top (or from rest) to the approach pose, each
  joint's speed at either end bounded by the line's tangent there
  (:func:`rt_drake.retiming.junction_speeds`: nearly at rest if it hardly
  moves on the line, at rest if it moves there against the transit);
- the descent, from the approach pose (free) to rest at the grasp;
- the MOVE's lift, from rest at the grasp up to the top of its line (free);
- the carry between the two lines' tops, the joints' speeds bounded at
  either end by the lines' tangents, as the transit's;
- the set-down, from the top of the place's line (free) to rest.

The MOVE's lines are the planner's (``PlannedPath.lines_m``); a shaped MOVE
(:class:`~rt_drake.shaping.MoveOptimizer`) runs only its own vertical ends
(``vertical_height``, 3 cm) straight, so with ``shaped`` each line counts up
to the lower of the two heights: every MOVE of the run, shaped or not,
passes through that line's top along the line. A line's top and its tangent
there come from the cup's IK on the line (the tangent over its last
``TANGENT_STEP_M``).

The report adds the object's ATTACH and DETACH times as run (the vacuum's,
which no motion changes) to make ``floor_s``, the fastest that object's
cycle could be with these configurations and limits.
"""

from __future__ import annotations

import dataclasses

import numpy as np
from pydrake.math import RigidTransform

from rt_drake.model.plant import make_arm_plant
from rt_drake.model.scenario import Scenario
from rt_drake.planning import CyclePlanner, PlanningError
from rt_drake.retiming import JointLimits, junction_speeds, segment_floor
from rt_drake.shaping import MoveOptimizerOptions
from rt_drake.types.phase import Phase

#: m, the step down a line over which its tangent at the top is taken.
TANGENT_STEP_M = 0.002


@dataclasses.dataclass(frozen=True)
class ObjectFloor:
    """The motion floor of one object (s), by segment (see the module docstring).

    Attributes:
        name: The object.
        retreat_s: The retreat up its line (0 for the first object).
        transit_s: From the retreat's top (or home) to the approach pose.
        descent_s: Down the descent line to the grasp.
        lift_s: The MOVE's lift up its line above the grasp.
        carry_s: The MOVE between its two lines' tops.
        set_down_s: The MOVE down its line to the place.
    """

    name: str
    retreat_s: float
    transit_s: float
    descent_s: float
    lift_s: float
    carry_s: float
    set_down_s: float

    @property
    def move_s(self) -> float:
        """The MOVE's floor, grasp to place (lift, carry, set-down), s."""
        return self.lift_s + self.carry_s + self.set_down_s

    @property
    def motion_s(self) -> float:
        """The sum of the segments, s."""
        return self.retreat_s + self.transit_s + self.descent_s + self.move_s


def cycle_floors(
    scenario: Scenario,
    seed: int = 0,
    jerk: np.ndarray | None = None,
    shaped: bool | None = None,
) -> tuple[ObjectFloor, ...]:
    """The motion floor of each object of ``scenario``'s cycle (module docstring).

    Args:
        scenario: The cell.
        seed: The planner's seed (the run's).
        jerk: Joint jerk limits (rad/s^3) for the rest-to-rest segments, or
            None (velocity and acceleration only).
        shaped: Whether the run shapes its MOVEs (None: the scenario's
            ``planning.optimize_move``): the MOVE's lines then count up to
            the shaped path's vertical ends.

    Raises:
        PlanningError: a pick or MOVE could not be planned, or a point of a
            MOVE's line has no IK solution.
    """
    plant = make_arm_plant(scenario)
    limits = JointLimits.from_plant(plant, scenario.robot)
    planner = CyclePlanner(scenario, seed=seed)
    if shaped is None:
        shaped = scenario.planning.optimize_move
    cap = np.inf
    if shaped:
        cap = MoveOptimizerOptions.from_config(scenario.planning).vertical_height
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
        assert move.lines_m is not None  # plan_move sets it
        lift_m, set_down_m = (min(h, cap) for h in move.lines_m)
        q_place = move.q_goal
        q_up, step_up = _line_top(planner, q_grasp, lift_m, obj.name)
        q_down, step_down = _line_top(planner, q_place, set_down_m, obj.name)
        carry = q_down - q_up
        carry_from = junction_speeds(step_up, carry, limits)
        carry_to = junction_speeds(step_down, -carry, limits)
        floors.append(
            ObjectFloor(
                obj.name,
                retreat_s,
                transit_s,
                descent_s,
                lift_s=segment_floor(q_grasp, q_up, limits, 0.0, np.inf, jerk),
                carry_s=segment_floor(q_up, q_down, limits, carry_from, carry_to, jerk),
                set_down_s=segment_floor(q_down, q_place, limits, np.inf, 0.0, jerk),
            )
        )
        q_from = q_place
    return tuple(floors)


def _line_top(
    planner: CyclePlanner, q_end: np.ndarray, height: float, name: str
) -> tuple[np.ndarray, np.ndarray]:
    """The top (rad) of the vertical line ``height`` m above the cup at ``q_end``.

    With the line's joint motion over its last ``TANGENT_STEP_M`` up to the
    top (rad: its tangent there, upward). A line of height 0: ``q_end`` and
    a zero step (the joints at rest there).
    """
    if height <= 0.0:
        return q_end, np.zeros_like(q_end)
    X_WC = planner.scene.cup_pose(q_end)
    points: list[np.ndarray] = []
    for h in (height - min(TANGENT_STEP_M, height), height):
        X_up = RigidTransform(X_WC.rotation(), X_WC.translation() + [0.0, 0.0, h])
        q = planner.ik.solve(X_up, q_end, q_end if not points else points[-1])
        if q is None:
            raise PlanningError(
                Phase.MOVE, name, f"floor: no IK {1e3 * h:.0f} mm above the cup"
            )
        points.append(q)
    return points[1], points[1] - points[0]


__all__ = ["ObjectFloor", "cycle_floors"]
