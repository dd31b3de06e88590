"""The carried object is part of the robot for the planner.

Query: carry the whetstone box (5.5 cm tall) from one side of the table
obstacle (top at z = 0.10 m) to the other, the cup at z = 0.125 m on both
sides. The robot alone clears the obstacle along the straight joint-space
path; the box hanging below the cup (bottom at z = 0.07 m) would go through
it. The planner must route the box over or around the obstacle.

The box-obstacle check below is independent of Drake: a separating-axis
test of two boxes, at every sample where the cup moved at most 1 mm.
"""

from __future__ import annotations

import numpy as np
import pytest
from pydrake.math import RigidTransform, RotationMatrix

from rt_drake.model.scenario import load_scenario
from rt_drake.planning import CyclePlanner, GeometricPath
from rt_drake.planning._geometry import object_geometries
from rt_drake.planning.dense_check import check_path
from rt_drake.types.phase import Phase

OBSTACLE_CENTER = np.array([0.55, 0.0, 0.05])  # cell.sdf table_obstacle
OBSTACLE_HALF = np.array([0.25, 0.05, 0.05])
CUP_HEIGHT = 0.125


def boxes_overlap(center_a, R_a, half_a, center_b, R_b, half_b) -> bool:
    """Separating-axis test of two oriented boxes (True: they intersect)."""
    axes = [R_a[:, i] for i in range(3)] + [R_b[:, i] for i in range(3)]
    axes += [np.cross(a, b) for a in axes[:3] for b in axes[3:]]
    d = center_b - center_a
    for axis in axes:
        norm = np.linalg.norm(axis)
        if norm < 1e-9:
            continue
        axis = axis / norm
        ra = np.sum(half_a * np.abs(R_a.T @ axis))
        rb = np.sum(half_b * np.abs(R_b.T @ axis))
        if abs(d @ axis) > ra + rb:
            return False
    return True


@pytest.fixture(scope="module")
def query(scenario_paths):
    scenario = load_scenario(scenario_paths["stack_four_objects"])
    planner = CyclePlanner(scenario, seed=0)
    name = "whetstone_box"
    X_OC = scenario.object(name).grasp.GetDeterministicValue()
    (box,) = object_geometries(scenario.object(name).model)
    planner.prepare(Phase.MOVE, name, planner.q_home, X_OC)
    q = [planner.q_home]
    yaw = RotationMatrix.MakeZRotation(np.pi)  # keeps the wrist's last joint near 0
    for y in (-0.12, 0.12):  # between bin and obstacle, then beyond the obstacle
        X_WO = RigidTransform(yaw, [0.55, y, CUP_HEIGHT - X_OC.translation()[2]])
        q.append(planner.configuration_for(X_WO @ X_OC, q[-1]))
    return planner, name, X_OC, box, q[1], q[2]


def box_hits_obstacle(planner, X_OC, box, path: GeometricPath) -> np.ndarray:
    """Per sample (<= 1 mm of cup travel): does the box penetrate the obstacle?"""
    s = np.linspace(0.0, 1.0, 4001)
    X_WC = [planner.scene.cup_pose(q) for q in path.value(s)]
    steps = np.linalg.norm(np.diff([X.translation() for X in X_WC], axis=0), axis=1)
    assert steps.max() <= 1e-3
    hits = []
    for X in X_WC:
        X_WB = X @ X_OC.inverse() @ box.X_FG
        hits.append(
            boxes_overlap(
                X_WB.translation(),
                X_WB.rotation().matrix(),
                0.5 * box.shape.size(),
                OBSTACLE_CENTER,
                np.eye(3),
                OBSTACLE_HALF,
            )
        )
    return np.array(hits)


@pytest.mark.slow
def test_straight_path_is_free_for_the_robot_but_drags_the_box_through(query):
    planner, name, X_OC, box, q_start, q_goal = query
    straight = GeometricPath.from_waypoints(np.array([q_start, q_goal]))
    planner.prepare(Phase.APPROACH, name, q_start)  # robot alone, box left in the bin
    assert check_path(planner.scene, straight).ok
    planner.prepare(Phase.MOVE, name, q_start, X_OC)  # box carried
    result = check_path(planner.scene, straight)
    assert not result.ok and result.reason == "collision"
    assert f"{name} (held) with cell::table_obstacle" in planner.scene.collisions(
        result.q
    )
    assert box_hits_obstacle(planner, X_OC, box, straight).any()


def test_planned_path_carries_the_box_over_or_around_the_obstacle(query):
    planner, name, X_OC, box, q_start, q_goal = query
    plan = planner.plan_between(q_start, q_goal, name, X_OC)
    np.testing.assert_array_equal(plan.path.value(0.0), q_start)
    np.testing.assert_allclose(plan.path.value(1.0), q_goal, rtol=0, atol=1e-15)
    assert len(plan.polyline) > 2  # not the straight path
    assert not box_hits_obstacle(planner, X_OC, box, plan.path).any()


def test_rrt_plan_is_deterministic_for_a_seed(query):
    planner, name, X_OC, _, q_start, q_goal = query
    first = planner.plan_between(q_start, q_goal, name, X_OC)
    again = planner.plan_between(q_start, q_goal, name, X_OC)
    # The straight edge collides, so the spline through the two anchors did
    # too and RRT-Connect added vertices.
    assert not planner.scene.edge_free(q_start, q_goal)
    assert len(first.polyline) > 2
    np.testing.assert_array_equal(first.polyline, again.polyline)
    np.testing.assert_array_equal(first.path.waypoints, again.path.waypoints)
