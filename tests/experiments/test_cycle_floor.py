"""The cycle's floor is a lower bound: no planned motion through its lines beats it.

The planner's own picks (retreat, transit and descent blended in one path)
and MOVEs of the shipped cycle, as ``rt-drake run`` plans them, retimed at
the joint limits without the grasp by toppra (an independent TOPP-RA), take
at least the floor of their segments, the MOVE's vertical lift and
set-down lines counted. The MOVE's lines are checked by forward kinematics
(their tops straight above the grasp and the place, by the planner's
heights) and its lift against the per-joint ramp written out here.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from pydrake.math import RigidTransform
from toppra_reference import toppra_duration

from rt_drake import CyclePlanner, JointLimits
from rt_drake.experiments import cycle_floors
from rt_drake.model.plant import make_arm_plant
from rt_drake.retiming import GraspConstraint, retime
from rt_drake.shaping import MoveOptimizerOptions, optimize_move
from rt_drake.simulation.move_grasp import held_object, move_polytope

#: Relative slack for toppra's grid (its duration on 2000 points).
GRID_SLACK = 2e-3


@pytest.fixture(scope="module")
def cycle(scenario):
    """The floors and, per object, the planner's pick and MOVE (seed 0)."""
    floors = cycle_floors(scenario, seed=0, shaped=False)
    planner = CyclePlanner(scenario, seed=0)
    q = planner.q_home
    plans = []
    for index, obj in enumerate(scenario.objects):
        for k, other in enumerate(scenario.objects):
            pose = other.goal if k < index else other.start
            planner.set_object_pose(other.name, pose.GetDeterministicValue())
        pick = planner.plan_pick(q, obj.name, retreat=index > 0)
        move = planner.plan_move(pick.path.q_goal, obj.name, reach=pick.path)
        plans.append((pick, move))
        q = move.q_goal
    plant = make_arm_plant(scenario)
    return floors, plans, JointLimits.from_plant(plant, scenario.robot), planner


@pytest.mark.slow
def test_no_planned_motion_through_the_lines_beats_its_floor(cycle):
    floors, plans, limits, _ = cycle
    assert [f.name for f in floors] == [pick.path.object for pick, _ in plans]
    for floor, (pick, move) in zip(floors, plans, strict=True):
        pick_floor = floor.retreat_s + floor.transit_s + floor.descent_s
        assert toppra_duration(pick.path.path, limits) >= pick_floor * (1 - GRID_SLACK)
        assert toppra_duration(move.path, limits) >= floor.move_s * (1 - GRID_SLACK)
        assert floor.transit_s > 0.0 and floor.descent_s > 0.0


def test_the_move_floor_counts_its_vertical_lines(cycle, scenario):
    """lift_s: the slowest joint's time from rest to the line's top.

    The top is found here by the planner's IK and checked by forward
    kinematics: the cup ``lines_m[0]`` straight above the grasp, same
    orientation. There every joint moves along the line's tangent ``delta``
    (one-sided, to second order, from points 2 and 4 mm below) at one speed,
    so joint j is at most ``u_j = |delta_j| min_k v_k / |delta_k|`` fast.
    Per joint, from rest over d, the larger of the time to a free end (``d
    / v + v / (2 a)`` if ``d >= v^2 / (2 a)``, else ``sqrt(2 d / a)``) and
    the time to rest (``d / v + v / a`` if ``d >= v^2 / a``, else ``2
    sqrt(d / a)``) less ``u / a``.
    """
    floors, plans, limits, _ = cycle
    planner = CyclePlanner(scenario, seed=0)
    v, a = limits.velocity, limits.acceleration
    for floor, (_, move) in zip(floors, plans, strict=True):
        lift_m, set_down_m = move.lines_m
        assert lift_m > 0.0 and set_down_m > 0.0
        X_grasp = planner.scene.cup_pose(move.q_start)
        tops = [move.q_start]
        for h in (lift_m - 0.004, lift_m - 0.002, lift_m):
            X_top = RigidTransform(
                X_grasp.rotation(), X_grasp.translation() + [0.0, 0.0, h]
            )
            q_top = planner.ik.solve(X_top, move.q_start, tops[-1])
            X_found = planner.scene.cup_pose(q_top)
            assert np.allclose(X_found.translation(), X_top.translation(), atol=1e-5)
            tops.append(q_top)
        delta = 1.5 * tops[3] - 2.0 * tops[2] + 0.5 * tops[1]
        d = tops[3] - move.q_start
        u = np.abs(delta) * np.min(v / np.abs(delta))
        u = np.where(delta * d > 0, u, 0.0)
        d = np.abs(d)
        free = np.where(d >= v * v / (2 * a), d / v + v / (2 * a), np.sqrt(2 * d / a))
        rest = np.where(d >= v * v / a, d / v + v / a, 2 * np.sqrt(d / a))
        times = np.maximum(free, rest - u / a)
        assert floor.lift_s == pytest.approx(times.max(), rel=1e-3)  # IK solves
        assert floor.move_s == floor.lift_s + floor.carry_s + floor.set_down_s
        assert floor.carry_s > 0.0 and floor.set_down_s > 0.0


@pytest.mark.slow
def test_no_jerk_limited_retime_through_the_lines_beats_its_jerk_floor(cycle, scenario):
    """The planner's picks and MOVEs retimed by the retimer under the
    scenario's jerk limits (no grasp) take at least the floor with the jerk,
    whose bound lies above the one without (by the jerk's share)."""
    floors, plans, limits, _ = cycle
    jerk = np.array(scenario.robot.jerk_limits or 20.0 * limits.acceleration)
    with_jerk = cycle_floors(scenario, seed=0, jerk=jerk, shaped=False)
    jerk_limits = dataclasses.replace(limits, jerk=jerk)
    plant = make_arm_plant(scenario)
    for floor, bare, (pick, move) in zip(with_jerk, floors, plans, strict=True):
        pick_floor = floor.retreat_s + floor.transit_s + floor.descent_s
        assert retime(plant, pick.path.path, jerk_limits).duration >= pick_floor
        assert retime(plant, move.path, jerk_limits).duration >= floor.move_s
        assert floor.motion_s > bare.motion_s + 0.05


@pytest.mark.slow
def test_a_shaped_move_through_its_short_ends_does_not_beat_its_floor(cycle, scenario):
    """The last MOVE (the carton's: 0.26 m lines) shaped, its ends 3 cm.

    With ``shaped`` the floor counts each line up to the shaped path's 3 cm
    vertical ends; that path, retimed by toppra without the grasp, takes
    at least that floor, while the full lines' floor is above it.
    """
    floors, plans, limits, planner = cycle
    obj = scenario.objects[-1]
    _, move = plans[-1]
    plant = make_arm_plant(scenario)
    grasp = GraspConstraint.for_polytope(
        held_object(obj, move.X_OC), move_polytope(scenario)
    )
    options = MoveOptimizerOptions.from_config(scenario.planning)
    shaped = optimize_move(
        planner, plant, move.q_start, obj.name, grasp, limits, options, spline=move
    )
    assert shaped.improved
    floor = cycle_floors(scenario, seed=0, shaped=True)[-1]
    full = floors[-1]  # the fixture's: the full lines (shaped=False)
    assert toppra_duration(shaped.path, limits) >= floor.move_s * (1 - GRID_SLACK)
    assert full.move_s > floor.move_s
