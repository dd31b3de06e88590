"""The shipped models parse, and sit where cell-facts.md puts them."""

from __future__ import annotations

import numpy as np
import pytest
from pydrake.geometry import Box, SceneGraph
from pydrake.math import RigidTransform
from pydrake.multibody.plant import AddMultibodyPlantSceneGraph, MultibodyPlant
from pydrake.systems.framework import DiagramBuilder

from rt_drake.model.object_model import OBJECT_BODY
from rt_drake.model.parser import make_parser
from rt_drake.model.plant import (
    CUP_FRAME,
    add_scenario_models,
    home_configuration,
)
from rt_drake.model.resources import models_dir
from rt_drake.model.scenario import load_scenario

MODEL_FILES = sorted(
    p for ext in ("urdf", "sdf") for p in models_dir().glob(f"*/*.{ext}")
)

# cell-facts.md: velocity and acceleration limits of the VS-060.
VELOCITY_LIMITS = [
    3.92699082,
    2.61799388,
    2.85832572,
    3.92699082,
    3.02168853,
    6.28318531,
]
ACCELERATION_LIMITS = [
    19.73356519,
    16.84469621,
    20.70885517,
    20.96646577,
    23.72286426,
    33.51032164,
]


# cell-facts.md: object masses (kg) and principal moments about the CoM (kg m^2).
OBJECT_FACTS = {
    "notebook": (0.551, (9.28e-4, 2.11e-3, 2.98e-3)),
    "kindle_box": (0.2103, (1.535e-4, 8.879e-5, 2.228e-4)),
    "whetstone_box": (0.204, (2.38e-4, 6.02e-4, 7.56e-4)),
    "carton_box": (0.347, (9.8e-4, 2.96e-3, 3.77e-3)),
}


@pytest.mark.parametrize("path", MODEL_FILES, ids=lambda p: p.name)
def test_every_model_parses_and_finalizes(path):
    plant = MultibodyPlant(0.0)
    scene_graph = SceneGraph()  # kept alive: the plant holds a raw pointer
    plant.RegisterAsSourceForSceneGraph(scene_graph)
    (instance,) = make_parser(plant).AddModels(str(path))
    plant.Finalize()
    assert len(plant.GetBodyIndices(instance)) >= 1
    assert plant.num_collision_geometries() >= 1


@pytest.mark.parametrize("name", sorted(OBJECT_FACTS))
def test_object_mass_and_inertia_are_the_facts(name):
    plant = MultibodyPlant(0.0)
    (instance,) = make_parser(plant).AddModels(
        str(models_dir() / "objects" / f"{name}.sdf")
    )
    plant.Finalize()
    body = plant.GetBodyByName(OBJECT_BODY, instance)
    mass, moments = OBJECT_FACTS[name]
    M = body.default_spatial_inertia()
    assert M.get_mass() == pytest.approx(mass)
    np.testing.assert_allclose(M.get_com(), 0.0, atol=1e-12)
    I_Bcm = M.CalcRotationalInertia().CopyToFullMatrix3()
    np.testing.assert_allclose(I_Bcm, np.diag(moments), rtol=1e-9, atol=1e-12)


def _cell_plant(scenario_path):
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlantSceneGraph(builder, 0.0)
    scenario = load_scenario(scenario_path)
    models = add_scenario_models(plant, scenario)
    plant.Finalize()
    diagram = builder.Build()
    return scenario, diagram, plant, scene_graph, models


def test_flange_at_zero_configuration_is_where_the_facts_say(scenario_paths):
    _, _, plant, _, _ = _cell_plant(scenario_paths["stack_four_objects"])
    context = plant.CreateDefaultContext()
    X_WF = plant.GetFrameByName("link6").CalcPoseInWorld(context)
    np.testing.assert_allclose(X_WF.translation(), [-0.010, 0.0, 1.020], atol=1e-9)
    # The cup face is 0.12 m beyond the flange, +z along the flange axis.
    X_WC = plant.GetFrameByName(CUP_FRAME).CalcPoseInWorld(context)
    np.testing.assert_allclose(X_WC.translation(), [-0.010, 0.0, 1.140], atol=1e-9)
    np.testing.assert_allclose(X_WC.rotation().matrix(), np.eye(3), atol=1e-12)


def test_robot_limits_are_the_hardware_limits(scenario_paths):
    _, _, plant, _, models = _cell_plant(scenario_paths["stack_four_objects"])
    assert plant.num_positions(models.robot) == 6
    np.testing.assert_allclose(plant.GetVelocityUpperLimits()[:6], VELOCITY_LIMITS)
    np.testing.assert_allclose(
        plant.GetAccelerationUpperLimits()[:6], ACCELERATION_LIMITS
    )
    np.testing.assert_allclose(
        np.degrees(plant.GetPositionUpperLimits()[:6]), [170, 120, 155, 270, 95, 185]
    )


def test_robot_and_tool_mass_match_the_facts(scenario_paths):
    _, _, plant, _, models = _cell_plant(scenario_paths["stack_four_objects"])
    links = [plant.GetBodyByName(f"link{i}", models.robot) for i in range(1, 7)]
    tool_mass = sum(
        plant.get_body(b).default_mass() for b in plant.GetBodyIndices(models.tool)
    )
    masses = [b.default_mass() for b in links]
    np.testing.assert_allclose(masses[:5], [4.327, 9.475, 4.097, 1.779, 1.211])
    # link6 + tool together carry the facts' 4.154 kg.
    assert masses[5] + tool_mass == pytest.approx(4.154)


def _penetrations(diagram, plant, scene_graph, models, q):
    context = diagram.CreateDefaultContext()
    plant.SetPositions(plant.GetMyMutableContextFromRoot(context), models.robot, q)
    query = scene_graph.get_query_output_port().Eval(
        scene_graph.GetMyContextFromRoot(context)
    )
    inspector = query.inspector()
    return [
        (inspector.GetName(p.id_A), inspector.GetName(p.id_B), p.depth)
        for p in query.ComputePointPairPenetration()
    ]


@pytest.mark.parametrize("name", ["stack_four_objects", "random_transport"])
def test_home_configuration_is_collision_free(scenario_paths, name):
    scenario, diagram, plant, scene_graph, models = _cell_plant(scenario_paths[name])
    q_home = home_configuration(plant, scenario)
    assert _penetrations(diagram, plant, scene_graph, models, q_home) == []


def test_penetration_query_sees_a_colliding_configuration(scenario_paths):
    # Failable counterpart of the test above: at q = 0 the arm stands through
    # the top plate, and the same query must say so.
    _, diagram, plant, scene_graph, models = _cell_plant(
        scenario_paths["stack_four_objects"]
    )
    hits = _penetrations(diagram, plant, scene_graph, models, np.zeros(6))
    assert any("top_plate" in a + b for a, b, _ in hits)


def _box_geometries(plant, scene_graph, model_name):
    """World AABBs (lo, hi) of the axis-aligned box geometries of a static model."""
    inspector = scene_graph.model_inspector()
    instance = plant.GetModelInstanceByName(model_name)
    context = plant.CreateDefaultContext()
    boxes = {}
    for body_index in plant.GetBodyIndices(instance):
        body = plant.get_body(body_index)
        X_WB = plant.EvalBodyPoseInWorld(context, body)
        for gid in plant.GetCollisionGeometriesForBody(body):
            shape = inspector.GetShape(gid)
            assert isinstance(shape, Box)
            X_WG = X_WB @ inspector.GetPoseInFrame(gid)
            half = np.abs(X_WG.rotation().matrix()) @ (np.array(shape.size()) / 2)
            name = inspector.GetName(gid).split("::")[-1]
            boxes[name] = (X_WG.translation() - half, X_WG.translation() + half)
    return boxes


def _object_corners(scene_graph, plant, models, name, X_WO: RigidTransform):
    inspector = scene_graph.model_inspector()
    body = plant.GetBodyByName(OBJECT_BODY, models.objects[name])
    (gid,) = plant.GetCollisionGeometriesForBody(body)
    size = np.array(inspector.GetShape(gid).size())
    signs = np.array(
        [[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
    )
    return (X_WO @ (signs * size / 2).T).T


@pytest.mark.parametrize("name", ["stack_four_objects", "random_transport"])
def test_starts_lie_in_the_bin_and_goals_on_the_destination(scenario_paths, name):
    scenario, _, plant, scene_graph, models = _cell_plant(scenario_paths[name])
    bin_boxes = _box_geometries(plant, scene_graph, "bin")
    lo = np.array(
        [
            bin_boxes["wall_back"][1][0],
            bin_boxes["wall_right"][1][1],
            bin_boxes["floor"][1][2],
        ]
    )
    hi = np.array(
        [
            bin_boxes["wall_front"][0][0],
            bin_boxes["wall_left"][0][1],
            bin_boxes["wall_left"][1][2],
        ]
    )
    zone_lo, zone_hi = _box_geometries(plant, scene_graph, "cell")["destination_zone"]
    for obj in scenario.objects:
        start = _object_corners(
            scene_graph, plant, models, obj.name, obj.start.GetDeterministicValue()
        )
        assert np.all(start >= lo - 1e-9) and np.all(start <= hi + 1e-9), obj.name
        X_WO_goal = obj.goal.GetDeterministicValue()
        centre = X_WO_goal.translation()
        assert zone_lo[0] <= centre[0] <= zone_hi[0], obj.name
        assert zone_lo[1] <= centre[1] <= zone_hi[1], obj.name
        goal = _object_corners(scene_graph, plant, models, obj.name, X_WO_goal)
        assert goal[:, 2].min() >= zone_hi[2] - 1e-9, obj.name


def test_random_transport_regions_stay_in_the_bin_for_every_yaw(scenario_paths):
    scenario, _, plant, scene_graph, models = _cell_plant(
        scenario_paths["random_transport"]
    )
    region = scenario.random_transport.start_region
    bin_boxes = _box_geometries(plant, scene_graph, "bin")
    lo = np.array(
        [
            bin_boxes["wall_back"][1][0],
            bin_boxes["wall_right"][1][1],
            bin_boxes["floor"][1][2],
        ]
    )
    hi = np.array([bin_boxes["wall_front"][0][0], bin_boxes["wall_left"][0][1], np.inf])
    from pydrake.math import RollPitchYaw

    name = scenario.random_transport.object
    for x in (region.lower[0], region.upper[0]):
        for y in (region.lower[1], region.upper[1]):
            for yaw in np.linspace(*region.yaw_deg, 7):
                X_WO = RigidTransform(
                    RollPitchYaw(0, 0, np.radians(yaw)), [x, y, region.lower[2]]
                )
                corners = _object_corners(scene_graph, plant, models, name, X_WO)
                assert np.all(corners >= lo - 1e-9) and np.all(corners <= hi), (
                    x,
                    y,
                    yaw,
                )
