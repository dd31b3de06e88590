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

- the retreat, from rest up to the top of its line;
- the transit from the top (or from rest) to the approach pose;
- the descent, from the approach pose to rest at the grasp;
- the MOVE's lift, from rest at the grasp up to the top of its line;
- the carry between the two lines' tops;
- the set-down, from the top of the place's line to rest.

Where a segment meets a line, each joint's speed and acceleration there are
bounded by the line's tangent and bend
(:func:`rt_drake.retiming.junction_speeds`,
:func:`rt_drake.retiming.junction_accelerations`: nearly at rest if it
hardly moves on the line, J1 on every line of this arm; a speed at most 0
toward the goal if it moves there against the segment); at rest, both are
0. With jerk limits each joint's bound is the jerk-limited one from those
end states (:func:`rt_drake.retiming.joint_floor`).

The MOVE's lines are the planner's (``PlannedPath.lines_m``); a shaped MOVE
(:class:`~rt_drake.shaping.MoveOptimizer`) runs only its own vertical ends
(``vertical_height``, 3 cm) straight, so with ``shaped`` each line counts up
to the lower of the two heights: every MOVE of the run, shaped or not,
passes through that line's top along the line. A line's top, its tangent
and its bend there come from the cup's IK on the line (three points
``TANGENT_STEP_M`` apart).

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
from rt_drake.retiming import (
    JointLimits,
    junction_accelerations,
    junction_speeds,
    segment_floor,
)
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
        jerk: Joint jerk limits (rad/s^3), or None (velocity and
            acceleration only).
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
        descent = np.asarray(pick.path.descent)
        q_approach, q_grasp = descent[0], descent[-1]
        down = (-2 * TANGENT_STEP_M, -TANGENT_STEP_M, 0.0)  # the approach last
        approach = _Line(_vertical(planner, q_approach, down, obj.name), True)
        if retreat:
            up = pick.path.path.value(np.linspace(0.0, pick.s_retreat, 20))
            top: _Line | None = _Line(up, leaving=False)
            q_top = up[-1]
            retreat_s = _floor(q_from, q_top, None, top, limits, jerk)
        else:
            top, q_top, retreat_s = None, q_from, 0.0
        move = planner.plan_move(q_grasp, obj.name, reach=pick.path)
        assert move.lines_m is not None  # plan_move sets it
        lift_m, set_down_m = (min(h, cap) for h in move.lines_m)
        q_place = move.q_goal
        lift = _Line(_line_top(planner, q_grasp, lift_m, obj.name), leaving=False)
        set_down = _Line(_line_top(planner, q_place, set_down_m, obj.name), True)
        q_up, q_down = lift.points[-1], set_down.points[-1]
        floors.append(
            ObjectFloor(
                obj.name,
                retreat_s,
                transit_s=_floor(q_top, q_approach, top, approach, limits, jerk),
                descent_s=_floor(q_approach, q_grasp, approach, None, limits, jerk),
                lift_s=_floor(q_grasp, q_up, None, lift, limits, jerk),
                carry_s=_floor(q_up, q_down, lift, set_down, limits, jerk),
                set_down_s=_floor(q_down, q_place, set_down, None, limits, jerk),
            )
        )
        q_from = q_place
    return tuple(floors)


@dataclasses.dataclass(frozen=True)
class _Line:
    """The end of a vertical line where a segment meets it.

    Attributes:
        points: (k >= 3, n) joint positions (rad) at equal steps along the
            line, the junction last.
        leaving: Whether the arm travels away from the junction along the
            line (down the descent, down the set-down line) rather than
            toward it (up the retreat and the lift).
    """

    points: np.ndarray

    leaving: bool

    def bounds(
        self, displacement: np.ndarray, limits: JointLimits
    ) -> tuple[np.ndarray, np.ndarray]:
        """(speeds, accelerations): each joint's bounds at the junction.

        Toward the goal of the segment's ``displacement`` (rad), by
        :func:`~rt_drake.retiming.junction_speeds` (the line's tangent at the
        junction, one-sided to second order, in its direction of travel) and
        :func:`~rt_drake.retiming.junction_accelerations`.
        """
        p0, p1, p2 = self.points[-3:]
        step = 1.5 * p2 - 2.0 * p1 + 0.5 * p0  # the tangent, to second order
        speeds = junction_speeds(-step if self.leaving else step, displacement, limits)
        return speeds, junction_accelerations(self.points[-3:], limits)


def _floor(
    q_from: np.ndarray,
    q_to: np.ndarray,
    start: _Line | None,
    end: _Line | None,
    limits: JointLimits,
    jerk: np.ndarray | None,
) -> float:
    """The floor (s) of one segment, each end at rest (None) or on a line."""
    at_rest = (np.zeros_like(q_from), np.zeros_like(q_from))
    (u0, a0), (u1, a1) = (
        at_rest if line is None else line.bounds(q_to - q_from, limits)
        for line in (start, end)
    )
    return segment_floor(q_from, q_to, limits, u0, u1, jerk, a0, a1)


def _line_top(
    planner: CyclePlanner, q_end: np.ndarray, height: float, name: str
) -> np.ndarray:
    """(3, n) joints (rad) up to the top of the line ``height`` m above ``q_end``.

    At the line's top and ``TANGENT_STEP_M`` and twice that below it (the
    top last), :func:`_vertical`; on a line shorter than ``2
    TANGENT_STEP_M`` the steps shrink to half its height. A line of height
    0: ``q_end`` three times (the joints at rest there).
    """
    step = min(TANGENT_STEP_M, height / 2)
    heights = (height - 2 * step, height - step, height)
    return _vertical(planner, q_end, heights, name) if height > 0.0 else (
        np.array([q_end] * 3))  # fmt: skip


def _vertical(
    planner: CyclePlanner, q: np.ndarray, heights: tuple[float, ...], name: str
) -> np.ndarray:
    """(k, n) joints (rad): the cup at ``q`` raised by each height (m) in turn.

    The cup's IK, each solve seeded by the previous point (``q`` first); a
    height of 0 is ``q`` itself. Equal steps of height give
    :func:`~rt_drake.retiming.junction_accelerations` its points.

    Raises:
        PlanningError: a point has no IK solution.
    """
    X_WC = planner.scene.cup_pose(q)
    points = [q]
    for h in heights:
        if h == 0.0:
            points.append(q)
            continue
        X_up = RigidTransform(X_WC.rotation(), X_WC.translation() + [0.0, 0.0, h])
        solution = planner.ik.solve(X_up, q, points[-1])
        if solution is None:
            raise PlanningError(
                Phase.MOVE,
                name,
                f"floor: no IK {1e3 * h:+.0f} mm vertically from the cup",
            )
        points.append(solution)
    return np.array(points[1:])


__all__ = ["ObjectFloor", "cycle_floors"]
