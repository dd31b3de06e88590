"""The blended pick when the straight transit to the approach pose is blocked.

The pick first tries the blend with nothing between start and approach pose
(no APPROACH path certified on its own); if that blend collides between
them, the APPROACH's own path (spline, else RRT-Connect polyline) joins in.
An obstacle on the straight joint-space segment forces the second route;
the path is checked independently: Drake forward kinematics, samples at most
1 mm of cup travel apart, the collision checker at each sample.
"""

from __future__ import annotations

import numpy as np
from pydrake.geometry import Sphere
from pydrake.math import RigidTransform

from rt_drake.model.plant import CUP_FRAME
from rt_drake.planning import CyclePlanner, GeometricPath
from rt_drake.planning.dense_check import check_path
from rt_drake.types.phase import Phase


def cup_travel_samples(plant, path, step=1e-3):
    """Parameters s of ``path`` with the cup moving at most ``step`` m apart."""
    context = plant.CreateDefaultContext()
    cup = plant.GetFrameByName(CUP_FRAME)
    s = np.linspace(0.0, 1.0, 401)
    while True:
        p = []
        for q in path.value(s):
            plant.SetPositions(context, q)
            p.append(cup.CalcPoseInWorld(context).translation())
        steps = np.linalg.norm(np.diff(np.array(p), axis=0), axis=1)
        if steps.max() <= step:
            return s
        s = np.sort(np.concatenate([s, 0.5 * (s[:-1] + s[1:])[steps > step]]))


def test_a_blocked_straight_transit_takes_the_approach_path(
    scenario, plant, monkeypatch
):
    planner = CyclePlanner(scenario, seed=0)
    name = scenario.objects[0].name
    q_home = planner.q_home
    q_goal = planner.approach_goal(q_home, name).q_goal
    # A ball where the cup passes halfway along the straight segment.
    q_mid = 0.5 * (q_home + q_goal)
    planner.scene.add_obstacle(
        "ball",
        Sphere(0.04),
        RigidTransform(planner.scene.cup_pose(q_mid).translation()),
    )
    planner.prepare(Phase.APPROACH, name, q_home)
    assert planner.scene.is_free(q_home) and planner.scene.is_free(q_goal)
    straight = GeometricPath.from_waypoints(np.array([q_home, q_goal]))
    assert not check_path(planner.scene, straight).ok  # the premise

    approaches = []
    plan_approach = planner.plan_approach

    def spy(q, obj):
        approaches.append(plan_approach(q, obj))
        return approaches[-1]

    monkeypatch.setattr(planner, "plan_approach", spy)
    pick = planner.plan_pick(q_home, name)
    (approach,) = approaches  # the second route was taken, once
    assert len(approach.polyline) > 2  # around the ball, not straight

    path = pick.path.path
    np.testing.assert_allclose(path.value(0.0), q_home, atol=1e-12)
    X_WO = scenario.objects[0].start.GetDeterministicValue()
    X_end = planner.scene.cup_pose(path.value(1.0))
    np.testing.assert_allclose(
        X_end.translation(), (X_WO @ pick.path.X_OC).translation(), atol=1e-4
    )
    planner.prepare(Phase.REACH, name, q_home, pick.path.X_OC)
    s = cup_travel_samples(plant, path)
    free = np.array(planner.scene.checker.CheckConfigsCollisionFree(path.value(s)))
    assert free.all(), s[~free][:3]
    assert 0.0 < pick.s_approach < 1.0
