"""Meshcat views of a scenario's cell (Drake's own Meshcat)."""

from __future__ import annotations

import base64
import re

from pydrake.geometry import Meshcat, MeshcatVisualizer, MeshcatVisualizerParams, Role
from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
from pydrake.systems.framework import DiagramBuilder

from rt_drake.model.object_model import OBJECT_BODY
from rt_drake.model.plant import (
    add_scenario_models,
    home_configuration,
)
from rt_drake.model.scenario import Scenario


def publish_scene(scenario: Scenario, meshcat: Meshcat, at_goals: bool = False) -> None:
    """Draw the cell once: robot at home, objects at start (or goal) poses.

    Illustration geometry goes to ``meshcat``'s ``visual`` path and proximity
    (collision) geometry, hidden by default, to ``collision``.
    """
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlantSceneGraph(builder, time_step=0.0)
    models = add_scenario_models(plant, scenario)
    plant.Finalize()
    MeshcatVisualizer.AddToBuilder(
        builder,
        scene_graph,
        meshcat,
        MeshcatVisualizerParams(role=Role.kIllustration, prefix="visual"),
    )
    MeshcatVisualizer.AddToBuilder(
        builder,
        scene_graph,
        meshcat,
        MeshcatVisualizerParams(
            role=Role.kProximity, prefix="collision", visible_by_default=False
        ),
    )
    diagram = builder.Build()
    context = diagram.CreateDefaultContext()
    plant_context = plant.GetMyMutableContextFromRoot(context)
    plant.SetPositions(plant_context, models.robot, home_configuration(plant, scenario))
    if at_goals:
        for obj in scenario.objects:
            body = plant.GetBodyByName(OBJECT_BODY, models.objects[obj.name])
            plant.SetFreeBodyPose(plant_context, body, obj.goal.GetDeterministicValue())
    diagram.ForcedPublish(context)


_DATA_URL = re.compile(rb"data:application/octet-binary;base64,([A-Za-z0-9+/=]+)")
_MESHCAT_PATH = re.compile(rb"/drake/[A-Za-z0-9_./:\-]+")
# msgpack: the key "type" (fixstr a4) then a fixstr value (a0-bf) of the name.
_COMMAND_TYPE = re.compile(rb"\xa4type[\xa0-\xbf]([a-z_]+)")


def _payloads(html: str):
    for match in _DATA_URL.finditer(html.encode()):
        yield base64.b64decode(match.group(1))


def meshcat_command_types(html: str) -> dict[str, int]:
    """Count the Meshcat commands (``set_object``, ``set_animation``, ...) of a page."""
    counts: dict[str, int] = {}
    for payload in _payloads(html):
        match = _COMMAND_TYPE.search(payload[:64])
        if match:
            name = match.group(1).decode()
            counts[name] = counts.get(name, 0) + 1
    return counts


def meshcat_paths_in_html(html: str) -> set[str]:
    """Return the Meshcat scene paths a ``Meshcat.StaticHtml()`` page draws.

    The page replays base64-encoded msgpack commands; each names the scene
    path it acts on (``/drake/visual/vs060/link2/...``). An empty set means an
    empty scene.
    """
    paths: set[str] = set()
    for payload in _payloads(html):
        paths.update(p.decode() for p in _MESHCAT_PATH.findall(payload))
    return paths
