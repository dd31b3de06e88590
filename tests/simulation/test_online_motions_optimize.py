"""OnlineMotions with MOVE optimisation (issues 13, 27): the wiring, not the search."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from rt_drake import CyclePlanner, JointLimits, OnlineMotions, make_arm_plant, retime
from rt_drake.model.scenario import (
    PlanningConfig,
    load_scenario,
)
from rt_drake.shaping import (
    MoveOptimizer,
    MoveOptimizerOptions,
)


@pytest.mark.slow
def test_optimised_move_is_never_slower_than_the_spline_move(scenario_paths):
    scenario = load_scenario(scenario_paths["random_transport"])
    scenario = dataclasses.replace(
        scenario, planning=PlanningConfig(optimize_move=True, max_evaluations=60)
    )
    obj = scenario.objects[0]
    optimised = OnlineMotions(scenario, seed=3)
    spline = OnlineMotions(scenario, seed=3, optimize=False)
    motions = []
    for source in (optimised, spline):
        approach = source.approach(source.q_home, obj)
        reach = source.reach(approach.q_end, obj)
        motions.append(source.move(reach.q_end, obj, reach))
    move, reference = motions
    assert move.planned is not None and reference.planned is not None
    # Same ends; the spline MOVE retimed as the optimiser retimes.
    np.testing.assert_array_equal(move.planned.q_start, reference.planned.q_start)
    np.testing.assert_array_equal(move.planned.q_goal, reference.planned.q_goal)
    assert move.grasp is not None and move.retimed is not None
    plant = make_arm_plant(scenario)
    limits = JointLimits.from_plant(plant, scenario.robot)
    options = MoveOptimizerOptions.from_config(scenario.planning)
    optimizer = MoveOptimizer(plant, limits, options)
    baseline = optimizer.retime(reference.planned.path, move.grasp)
    assert move.retimed.duration <= baseline.duration
    assert move.duration == pytest.approx(move.retimed.duration)
    # The search counts as planning, the final retime as retiming.
    assert move.times.plan_s > 0.0 and move.times.retime_s > 0.0
    # Shaped, and by a margin: 0.872 of the spline path on the same grid
    # (60 paths scored, deterministic); the fallback's 1.0 fails.
    assert move.retimed.duration <= 0.92 * baseline.duration


@pytest.mark.slow
def test_no_optimize_plays_the_planners_spline_move_bit_for_bit(scenario_paths):
    """optimize=False: the planner's MOVE, retimed as before (100 points),
    and the planner's blended picks, not shaped."""
    scenario = load_scenario(scenario_paths["stack_four_objects"])
    assert scenario.planning.optimize_move  # the shipped cycle shapes by default
    obj = scenario.objects[0]
    spline = OnlineMotions(scenario, seed=0, optimize=False, split_first_pick=False)
    pick = spline.pick(spline.q_home, obj)  # the blended pick, as plan_pick's
    move = spline.move(pick.q_end, obj, pick)
    # The same MOVE from the planner itself, and the retimer called directly.
    planner = CyclePlanner(scenario, seed=0)
    planned_pick = planner.plan_pick(planner.q_home, obj.name)
    reference = planner.plan_move(pick.q_end, obj.name, reach=planned_pick.path)
    assert move.planned is not None and move.grasp is not None
    np.testing.assert_array_equal(move.planned.path.waypoints, reference.path.waypoints)
    plant = make_arm_plant(scenario)
    limits = JointLimits.from_plant(plant, scenario.robot)
    retimed = retime(plant, reference.path, limits, move.grasp, gridpoints=100)
    assert move.duration == retimed.duration
    # The picks are the planner's blended picks, unshaped: the first from
    # home and the next after the place, retimed as any pick.
    assert pick.planned is not None
    np.testing.assert_array_equal(
        pick.planned.path.waypoints, planned_pick.path.path.waypoints
    )
    assert pick.duration == spline.retime_free(planned_pick.path.path).duration
    after = scenario.objects[1]
    second = spline.pick(move.q_end, after, retreat=True)
    planner.set_object_pose(obj.name, obj.goal.GetDeterministicValue())
    planned_second = planner.plan_pick(move.q_end, after.name, retreat=True)
    assert second.planned is not None
    np.testing.assert_array_equal(
        second.planned.path.waypoints, planned_second.path.path.waypoints
    )
    assert second.duration == spline.retime_free(planned_second.path.path).duration


@pytest.mark.slow
def test_with_jerk_limits_the_kept_path_is_retimed_under_them(scenario_paths):
    """The search compares paths under the acceleration limits; the MOVE
    played is the kept path retimed under the jerk limits too, and holds
    them at 1 kHz (checked by check_trajectory, not the retimer)."""
    from rt_drake import check_trajectory

    scenario = load_scenario(scenario_paths["random_transport"])
    assert scenario.robot.jerk_limits  # the shipped scenario sets them
    scenario = dataclasses.replace(
        scenario, planning=PlanningConfig(optimize_move=True, max_evaluations=60)
    )
    obj = scenario.objects[0]
    source = OnlineMotions(scenario, seed=3, jerk_limits=True)
    approach = source.approach(source.q_home, obj)
    reach = source.reach(approach.q_end, obj)
    move = source.move(reach.q_end, obj, reach)
    assert move.retimed is not None and move.grasp is not None
    assert move.retimed.path_acceleration is not None  # the jerk-limited profile
    plant = make_arm_plant(scenario)
    limits = JointLimits.from_plant(plant, scenario.robot, jerk=True)
    check = check_trajectory(plant, move.retimed.trajectory, limits, move.grasp)
    assert check.passed(), check.summary()
    # Without the jerk limits the same path is retimed faster (bang-bang),
    # on a grid fine enough that TOPP-RA's one s'' per segment costs little
    # (on 100 uniform points it lost 2 % against the jerk-limited MOVE on
    # its refined grid).
    free = retime(
        plant,
        move.planned.path,
        dataclasses.replace(limits, jerk=None),
        move.grasp,
        gridpoints=1000,
    )
    assert free.duration < move.retimed.duration
