"""The cycle's first pick, staged: a straight APPROACH timed by Ruckig, then REACH.

On the shipped default cell (``approach_offset: auto``, the robot's jerk
limits) the first pick from home must be staged, and its APPROACH must be
what the arm can play: every joint's velocity, acceleration and jerk from
finite differences of the positions at 1 kHz within the robot's limits; on
the straight joint-space line; in the least time that line allows (a
closed-form rest-to-rest profile, not Ruckig); ending at rest with the cup
at the approach pose (forward kinematics against the grasp raised by the
line's height); collision-free at every sample (Drake's signed distances).
Where the line is blocked, the first pick is the blended one.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from pydrake.common.schema import Transform
from pydrake.math import RigidTransform

from rt_drake.model.plant import make_arm_plant, scenario_cup_frame
from rt_drake.model.scenario import load_scenario
from rt_drake.planning import CyclePlanner
from rt_drake.retiming import JointLimits, check_trajectory
from rt_drake.simulation import OnlineMotions
from rt_drake.types.phase import Phase

#: s, the sampling period of the finite differences.
DT = 1e-3


@pytest.fixture(scope="module")
def first(scenario_paths):
    """The default cell, its motion source and its first pick from home."""
    scenario = load_scenario(scenario_paths["stack_four_objects"])
    assert scenario.robot.jerk_limits  # the shipped cell limits the jerk
    motions = OnlineMotions(scenario, optimize=False, jerk_limits=True)
    obj = scenario.objects[0]
    return scenario, motions, obj, motions.pick(motions.q_home, obj)


def _samples(trajectory, t0: float, t1: float) -> np.ndarray:
    """q at every DT from t0 to t1 (N, n)."""
    times = t0 + DT * np.arange(int(math.floor((t1 - t0) / DT)) + 1)
    return np.array([trajectory.value(t).ravel() for t in times])


def rest_to_rest_time(distance: float, v: float, a: float, j: float) -> float:
    """Least time (s) from rest to rest over ``distance`` under v, a, j.

    The symmetric jerk-limited profile: accelerating to the peak speed u
    takes ``T(u) = u / a + a / j`` if ``u >= a^2 / j`` (the acceleration
    limit is reached), else ``2 sqrt(u / j)``, and covers ``u T(u) / 2``;
    decelerating is its mirror. The distance is ``u T(u)`` at the peak, plus
    a cruise at ``v`` when ``v T(v) < distance``.
    """

    def ramp(u: float) -> float:
        return u / a + a / j if u >= a * a / j else 2.0 * math.sqrt(u / j)

    if v * ramp(v) <= distance:
        return ramp(v) + distance / v
    u = 0.5 * a * (-a / j + math.sqrt((a / j) ** 2 + 4.0 * distance / a))
    if u < a * a / j:  # the acceleration limit is not reached
        u = (0.5 * distance * math.sqrt(j)) ** (2.0 / 3.0)
    return 2.0 * ramp(u)


def test_the_first_pick_is_staged_and_the_arm_starts_on_its_approach(first):
    _, motions, obj, pick = first
    assert pick.staged
    assert [part.phase for part in pick.parts] == [Phase.APPROACH, Phase.REACH]
    assert 0.0 < pick.phase_end(Phase.APPROACH) < pick.duration
    # Its REACH is the planner's, from the approach pose: the MOVE lifts along it.
    assert pick.planned is not None and pick.planned.phase is Phase.REACH
    assert pick.planned.descent is not None
    end = pick.trajectory.value(pick.phase_end(Phase.APPROACH)).ravel()
    np.testing.assert_array_equal(end, pick.planned.descent[0])
    # The same descent as the blended pick's (its turn point included): the
    # MOVE lifts along the same line either way.
    blended = motions.planner.plan_pick(motions.q_home, obj.name)
    np.testing.assert_array_equal(pick.planned.descent, blended.path.descent)
    # Later picks (after a place) are blended, without a stop.
    move = motions.move(pick.q_end, obj, pick)
    after = motions.pick(move.q_end, motions.planner.scenario.objects[1], True)
    assert not after.staged


def test_the_approach_keeps_every_limit_at_1_khz(first):
    scenario, _, _, pick = first
    plant = make_arm_plant(scenario)
    limits = JointLimits.from_plant(plant, scenario.robot, jerk=True)
    q = _samples(pick.trajectory, 0.0, pick.phase_end(Phase.APPROACH))
    velocity = np.diff(q, axis=0) / DT
    acceleration = np.diff(q, 2, axis=0) / DT**2
    jerk = np.diff(q, 3, axis=0) / DT**3
    # Each difference is a weighted mean of the derivative over its span.
    assert np.all(np.abs(velocity) <= limits.velocity * (1 + 1e-9))
    assert np.all(np.abs(acceleration) <= limits.acceleration * (1 + 1e-9))
    assert np.all(np.abs(jerk) <= limits.jerk * (1 + 1e-6))
    assert np.abs(jerk).max(axis=0).max() > 0.5 * limits.jerk.min()  # not idle
    # The whole pick, the REACH after the stop included (its retimer's 1e-3).
    check = check_trajectory(plant, pick.trajectory, limits)
    assert check.passed(1e-3), check.summary()


def test_the_approach_is_the_fastest_motion_along_its_line(first):
    scenario, motions, _, pick = first
    plant = make_arm_plant(scenario)
    limits = JointLimits.from_plant(plant, scenario.robot, jerk=True)
    q_home, q_top = motions.q_home, pick.planned.descent[0]
    step = q_top - q_home
    q = _samples(pick.trajectory, 0.0, pick.phase_end(Phase.APPROACH))
    h = (q - q_home) @ step / (step @ step)  # the share of the line travelled
    np.testing.assert_allclose(q, q_home + np.outer(h, step), atol=1e-9)
    assert np.all(np.diff(h) >= -1e-12)  # never back
    # q = q_home + h(t) step: h is limited by the tightest joint's v, a, j.
    scale = np.abs(step)
    least = rest_to_rest_time(
        1.0,
        float(np.min(limits.velocity / scale)),
        float(np.min(limits.acceleration / scale)),
        float(np.min(limits.jerk / scale)),
    )
    assert pick.phase_end(Phase.APPROACH) == pytest.approx(least, rel=1e-6)


def test_the_approach_ends_at_rest_on_the_approach_pose(first):
    scenario, motions, obj, pick = first
    t = pick.phase_end(Phase.APPROACH)
    approach = pick.trajectory
    for order in (1, 2):  # the last instant of the APPROACH
        assert np.abs(approach.EvalDerivative(t - 1e-9, order)).max() < 1e-5
    plant = make_arm_plant(scenario)
    context = plant.CreateDefaultContext()
    plant.SetPositions(context, approach.value(t - 1e-9).ravel())
    X_WC = plant.CalcRelativeTransform(
        context, plant.world_frame(), scenario_cup_frame(plant, scenario)
    )
    X_WO = obj.start.GetDeterministicValue()
    height = motions.planner.line_height(obj.name, X_WO, Phase.APPROACH)
    X_grasp = X_WO @ pick.planned.X_OC
    expected = X_grasp.translation() + [0.0, 0.0, height]
    # within what the planner's IK accepts: 10 um and 1e-4 rad
    np.testing.assert_allclose(X_WC.translation(), expected, atol=1e-5)
    angle = X_WC.rotation().InvertAndCompose(X_grasp.rotation()).ToAngleAxis()
    assert angle.angle() < 1e-4


def test_the_approach_is_collision_free_at_every_sample(first):
    _, motions, obj, pick = first
    planner = motions.planner
    scene = planner.prepare(Phase.APPROACH, obj.name, motions.q_home)
    q = _samples(pick.trajectory, 0.0, pick.phase_end(Phase.APPROACH))
    closest = min(
        float(np.min(scene.clearance(qk, 0.05).distances(), initial=0.05)) for qk in q
    )
    assert closest > 0.0


def test_a_blocked_line_falls_back_to_the_blended_pick(scenario):
    """The paper's stack with the second box hung where the first pick's
    straight APPROACH passes halfway: the first pick is the blended one,
    around it, and charges the straight line it tried."""
    probe = CyclePlanner(scenario)
    first, second = scenario.objects[:2]
    line = probe.straight_approach(probe.q_home, first.name)
    assert line is not None
    X_mid = RigidTransform(probe.scene.cup_pose(line.path.value(0.5)).translation())
    hung = dataclasses.replace(second, start=Transform(X_mid))
    cell = dataclasses.replace(scenario, objects=[first, hung, *scenario.objects[2:]])
    motions = OnlineMotions(cell)
    assert motions.straight_approach(motions.q_home, first) is None
    pick = motions.pick(motions.q_home, first)
    assert not pick.staged
    assert [part.phase for part in pick.parts] == [Phase.APPROACH, Phase.REACH]
    np.testing.assert_allclose(pick.q_end, pick.planned.descent[-1], atol=1e-9)
    # Around the box: up to the approach pose (the descent's top, a knot of
    # the path), every sample is free in the APPROACH scene.
    path = pick.planned.path
    top = np.flatnonzero(np.all(path.waypoints == pick.planned.descent[0], axis=1))
    scene = motions.planner.prepare(Phase.APPROACH, first.name, motions.q_home)
    samples = path.value(np.linspace(0.0, path.knots[top[0]], 200))
    assert all(scene.is_free(q) for q in samples)
