"""The blended pick: one path through the approach pose, vertical where it must be.

The four objects of the stacking task, picked in order (the first from
home, each next one after a vertical retreat from the object just placed).
Every path is checked independently of the planner's own checks: Drake
forward kinematics on the retimer's plant, samples at most 1 mm of cup
travel apart, and the collision checker at each sample.
"""

from __future__ import annotations

import numpy as np
import pytest

from rt_drake.model.plant import CUP_FRAME
from rt_drake.planning import CyclePlanner
from rt_drake.planning._pick import RETREAT_HEIGHT
from rt_drake.retiming import JointLimits, retime
from rt_drake.types.phase import Phase

#: Plans four picks and moves and samples each pick at 1 mm of cup travel.
pytestmark = pytest.mark.slow

#: m and deg: the cup's largest horizontal offset from, and tilt off, the
#: vertical line over the last approach_offset and over the retreat.
LINE_BOUND_M = 1e-3
TILT_BOUND_DEG = 0.5
CUP_STEP = 1e-3  # m of cup travel between samples


def cup_samples(plant, path, s0, s1):
    """(s, X_WC) along ``path`` on [s0, s1], the cup moving <= CUP_STEP apart."""
    context = plant.CreateDefaultContext()
    cup = plant.GetFrameByName(CUP_FRAME)

    def poses(s):
        out = []
        for q in path.value(s):
            plant.SetPositions(context, q)
            out.append(cup.CalcPoseInWorld(context))
        return out

    s = np.linspace(s0, s1, 201)
    while True:
        X = poses(s)
        p = np.array([x.translation() for x in X])
        steps = np.linalg.norm(np.diff(p, axis=0), axis=1)
        if steps.max() <= CUP_STEP:
            return s, X
        length = np.concatenate([[0.0], np.cumsum(steps)])
        count = int(2 * np.ceil(length[-1] / CUP_STEP)) + len(s)
        s = np.interp(np.linspace(0.0, length[-1], count), length, s)


def off_line(X_line, poses):
    """Largest horizontal offset (m) and tilt (deg) of ``poses`` off the line."""
    p = np.array([X.translation() for X in poses])
    offset = np.linalg.norm((p - X_line.translation())[:, :2], axis=1).max()
    tilt = max(
        X_line.rotation().InvertAndCompose(X.rotation()).ToAngleAxis().angle()
        for X in poses
    )
    return offset, np.degrees(tilt)


@pytest.fixture(scope="module")
def picks(scenario, plant):
    planner = CyclePlanner(scenario, seed=0)
    q = planner.q_home
    out = []
    for index, obj in enumerate(scenario.objects):
        for k, other in enumerate(scenario.objects):
            pose = other.goal if k < index else other.start
            planner.set_object_pose(other.name, pose.GetDeterministicValue())
        pick = planner.plan_pick(q, obj.name, retreat=index > 0)
        out.append((obj, q, pick))
        move = planner.plan_move(pick.path.q_goal, obj.name, reach=pick.path)
        q = move.q_goal
    return planner, out


def test_the_cup_descends_vertically_for_its_last_approach_offset(picks, plant):
    planner, runs = picks
    for obj, _, pick in runs:
        X_grasp = obj.start.GetDeterministicValue() @ pick.path.X_OC
        s, X = cup_samples(plant, pick.path.path, pick.s_approach, 1.0)
        z = np.array([x.translation()[2] for x in X])
        # It starts at the approach pose and ends on the grasp.
        assert z[0] - X_grasp.translation()[2] == pytest.approx(
            obj.approach_offset, abs=1e-4
        )
        np.testing.assert_allclose(
            X[-1].translation(), X_grasp.translation(), atol=1e-4
        )
        offset, tilt = off_line(X_grasp, X)
        assert offset <= LINE_BOUND_M, (obj.name, offset)
        assert tilt <= TILT_BOUND_DEG, (obj.name, tilt)
        assert np.all(np.diff(z) <= 1e-6), obj.name  # straight down, never up


def test_after_a_place_the_cup_first_rises_vertically(picks, plant):
    _, runs = picks
    for obj, _, pick in runs[1:]:
        assert pick.s_retreat > 0.0
        _, X = cup_samples(plant, pick.path.path, 0.0, pick.s_retreat)
        z = np.array([x.translation()[2] for x in X])
        assert z[-1] - z[0] == pytest.approx(RETREAT_HEIGHT, abs=1e-4)
        offset, tilt = off_line(X[0], X)
        assert offset <= LINE_BOUND_M and tilt <= TILT_BOUND_DEG, obj.name
        assert np.all(np.diff(z) >= -1e-6), obj.name
    assert runs[0][2].s_retreat == 0.0  # from home: nothing to retreat from


def test_the_pick_starts_and_ends_at_rest_and_keeps_moving_between(
    picks, plant, scenario
):
    _, runs = picks
    limits = JointLimits.from_plant(plant, scenario.robot)
    for obj, _, pick in runs:
        path = pick.path.path
        np.testing.assert_allclose(path.deriv(0.0), 0.0, atol=1e-12)
        np.testing.assert_allclose(path.deriv(1.0), 0.0, atol=1e-12)
        result = retime(plant, path, limits)
        traj = result.trajectory
        end = traj.end_time()
        np.testing.assert_allclose(traj.EvalDerivative(end, 1).ravel(), 0, atol=1e-9)
        # No stop on the way: s' > 0 everywhere inside, at the approach pose too.
        assert result.sd[1:-1].min() > 0.0, obj.name
        assert np.interp(pick.s_approach, result.gridpoints, result.sd) > 0.1


def test_every_pick_is_collision_free(picks, plant):
    planner, runs = picks
    for index, (obj, q_start, pick) in enumerate(runs):
        for k, other in enumerate(planner.scenario.objects):
            pose = other.goal if k < index else other.start
            planner.set_object_pose(other.name, pose.GetDeterministicValue())
        planner.prepare(Phase.REACH, obj.name, q_start, pick.path.X_OC)
        s, _ = cup_samples(plant, pick.path.path, 0.0, 1.0)
        q = pick.path.path.value(s)
        free = planner.scene.checker.CheckConfigsCollisionFree(q)
        assert all(free), (obj.name, s[np.flatnonzero(~np.array(free))[:3]])
