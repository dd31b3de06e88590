"""Scenarios: typed dataclasses loaded with ``yaml_load_typed``.

A scenario file names the cell (Drake model directives), the robot's home
configuration and limits, the suction cup, the objects with their start and
goal poses, and the attach/detach times. ``yaml_load_typed`` rejects
misspelled keys; :func:`load_scenario` turns every error into a one-line
:class:`~rt_drake.errors.ScenarioError` that names the file, the key path
(``objects[1].start.translation``) and the offending value.

Poses are ``pydrake.common.schema.Transform`` (metres, and degrees in
``!Rpy {deg: [roll, pitch, yaw]}``), expressed in the world frame W unless a
field says otherwise.
"""

import dataclasses
import math
import re
from pathlib import Path
from typing import Any

import yaml
from pydrake.common.schema import Transform
from pydrake.common.yaml import yaml_load_typed
from pydrake.multibody.parsing import ModelDirective

from rt_drake.contact import CupParameters
from rt_drake.errors import InputError, ScenarioError
from rt_drake.resources import models_dir
from rt_drake.uncertainty import ObjectUncertainty


@dataclasses.dataclass
class RobotConfig:
    """The arm: its model instance, home configuration and limit overrides.

    Empty limit lists mean "take them from the model" (URDF ``velocity``,
    ``drake:acceleration`` and ``effort``). Units: rad, rad/s, rad/s^2, N m.
    ``limit_torques``: retime under the torque limits too (inverse dynamics,
    held object included), for an arm whose maker publishes torque limits
    rather than acceleration limits (e.g. the UR5e).
    """

    model_instance: str = "vs060"
    home: list[float] = dataclasses.field(default_factory=list)
    velocity_limits: list[float] = dataclasses.field(default_factory=list)
    acceleration_limits: list[float] = dataclasses.field(default_factory=list)
    torque_limits: list[float] = dataclasses.field(default_factory=list)
    limit_torques: bool = False


@dataclasses.dataclass
class ObjectConfig:
    """One object to pick and place.

    Attributes:
        name: model instance name in the plant (unique in the scenario).
        model: ``package://rt_drake/...`` URL (or file path) of its SDF.
        start: X_WO, pose of the object's body frame in the world at the start.
        goal: X_WO at the place pose.
        approach_offset: m; the approach pose is the grasp pose raised by it.
        grasp: X_OC, pose of the cup frame C in the object frame O while held
            (cup +z pointing into the object).
        uncertainty: What is not known about its inertia (None: known
            exactly): the MOVE is then retimed to hold every object of the
            set (:class:`~rt_drake.uncertainty.ObjectUncertainty`).
    """

    name: str = ""
    model: str = ""
    start: Transform = dataclasses.field(default_factory=Transform)
    goal: Transform = dataclasses.field(default_factory=Transform)
    approach_offset: float = 0.2
    grasp: Transform = dataclasses.field(default_factory=Transform)
    uncertainty: ObjectUncertainty | None = None


@dataclasses.dataclass
class Timing:
    """Waits of the cycle, in seconds (the paper: 1 s each)."""

    attach_s: float = 1.0
    detach_s: float = 1.0


@dataclasses.dataclass
class Region:
    """An axis-aligned box of object positions (m, world) and a yaw range (deg)."""

    lower: list[float] = dataclasses.field(default_factory=lambda: [0.0, 0.0, 0.0])
    upper: list[float] = dataclasses.field(default_factory=lambda: [0.0, 0.0, 0.0])
    yaw_deg: list[float] = dataclasses.field(default_factory=lambda: [0.0, 0.0])


@dataclasses.dataclass
class RandomTransport:
    """Where Table I's random start and goal poses of ``object`` are sampled."""

    object: str = ""
    start_region: Region = dataclasses.field(default_factory=Region)
    goal_region: Region = dataclasses.field(default_factory=Region)


@dataclasses.dataclass
class Scenario:
    """Everything a cycle needs; see ``scenarios/stack_four_objects.yaml``."""

    directives: list[ModelDirective] = dataclasses.field(default_factory=list)
    robot: RobotConfig = dataclasses.field(default_factory=RobotConfig)
    cup: CupParameters = dataclasses.field(default_factory=CupParameters)
    objects: list[ObjectConfig] = dataclasses.field(default_factory=list)
    timing: Timing = dataclasses.field(default_factory=Timing)
    random_transport: RandomTransport | None = None

    def object(self, name: str) -> ObjectConfig:
        """Return the object called ``name``; ScenarioError if there is none."""
        for obj in self.objects:
            if obj.name == name:
                return obj
        known = ", ".join(o.name for o in self.objects)
        raise ScenarioError(f"unknown object '{name}' (scenario has: {known})")


def load_scenario(path: str | Path) -> Scenario:
    """Load and check a scenario file.

    Raises:
        ScenarioError: one line naming the file, the key and the value, for a
            missing file, YAML syntax error, unknown key, malformed pose or
            number, unknown model file, or inconsistent names.
    """
    path = Path(path)
    if not path.is_file():
        raise ScenarioError(f"{path}: scenario file does not exist")
    text = path.read_text()
    try:
        raw = yaml.load(text, Loader=_TaggedLoader)
    except yaml.YAMLError as error:
        raise ScenarioError(f"{path}: not valid YAML: {error}") from None
    if not isinstance(raw, dict):
        raise ScenarioError(f"{path}: expected a mapping of keys at the top level")
    _check_poses(path, raw)
    try:
        scenario = yaml_load_typed(schema=Scenario, data=text)
    except (RuntimeError, ValueError, TypeError) as error:
        raise ScenarioError(_locate(path, raw, str(error))) from None
    _check_semantics(path, scenario)
    return scenario


class _TaggedLoader(yaml.SafeLoader):
    """SafeLoader that keeps ``!Tag {...}`` nodes as plain mappings."""


def _construct_tagged(loader: yaml.SafeLoader, _suffix: str, node: yaml.Node) -> Any:
    if isinstance(node, yaml.MappingNode):
        return loader.construct_mapping(node, deep=True)
    if isinstance(node, yaml.SequenceNode):
        return loader.construct_sequence(node, deep=True)
    return loader.construct_scalar(node)


_TaggedLoader.add_multi_constructor("!", _construct_tagged)


def _walk(node: Any, prefix: str = ""):
    """Yield ``(key_path, key, value)`` for every mapping entry and list item."""
    if isinstance(node, dict):
        for key, value in node.items():
            child = f"{prefix}.{key}" if prefix else str(key)
            yield child, key, value
            yield from _walk(value, child)
    elif isinstance(node, list):
        for index, value in enumerate(node):
            child = f"{prefix}[{index}]"
            yield child, index, value
            yield from _walk(value, child)


def _is_number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _check_poses(path: Path, raw: dict) -> None:
    """Every ``translation`` and rotation angle list must hold 3 numbers."""
    for key_path, key, value in _walk(raw):
        if key in ("translation", "deg", "rad") and not (
            isinstance(value, list) and len(value) == 3 and all(map(_is_number, value))
        ):
            raise ScenarioError(
                f"{path}: key '{key_path}': expected 3 numbers, got {value!r}"
            )


def _locate(path: Path, raw: dict, message: str) -> str:
    """Turn a ``yaml_load_typed`` error into 'file: key ...: problem'."""
    unknown = re.search(r"fields \[(.*?)\] were unknown", message)
    if unknown:
        names = [n.strip(" '\"") for n in unknown.group(1).split(",")]
        for key_path, key, _ in _walk(raw):
            if key in names:
                return f"{path}: unknown key '{key_path}'"
        return f"{path}: unknown key(s) {', '.join(names)}"
    bad_float = re.search(r"could not convert string to float: '(.*)'", message)
    if bad_float:
        for key_path, _, value in _walk(raw):
            if isinstance(value, str) and value == bad_float.group(1):
                return f"{path}: key '{key_path}': value {value!r} is not a number"
    return f"{path}: {' '.join(message.split())[:300]}"


def _resolve_model(url: str) -> Path:
    """Return the file a ``package://rt_drake/...`` URL or a path points to."""
    prefix = "package://rt_drake/"
    if url.startswith(prefix):
        return models_dir() / url[len(prefix) :]
    return Path(url)


def _check_uncertainty(path: Path, key: str, obj: ObjectConfig) -> None:
    """The widths in range and the CoM box inside the object's box."""
    from rt_drake.object_geometry import object_box  # parses the model: Drake

    assert obj.uncertainty is not None
    try:
        obj.uncertainty.validate()
        if any(obj.uncertainty.com):
            p_OoScm_O, half_extents = object_box(obj)
            obj.uncertainty.check_inside(p_OoScm_O, half_extents)
    except InputError as error:
        raise ScenarioError(f"{path}: key '{key}': {error}") from None


def _check_semantics(path: Path, scenario: Scenario) -> None:
    names = [obj.name for obj in scenario.objects]
    for index, obj in enumerate(scenario.objects):
        where = f"{path}: key 'objects[{index}]"
        if not obj.name:
            raise ScenarioError(f"{where}.name': an object needs a name")
        if obj.name in names[:index]:
            raise ScenarioError(f"{where}.name': duplicate object name '{obj.name}'")
        if not _resolve_model(obj.model).is_file():
            raise ScenarioError(
                f"{where}.model': unknown model '{obj.model}' (no such file)"
            )
        if not (math.isfinite(obj.approach_offset) and obj.approach_offset >= 0):
            raise ScenarioError(
                f"{where}.approach_offset': must be >= 0 m, got {obj.approach_offset}"
            )
        if obj.uncertainty is not None:
            _check_uncertainty(path, f"objects[{index}].uncertainty", obj)
    transport = scenario.random_transport
    if transport is not None:
        if transport.object not in names:
            raise ScenarioError(
                f"{path}: key 'random_transport.object': unknown object "
                f"'{transport.object}' (scenario has: {', '.join(names)})"
            )
        for which in ("start_region", "goal_region"):
            region = getattr(transport, which)
            key = f"{path}: key 'random_transport.{which}"
            if len(region.lower) != 3 or len(region.upper) != 3:
                raise ScenarioError(f"{key}': lower and upper need 3 numbers each")
            if any(lo > hi for lo, hi in zip(region.lower, region.upper, strict=True)):
                raise ScenarioError(
                    f"{key}': lower {region.lower} > upper {region.upper}"
                )
            if len(region.yaw_deg) != 2 or region.yaw_deg[0] > region.yaw_deg[1]:
                raise ScenarioError(
                    f"{key}.yaw_deg': expected [low, high], got {region.yaw_deg}"
                )
    try:
        scenario.cup.validate()
    except ValueError as error:
        raise ScenarioError(f"{path}: key 'cup': {error}") from None
    for field in ("attach_s", "detach_s"):
        value = getattr(scenario.timing, field)
        if not (math.isfinite(value) and value >= 0):
            raise ScenarioError(
                f"{path}: key 'timing.{field}': must be >= 0 s, got {value}"
            )
