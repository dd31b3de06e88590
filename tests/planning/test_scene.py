"""PlanningScene: objects as checker shapes, kinematics and motion bounds."""

from __future__ import annotations

import numpy as np
import pytest
from pydrake.geometry import Box
from pydrake.math import RigidTransform, RotationMatrix

from rt_drake.dynamics.body_kinematics import step_motion
from rt_drake.model.plant import home_configuration
from rt_drake.model.scenario import load_scenario
from rt_drake.planning._geometry import object_geometries
from rt_drake.planning.dense_check import check_path
from rt_drake.planning.scene import PlanningScene
from rt_drake.types.path import GeometricPath
from rt_drake.types.phase import Phase


@pytest.fixture(scope="module")
def scene(scenario_paths):
    return PlanningScene(load_scenario(scenario_paths["stack_four_objects"]))


def _load_corners(scene: PlanningScene, name: str, X_CO: RigidTransform, q: np.ndarray):
    """World positions (8, 3) of the corners of the carried box at q."""
    (posed,) = object_geometries(scene.scenario.object(name).model)
    half = 0.5 * posed.shape.size()
    signs = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)])
    X_WG = scene.cup_pose(q) @ X_CO @ posed.X_FG
    return np.array([X_WG.multiply(half * sign) for sign in signs])


def test_vectorised_cup_frames_match_drake(scene):
    rng = np.random.default_rng(3)
    q = rng.uniform(scene.lower, scene.upper, (25, 6))
    R, p = scene.cup_frames(q)
    context = scene.plant.CreateDefaultContext()
    for k in range(len(q)):
        scene.plant.SetPositions(context, q[k])
        X_WC = scene.cup_frame.CalcPoseInWorld(context)
        np.testing.assert_allclose(R[k], X_WC.rotation().matrix(), atol=1e-12)
        np.testing.assert_allclose(p[k], X_WC.translation(), atol=1e-12)


def test_vectorised_kinematics_matches_drake(scene):
    rng = np.random.default_rng(1)
    q = rng.uniform(scene.lower, scene.upper, (25, 6))
    R, p = scene.bounds.kinematics.poses(q)
    for k in range(len(q)):
        context = scene.checker.UpdatePositions(q[k])
        for column, body in enumerate(scene.bounds.bodies):
            X_WB = scene.plant.EvalBodyPoseInWorld(context, scene.plant.get_body(body))
            np.testing.assert_allclose(
                R[column, :, :, k], X_WB.rotation().matrix(), atol=1e-12
            )
            np.testing.assert_allclose(p[column, :, k], X_WB.translation(), atol=1e-12)


def test_motion_bounds_cover_every_point_of_the_load(scene):
    """Both bounds of the dense check hold for the carried box's corners."""
    obj = scene.scenario.object("carton_box")
    X_CO = obj.grasp.GetDeterministicValue().inverse()
    scene.attach("carton_box", X_CO)
    tool = len(scene.bounds.bodies) - 1
    rng = np.random.default_rng(2)
    try:
        for _ in range(40):
            q_a = rng.uniform(scene.lower, scene.upper)
            q_b = q_a + rng.normal(0.0, 0.05, 6)
            moved = np.linalg.norm(
                _load_corners(scene, obj.name, X_CO, q_b)
                - _load_corners(scene, obj.name, X_CO, q_a),
                axis=1,
            ).max()
            lever_bound = scene.bounds.radii[:, tool] @ np.abs(q_b - q_a)
            R, p = scene.bounds.kinematics.poses(np.array([q_a, q_b]))
            rigid_bound = step_motion(R, p, scene.bounds.body_radius)[0, tool]
            assert moved <= rigid_bound + 1e-12 <= lever_bound + 1e-9
    finally:
        scene.detach()


def test_collisions_are_named_and_load_is_not_checked_against_its_cup(scene):
    q = np.array([0.0, 1.6, 1.6, 0.0, 0.0, 0.0])
    pairs = scene.collisions(q)
    assert not scene.is_free(q)
    assert "vs060::link4 with cell::table_obstacle" in pairs
    q_home = home_configuration(scene.plant, scene.scenario)
    assert scene.is_free(q_home) and scene.collisions(q_home) == []
    # The carried box touches the cup face: no collision with the tool.
    scene.attach(
        "notebook",
        scene.scenario.object("notebook").grasp.GetDeterministicValue().inverse(),
    )
    try:
        assert scene.is_free(q_home)
        X_WC = scene.cup_pose(q_home)
        scene.add_obstacle(
            "slab",
            Box(0.3, 0.3, 0.01),
            RigidTransform(X_WC.translation() + [0, 0, -0.03]),
        )
        assert scene.collisions(q_home) == ["notebook (held) with slab"]
    finally:
        scene.remove_obstacle("slab")
        scene.detach()
    assert scene.is_free(q_home)


def test_touch_allowance_lets_the_cup_press_the_grasped_face_only(scene):
    """With a 2 mm allowance the cup may press 1 mm into the face, not 3 mm."""
    from rt_drake.planning._cycle_planner import CyclePlanner

    planner = CyclePlanner(scene.scenario, scene=scene)
    obj = scene.scenario.objects[0]  # top of the stack
    X_OC = obj.grasp.GetDeterministicValue()
    X_WC = obj.start.GetDeterministicValue() @ X_OC
    q_home = planner.q_home
    pressed = {}
    for depth in (0.001, 0.003):
        pressed[depth] = planner.ik.solve(
            RigidTransform([0, 0, -depth]) @ X_WC, q_home, q_home
        )
    planner.prepare(Phase.REACH, obj.name, q_home, X_OC)
    assert scene.is_free(pressed[0.001])
    assert scene.collisions(pressed[0.003]) == [f"suction_tool::tool with {obj.name}"]
    planner.prepare(Phase.APPROACH, obj.name, q_home)  # no allowance: full box
    assert not scene.is_free(pressed[0.001])


def test_dense_check_finds_a_thin_obstacle_on_a_straight_path(scene):
    """A 4 mm plate across the cup's way: caught, at the right place."""
    q_home = home_configuration(scene.plant, scene.scenario)
    q_goal = q_home + np.array([0.8, 0, 0, 0, 0, 0])
    path = GeometricPath.from_waypoints(np.array([q_home, q_goal]))
    assert check_path(scene, path).ok
    X_mid = scene.cup_pose(path.value(0.5))
    yaw = RotationMatrix.MakeZRotation(
        np.arctan2(X_mid.translation()[1], X_mid.translation()[0])
    )
    scene.add_obstacle(
        "plate", Box(0.2, 0.004, 0.2), RigidTransform(yaw, X_mid.translation())
    )
    try:
        result = check_path(scene, path)
        assert not result.ok and result.reason == "collision"
        assert 0.4 < result.s < 0.5
        assert not scene.is_free(result.q)
    finally:
        scene.remove_obstacle("plate")
