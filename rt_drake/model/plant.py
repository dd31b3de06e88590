"""Populate a MultibodyPlant with a scenario's cell, robot, tool and objects.

Every consumer (``rt-drake show``, the planner's RobotDiagram, the retimer,
the simulation station) builds its plant through :func:`add_scenario_models`
so they all see the same models. World frame W: at the robot base, z up.
The cup's rim and a tool's holders are :mod:`rt_drake.model.cup_geometry`
(its functions stay importable from here).
"""

from __future__ import annotations

import dataclasses
import enum

import numpy as np
from pydrake.multibody.parsing import (
    AddModel,
    ModelDirective,
    ModelDirectives,
    ModelInstanceInfo,
    Parser,
    ProcessModelDirectives,
)
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import Frame, ModelInstanceIndex

from rt_drake import arguments
from rt_drake.errors import InputError, ScenarioError
from rt_drake.model.cup_geometry import (
    add_cup_rim,
    add_tool_cups,
    cup_poses_in_body,
    rim_friction,
)
from rt_drake.model.frames import (
    DEFAULT_CUP_FRAME,
    find_frame,
)
from rt_drake.model.object_model import OBJECT_BODY
from rt_drake.model.parser import with_rt_drake_package
from rt_drake.model.scenario import Scenario

#: Name of the shipped tool's cup frame C (origin at the centre of the cup's
#: contact face, +z out of the cup toward the object, suction_tool.urdf): the
#: default of the scenario's ``robot.cup_frame``.
CUP_FRAME = DEFAULT_CUP_FRAME


class ObjectMode(enum.Enum):
    """How the scenario's objects enter the plant."""

    FREE = "free"  # free bodies at their start poses (simulation, show)
    WELDED = "welded"  # welded to the world at their start poses (planning)
    NONE = "none"  # left out


@dataclasses.dataclass(frozen=True)
class ScenarioModels:
    """Model instances added by :func:`add_scenario_models`."""

    robot: ModelInstanceIndex
    tool: ModelInstanceIndex
    objects: dict[str, ModelInstanceIndex]


def add_scenario_models(
    plant: MultibodyPlant,
    scenario: Scenario,
    objects: ObjectMode = ObjectMode.FREE,
    parser: Parser | None = None,
    rims: bool = True,
) -> ScenarioModels:
    """Add the scenario's directives and objects to an unfinalized ``plant``.

    Free objects get their start pose X_WO as default free-body pose; welded
    objects are welded to W at X_WO. The caller finalizes the plant.
    ``rims``: register the cup's rim spheres (and a multi-cup tool's
    holders); the bellows simulation models its own lip instead.

    Raises:
        ScenarioError: the directives cannot be loaded, do not contain
            ``robot.model_instance`` or the ``suction_cup`` frame, or the
            robot's ``home`` or limit lists do not have one entry per joint;
            an object model cannot be loaded. Messages name the scenario file.
    """
    parser = with_rt_drake_package(parser or Parser(plant))
    try:
        infos: list[ModelInstanceInfo] = ProcessModelDirectives(
            ModelDirectives(directives=scenario.directives), plant, parser
        )
    except RuntimeError as error:
        raise ScenarioError(
            f"{scenario.key('directives')}: {_one_line(error)}"
        ) from None
    by_name = {info.model_name: info.model_instance for info in infos}
    robot_name = scenario.robot.model_instance
    if robot_name not in by_name:
        raise ScenarioError(
            f"{scenario.key('robot.model_instance')}: '{robot_name}' is not a model "
            f"of the directives (they add: {', '.join(by_name)})"
        )
    _check_robot_lengths(plant, by_name[robot_name], scenario)
    cup_frame = scenario_cup_frame(plant, scenario)
    tool = cup_frame.model_instance()
    if plant.geometry_source_is_registered() and rims:
        if scenario.tool is None:
            add_cup_rim(plant, cup_frame, scenario.cup)
        else:
            add_tool_cups(plant, cup_frame, scenario.tool_parameters())
    added: dict[str, ModelInstanceIndex] = {}
    if objects is not ObjectMode.NONE:
        for index, obj in enumerate(scenario.objects):
            try:
                instance = _add_object(plant, parser, obj.name, obj.model)
            except RuntimeError as error:
                raise ScenarioError(
                    f"{scenario.key(f'objects[{index}].model')}: '{obj.model}' "
                    f"cannot be loaded: {_one_line(error)}"
                ) from None
            X_WO = obj.start.GetDeterministicValue()
            body = plant.GetBodyByName(OBJECT_BODY, instance)
            if objects is ObjectMode.WELDED:
                plant.WeldFrames(plant.world_frame(), body.body_frame(), X_WO)
            else:
                plant.SetDefaultFloatingBaseBodyPose(body, X_WO)
            added[obj.name] = instance
    return ScenarioModels(robot=by_name[robot_name], tool=tool, objects=added)


def scenario_cup_frame(plant: MultibodyPlant, scenario: Scenario) -> Frame:
    """The frame named by the scenario's ``robot.cup_frame``.

    Raises:
        ScenarioError: the directives define no such frame (or several).
    """
    try:
        return find_frame(plant, scenario.robot.cup_frame)
    except InputError as error:
        raise ScenarioError(f"{scenario.key('robot.cup_frame')}: {error}") from None


def make_arm_plant(scenario: Scenario) -> MultibodyPlant:
    """A finalized continuous plant of the arm and tool only (no objects).

    Its positions are the arm's joints: the plant the retimer, the dynamics and
    the controller's feedforward work on.
    """
    arguments.instance(scenario, "scenario", Scenario, where="make_arm_plant")
    plant = MultibodyPlant(0.0)
    add_scenario_models(plant, scenario, ObjectMode.NONE)
    plant.Finalize()
    return plant


def _add_object(
    plant: MultibodyPlant, parser: Parser, name: str, model: str
) -> ModelInstanceIndex:
    """Load one object SDF as a model instance called ``name``."""
    directive = ModelDirectives(
        directives=[ModelDirective(add_model=AddModel(file=model, name=name))]
    )
    (info,) = ProcessModelDirectives(directive, plant, parser)
    instance = info.model_instance
    if not plant.HasBodyNamed(OBJECT_BODY, instance):
        raise ScenarioError(
            f"object '{name}': model '{model}' has no body named '{OBJECT_BODY}'"
        )
    return instance


def _check_robot_lengths(
    plant: MultibodyPlant, robot: ModelInstanceIndex, scenario: Scenario
) -> None:
    """``robot.home`` and non-empty limit lists: one entry per robot joint."""
    joints = sum(
        plant.get_joint(index).num_positions() for index in plant.GetJointIndices(robot)
    )
    config = scenario.robot
    fields = ("home", "velocity_limits", "acceleration_limits", "torque_limits")
    for field in (*fields, "jerk_limits"):
        values = getattr(config, field)
        if (values or field == "home") and len(values) != joints:
            raise ScenarioError(
                f"{scenario.key(f'robot.{field}')}: {len(values)} values but robot "
                f"'{config.model_instance}' has {joints} joint positions"
            )


def _one_line(error: Exception) -> str:
    """A Drake error message on one line, at most 300 characters."""
    return " ".join(str(error).split())[:300]


def home_configuration(plant: MultibodyPlant, scenario: Scenario) -> np.ndarray:
    """Return the robot's home joint positions (rad), checked against the plant.

    Raises:
        ScenarioError: ``robot.home`` has the wrong length or leaves the limits.
    """
    robot = plant.GetModelInstanceByName(scenario.robot.model_instance)
    q_home = np.asarray(scenario.robot.home, dtype=float)
    n = plant.num_positions(robot)
    if q_home.shape != (n,):
        raise ScenarioError(
            f"{scenario.key('robot.home')}: expected {n} joint positions, got "
            f"{q_home.tolist()}"
        )
    indices = robot_position_indices(plant, robot)
    lower = plant.GetPositionLowerLimits()[indices]
    upper = plant.GetPositionUpperLimits()[indices]
    outside = np.flatnonzero((q_home < lower) | (q_home > upper))
    if outside.size:
        i = int(outside[0])
        raise ScenarioError(
            f"{scenario.key(f'robot.home[{i}]')}: {q_home[i]:.4f} rad is outside "
            f"the joint limits [{lower[i]:.4f}, {upper[i]:.4f}]"
        )
    return q_home


def robot_position_indices(
    plant: MultibodyPlant, instance: ModelInstanceIndex
) -> np.ndarray:
    """Indices of a model instance's joint positions in the plant's q."""
    q = np.zeros(plant.num_positions())
    plant.SetPositionsInArray(instance, np.ones(plant.num_positions(instance)), q)
    return np.flatnonzero(q)


__all__ = [
    "CUP_FRAME",
    "OBJECT_BODY",
    "ObjectMode",
    "ScenarioModels",
    "add_cup_rim",
    "add_scenario_models",
    "add_tool_cups",
    "cup_poses_in_body",
    "home_configuration",
    "make_arm_plant",
    "rim_friction",
    "robot_position_indices",
    "scenario_cup_frame",
]
