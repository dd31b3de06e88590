"""The shaped pick (rt_drake.shaping.shape_pick) against independent checks.

The paper's stacking cell's picks (the session's scenario: acceleration
limits, no jerk limits), planned as the cycle plans them (the first from
home, the others after a place), each played twice by
:meth:`rt_drake.simulation.OnlineMotions.pick`: with the optimisation on
(``planning.shape_picks``: the transit shaped) and off (the blended
pick). References independent of
the shaping:

- Drake's signed distance (:meth:`PlanningScene.collisions`, the scene's
  ``ComputeSignedDistancePairwiseClosestPoints``) at every 1 mm of joint
  motion of the shaped path, in the scene the pick was planned in;
- the blended pick's own lines: the shaped path starts and ends at the same
  configurations, passes through the same retreat top and approach pose,
  and keeps the cup on both vertical lines (1 mm, 0.5 deg, the planner's
  tolerance) by forward kinematics at 1000 samples per line;
- the played trajectory sampled at 1 kHz: velocity and acceleration
  (differences of q), and jerk where the cell sets jerk limits, within the
  limits;
- the blended pick's duration: the shaped one is never longer, and over the
  picks where the transit is free to move, shorter by a margin that the
  blended pick (an optimiser that never finds anything) fails.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from rt_drake import CyclePlanner, JointLimits, OnlineMotions, make_arm_plant
from rt_drake.planning._pick import LINE_TOLERANCE_M, LINE_TOLERANCE_RAD
from rt_drake.types.phase import Phase

#: The jerk-limited cycle's picks: tens of seconds for the module.
pytestmark = pytest.mark.slow

#: s, sampling period of the played trajectories (the robot's 1 kHz).
PERIOD = 1e-3
#: Relative tolerance of the finite-difference limit checks.
SLACK = 0.02
#: The median ratio of shaped to blended duration over the picks after a
#: place must be at most this.
BOUND = 0.99


@pytest.fixture(scope="module")
def cell(scenario):
    """The paper's stacking cell (the session's scenario), picks shaped."""
    planning = dataclasses.replace(scenario.planning, shape_picks=True)
    return dataclasses.replace(scenario, planning=planning)


@pytest.fixture(scope="module")
def sources(cell):
    """The motion sources: (blended, shaped)."""
    return (
        OnlineMotions(cell, seed=0, jerk_limits=True, optimize=False),
        OnlineMotions(cell, seed=0, jerk_limits=True),
    )


@pytest.fixture(scope="module")
def picks(cell, sources):
    """(blended, shaped, object index) per object, each from the same start."""
    blended, shaped = sources
    q, out = shaped.q_home, []
    for index, obj in enumerate(cell.objects):
        pair = [
            source.pick(q, obj, retreat=index > 0) if index else _blended(source, obj)
            for source in sources
        ]
        out.append((*pair, index))
        q = blended.planner.plan_move(
            pair[0].q_end, obj.name, reach=pair[0].planned
        ).q_goal
    return out


def _blended(source: OnlineMotions, obj):
    """The first pick as a blended pick from home (the cycle stages it)."""
    from rt_drake.simulation._blended_pick import blended_pick

    source._place_objects_for(obj)  # noqa: SLF001 - the source's own scene
    shape = source._shape_pick if source._optimizer else None  # noqa: SLF001
    return blended_pick(
        source.planner,
        lambda path, profile: source.retime_free(path, profile=profile),
        source.q_home,
        obj.name,
        False,
        shape=shape,
    )


@pytest.fixture(scope="module")
def planner(cell):
    return CyclePlanner(cell, seed=0)


def _scene(planner, scenario, index, planned):
    """The REACH scene of pick ``index``: the objects before it at their goals."""
    for k, other in enumerate(scenario.objects):
        pose = other.goal if k < index else other.start
        planner.set_object_pose(other.name, pose.GetDeterministicValue())
    return planner.prepare(Phase.REACH, planned.object, planned.q_start, planned.X_OC)


def test_the_shaped_pick_keeps_the_blended_picks_ends_and_lines(picks, planner):
    for blended, shaped, _ in picks:
        old, new = blended.planned, shaped.planned
        np.testing.assert_array_equal(new.q_start, old.q_start)
        np.testing.assert_array_equal(new.q_goal, old.q_goal)
        np.testing.assert_array_equal(new.descent, old.descent)
        path = new.path
        s_approach = path.knots[-len(new.descent)]
        np.testing.assert_array_equal(path.value([s_approach])[0], new.descent[0])
        X_grasp = planner.scene.cup_pose(new.q_goal)
        s = np.linspace(s_approach, 1.0, 1000)
        R, p = planner.scene.cup_frames(path.value(s))
        offset = np.linalg.norm((p - X_grasp.translation())[:, :2], axis=1)
        trace = np.einsum("ij,nij->n", X_grasp.rotation().matrix(), R)
        tilt = np.arccos(np.clip(0.5 * (trace - 1.0), -1.0, 1.0))
        assert offset.max() <= LINE_TOLERANCE_M
        assert tilt.max() <= LINE_TOLERANCE_RAD


def test_the_shaped_pick_is_collision_free_by_drakes_signed_distance(
    picks, planner, cell
):
    checked = 0
    for blended, shaped, index in picks:
        path = shaped.planned.path
        if np.array_equal(path.waypoints, blended.planned.path.waypoints):
            continue  # the blended pick, certified by the planner's own tests
        scene = _scene(planner, cell, index, shaped.planned)
        s = np.linspace(0.0, 1.0, 400)
        length = np.abs(np.diff(path.value(s), axis=0)).max(axis=1).sum()
        s = np.linspace(0.0, 1.0, int(length / 1e-3) + 2)
        hits = [(t, scene.collisions(q)) for t, q in zip(s, path.value(s), strict=True)]
        assert not [h for h in hits if h[1]], hits[:3]
        checked += 1
    assert checked  # a shaped path was checked, not only blended ones


def test_the_played_pick_holds_the_joint_and_jerk_limits_at_1khz(picks, cell):
    plant = make_arm_plant(cell)
    limits = JointLimits.from_plant(plant, cell.robot, jerk=True)
    for _, shaped, _ in picks:
        trajectory = shaped.trajectory
        t = np.arange(0.0, trajectory.end_time(), PERIOD)
        q = np.array([trajectory.value(x).ravel() for x in t])
        v = np.gradient(q, PERIOD, axis=0)
        a = np.diff(q, 2, axis=0) / PERIOD**2
        j = np.diff(a, axis=0) / PERIOD
        assert np.all(np.abs(v) <= limits.velocity * (1 + SLACK))
        assert np.all(np.abs(a) <= limits.acceleration * (1 + SLACK))
        if limits.jerk is not None:
            assert np.all(np.abs(j) <= limits.jerk * (1 + SLACK) + 1e-6)


def test_the_shaped_pick_is_never_slower_and_faster_where_it_can_be(picks):
    """Measured (budget of evaluations, no clock): 0.982, 1.000, 0.985 for
    the three picks after a place; the blended pick gives 1.0 each."""
    ratios = [shaped.duration / blended.duration for blended, shaped, _ in picks]
    assert max(ratios) <= 1.0
    assert np.median(ratios[1:]) <= BOUND


def test_a_failed_shaping_plays_the_blended_pick_and_says_so_once(
    picks, sources, cell, monkeypatch
):
    from rt_drake.errors import RtDrakeError
    from rt_drake.simulation import online_motions

    def broken(*args, **kwargs):
        raise RtDrakeError("shaping broken on purpose")

    monkeypatch.setattr(online_motions, "shape_pick", broken)
    blended, shaped = sources
    obj = cell.objects[1]
    q = picks[1][0].planned.q_start
    with pytest.warns(RuntimeWarning, match="shaping broken on purpose") as said:
        first = shaped.pick(q, obj, retreat=True)
        shaped.pick(q, obj, retreat=True)
    assert len(said) == 1
    np.testing.assert_array_equal(
        first.planned.path.waypoints, picks[1][0].planned.path.waypoints
    )
    assert first.duration == picks[1][0].duration
