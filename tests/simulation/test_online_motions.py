"""Online motions: planning depends on the picking order, not on call history."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from toppra_reference import toppra_duration

from rt_drake.model.plant import make_arm_plant
from rt_drake.retiming import JointLimits, Margin, TimeScaled, check_trajectory
from rt_drake.shaping import retime_adaptive
from rt_drake.simulation import OnlineMotions, _motion_retimer
from rt_drake.types.phase import Phase


@pytest.fixture(scope="module")
def motions(scenario):
    # The blended pick (every pick after a place) from home too; the cycle's
    # staged first pick: test_online_motions_first_pick.py.
    return OnlineMotions(scenario, split_first_pick=False)


def test_replanning_after_a_move_gives_the_same_motion(motions, scenario):
    first = scenario.objects[0]
    approach = motions.approach(motions.q_home, first)
    reach = motions.reach(approach.q_end, first)
    move = motions.move(reach.q_end, first, reach)
    # The motion carries its path, retiming and grasp: nothing to read back.
    assert move.planned is not None and move.retimed is not None
    assert move.grasp is not None and move.grasp.held.mass > 0
    np.testing.assert_array_equal(move.planned.path.waypoints[0], reach.q_end)
    assert move.retimed.duration == pytest.approx(move.duration, rel=1e-12)
    # A re-run of the cycle (new context) asks again: same scene, same path.
    again = motions.approach(motions.q_home, first)
    assert again.duration == pytest.approx(approach.duration, rel=1e-12)
    np.testing.assert_allclose(again.q_end, approach.q_end, atol=1e-12)


def test_time_scaling_scales_every_derivative(motions, scenario):
    first = scenario.objects[0]
    motion = motions.approach(motions.q_home, first)
    factor = 1.4
    fast = TimeScaled(motion.trajectory, factor)
    assert fast.end_time() == pytest.approx(motion.trajectory.end_time() / factor)
    t = 0.3 * fast.end_time()
    for order in range(3):
        np.testing.assert_allclose(
            fast.EvalDerivative(t, order),
            factor**order * motion.trajectory.EvalDerivative(factor * t, order),
            atol=1e-12,
        )


def test_picks_and_moves_keep_their_limits_between_grid_points(motions, scenario):
    """At 1 kHz, every joint velocity and acceleration (and the MOVE's grasp
    constraint) within 2 % of its limit, for the pick from home, the MOVE and
    the pick after a place (retreat, transit, descent); the APPROACH part ends
    where the cup passes the approach pose."""
    plant = make_arm_plant(scenario)
    limits = JointLimits.from_plant(plant, scenario.robot)
    first, second = scenario.objects[:2]
    pick = motions.pick(motions.q_home, first)
    move = motions.move(pick.q_end, first, pick)
    after = motions.pick(move.q_end, second, retreat=True)
    for motion in (pick, move, after):
        check = check_trajectory(plant, motion.trajectory, limits, motion.grasp)
        assert check.passed(0.02), check.summary()
    for motion in (pick, after):
        t = motion.phase_end(Phase.APPROACH)
        assert 0.0 < t < motion.duration
        np.testing.assert_allclose(
            motion.trajectory.value(t).ravel(), motion.planned.descent[0], atol=1e-9
        )


def test_the_pick_is_retimed_within_a_percent_of_a_fine_grid(motions, scenario):
    """On its adaptive grid the pick is within 1 % of toppra's time-optimal
    duration on 2000 points (on 100 uniform points it is 4-6 % above), and
    at least 3 % faster than on the 100 uniform points alone. The shaped
    MOVE's grasp price is its path retimed with the grasp (adaptive grid)
    less toppra's duration without it, within 1 % of the MOVE, and >= 0."""
    plant = make_arm_plant(scenario)
    limits = JointLimits.from_plant(plant, scenario.robot)
    first, second = scenario.objects[:2]
    pick = motions.pick(motions.q_home, first)
    move = motions.move(pick.q_end, first, pick)
    after = motions.pick(move.q_end, second, retreat=True)
    # The kindle box: its grasp hardly binds, and its price is never
    # negative (-3.4 ms with each retime on a grid of its own).
    light = motions.move(after.q_end, second, after)
    assert 0.0 <= light.grasp_price_s <= 0.01 * light.duration
    for motion in (pick, after):
        path = motion.planned.path
        reference = toppra_duration(path, limits)
        assert reference * (1 - 2e-3) <= motion.duration <= reference * 1.01
        uniform = motions.retime_path(path, None).duration
        assert motion.duration <= 0.97 * uniform
    # The carton box, whose MOVE its grasp slows (the light boxes' hardly).
    carton = scenario.objects[3]
    pick = motions.pick(motions.q_home, carton)
    move = motions.move(pick.q_end, carton, pick)
    path = move.planned.path
    with_grasp = retime_adaptive(plant, path, limits, move.grasp).duration
    price = with_grasp - toppra_duration(path, limits)
    assert move.grasp_price_s == pytest.approx(price, abs=0.01 * move.duration)
    assert move.grasp_price_s > 0.02 * move.duration


def test_a_jerk_limited_pick_is_retimed_on_its_adaptive_grid(scenario, monkeypatch):
    """Under jerk limits (each joint's acceleration reached in 50 ms) the
    pick is retimed on points placed by its acceleration-limited profile,
    then on that grid refined where s'^2 moves (``jerk_grid``): every
    limit, the jerk too, holds at 1 kHz, and it is faster than the same
    path on the uniform grid (1.5-2 % on the default cycle's picks) and
    than on the adaptive grid alone (1-5 %)."""
    plant = make_arm_plant(scenario)
    plain = JointLimits.from_plant(plant, scenario.robot)
    robot = dataclasses.replace(
        scenario.robot, jerk_limits=list(20.0 * plain.acceleration)
    )
    jerky = dataclasses.replace(scenario, robot=robot)
    motions = OnlineMotions(jerky, split_first_pick=False, jerk_limits=True)
    limits = JointLimits.from_plant(plant, robot, jerk=True)
    pick = motions.pick(motions.q_home, jerky.objects[0])
    check = check_trajectory(plant, pick.trajectory, limits)
    assert Margin.JERK in check.margins and check.passed(), check.summary()
    uniform = motions.retime_path(pick.planned.path, None).duration
    assert pick.duration < uniform
    monkeypatch.setattr(_motion_retimer, "JERK_GRID_PASSES", 0)
    adaptive = motions.retime_free(pick.planned.path).duration
    assert pick.duration < adaptive
    # Ends halved too deep for the LPs (they stop the motion there): the
    # refinement runs without them, and still shortens the pick.
    monkeypatch.setattr(_motion_retimer, "JERK_GRID_PASSES", 2)
    monkeypatch.setattr(_motion_retimer, "END_HALVINGS", 12)
    too_deep = motions.retime_free(pick.planned.path).duration
    assert too_deep < adaptive
