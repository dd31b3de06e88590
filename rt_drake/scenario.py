"""Scenarios: typed dataclasses loaded with ``yaml_load_typed``.

A scenario file names the cell (Drake model directives), the robot's home
configuration and limits, the suction cup, the objects with their start and
goal poses, and the attach/detach times. :func:`load_scenario` refuses,
with a one-line :class:`~rt_drake.errors.ScenarioError` that names the file,
the key path (``objects[1].start.translation``) and the offending value:
unknown keys, a value of the wrong type, null where a value is needed, NaN
or inf anywhere, duplicate keys (YAML would keep the last one silently),
aliases (``*name``: an alias bomb expands exponentially), nesting deeper
than :data:`MAX_DEPTH`, files over :data:`MAX_SCENARIO_BYTES` or not UTF-8,
a scenario without objects, object models whose inertia is missing or not
physically valid (:mod:`rt_drake.object_model`), and inconsistent names.

Poses are ``pydrake.common.schema.Transform`` (metres, and degrees in
``!Rpy {deg: [roll, pitch, yaw]}``), expressed in the world frame W unless a
field says otherwise.
"""

import dataclasses
import math
import re
import types
import typing
from pathlib import Path
from typing import Any

import yaml
from pydrake.common.schema import Transform
from pydrake.common.yaml import yaml_load_typed
from pydrake.multibody.parsing import ModelDirective

from rt_drake.contact import CupParameters
from rt_drake.errors import InputError, ScenarioError
from rt_drake.object_model import model_file, read_model_inertia

#: Largest scenario file read, bytes (the shipped ones are about 3 kB).
MAX_SCENARIO_BYTES = 2**20
#: Deepest nesting of YAML mappings and lists accepted.
MAX_DEPTH = 32


@dataclasses.dataclass
class RobotConfig:
    """The arm: its model instance, home configuration and limit overrides.

    Empty limit lists mean "take them from the model" (URDF ``velocity``,
    ``drake:acceleration`` and ``effort``). Units: rad, rad/s, rad/s^2, N m.
    """

    model_instance: str = "vs060"
    home: list[float] = dataclasses.field(default_factory=list)
    velocity_limits: list[float] = dataclasses.field(default_factory=list)
    acceleration_limits: list[float] = dataclasses.field(default_factory=list)
    torque_limits: list[float] = dataclasses.field(default_factory=list)


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
    """

    name: str = ""
    model: str = ""
    start: Transform = dataclasses.field(default_factory=Transform)
    goal: Transform = dataclasses.field(default_factory=Transform)
    approach_offset: float = 0.2
    grasp: Transform = dataclasses.field(default_factory=Transform)


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
    #: The file it was loaded from, for messages (set by load_scenario; not
    #: a YAML key).
    source: str = dataclasses.field(default="", metadata={"yaml": False})

    def key(self, key_path: str) -> str:
        """``"<file>: key '<key_path>'"``, the start of a message about a key."""
        where = f"key '{key_path}'"
        return f"{self.source}: {where}" if self.source else where

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
        ScenarioError: one line naming the file, the key and the value (see
            the module docstring for what is refused).
    """
    path = Path(path)
    if path.is_dir():
        raise ScenarioError(f"{path}: is a directory, not a scenario file")
    if not path.is_file():
        raise ScenarioError(f"{path}: scenario file does not exist")
    size = path.stat().st_size
    if size > MAX_SCENARIO_BYTES:
        raise ScenarioError(
            f"{path}: {size} bytes; a scenario file is at most "
            f"{MAX_SCENARIO_BYTES} bytes"
        )
    try:
        text = path.read_bytes().decode("utf-8")
    except UnicodeDecodeError as error:
        byte = error.object[error.start]
        raise ScenarioError(
            f"{path}: not UTF-8 text (byte {error.start} is {byte:#04x})"
        ) from None
    except OSError as error:
        raise ScenarioError(f"{path}: cannot be read: {error.strerror}") from None
    try:
        raw = yaml.load(text, Loader=_StrictLoader)
    except _Refused as error:
        raise ScenarioError(f"{path}: {error}") from None
    except yaml.YAMLError as error:
        raise ScenarioError(f"{path}: not valid YAML: {error}") from None
    if not isinstance(raw, dict):
        got = "an empty file" if raw is None else type(raw).__name__
        raise ScenarioError(
            f"{path}: expected a mapping of keys at the top level, got {got}"
        )
    _check_raw(path, raw, Scenario, "")
    try:
        scenario = yaml_load_typed(schema=Scenario, data=text)
    except (RuntimeError, ValueError, TypeError) as error:
        raise ScenarioError(_locate(path, raw, str(error))) from None
    scenario.source = str(path)
    _check_semantics(path, scenario)
    return scenario


class _Refused(ScenarioError):
    """A YAML construct scenario files do not accept (the path added later)."""


class _StrictLoader(yaml.SafeLoader):
    """SafeLoader for scenario files.

    Keeps ``!Tag {...}`` nodes as plain mappings; refuses duplicate keys,
    aliases and nesting deeper than MAX_DEPTH, while composing (before
    anything is expanded).
    """

    _depth = 0

    def compose_node(self, parent: Any, index: Any) -> Any:
        """Compose one node, refusing aliases and deep nesting."""
        event = self.peek_event()
        if isinstance(event, yaml.AliasEvent):
            raise _Refused(
                f"line {event.start_mark.line + 1}: YAML aliases (*{event.anchor}) "
                "are not accepted in scenario files; write the value out"
            )
        if self._depth >= MAX_DEPTH:
            raise _Refused(
                f"line {event.start_mark.line + 1}: nested deeper than {MAX_DEPTH} "
                "levels"
            )
        self._depth += 1
        try:
            return super().compose_node(parent, index)
        finally:
            self._depth -= 1

    def construct_mapping(self, node: yaml.MappingNode, deep: bool = False) -> Any:
        """Construct a mapping, refusing a key that appears twice."""
        lines: dict[Any, int] = {}
        for key_node, _ in node.value:
            key = self.construct_object(key_node, deep=True)
            line = key_node.start_mark.line + 1
            try:
                duplicate = key in lines
            except TypeError:  # unhashable: SafeLoader refuses it below
                continue
            if duplicate:
                raise _Refused(
                    f"line {line}: duplicate key '{key}' (first on line "
                    f"{lines[key]}); YAML would silently keep the last value"
                )
            lines[key] = line
        return super().construct_mapping(node, deep=deep)


def _construct_tagged(loader: yaml.SafeLoader, _suffix: str, node: yaml.Node) -> Any:
    if isinstance(node, yaml.MappingNode):
        return loader.construct_mapping(node, deep=True)
    if isinstance(node, yaml.SequenceNode):
        return loader.construct_sequence(node, deep=True)
    return loader.construct_scalar(node)


_StrictLoader.add_multi_constructor("!", _construct_tagged)


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
    """An int or float, or a string the typed loader reads as one (``1e-3``).

    YAML 1.1 (PyYAML) reads ``1e-3`` as a string, YAML 1.2 (the typed
    loader) as a number.
    """
    if isinstance(value, str):
        try:
            float(value)
        except ValueError:
            return False
        return "_" not in value
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _is_finite(value: Any) -> bool:
    """A number (see :func:`_is_number`) that is not NaN or inf."""
    return _is_number(value) and math.isfinite(float(value))


def _shown(value: Any) -> str:
    return "null" if value is None else repr(value)


def _check_raw(path: Path, raw: dict, schema: type, prefix: str) -> None:
    """Check the keys of one mapping against a dataclass schema, recursively.

    Unknown keys, wrong types, null where a value is needed, and NaN or inf
    are refused here, with the key path, before the typed loader (whose
    messages name neither key nor value) sees the text.
    """
    hints = typing.get_type_hints(schema)
    names = [f.name for f in dataclasses.fields(schema) if f.metadata.get("yaml", True)]
    for key, value in raw.items():
        key_path = f"{prefix}.{key}" if prefix else str(key)
        if key not in names:
            raise ScenarioError(
                f"{path}: unknown key '{key_path}' (expected one of: "
                f"{', '.join(names)})"
            )
        _check_value(path, value, hints[key], key_path)


def _check_value(path: Path, value: Any, kind: Any, key_path: str) -> None:
    where = f"{path}: key '{key_path}'"
    if typing.get_origin(kind) in (typing.Union, types.UnionType):
        if value is None and type(None) in typing.get_args(kind):
            return
        (kind,) = [a for a in typing.get_args(kind) if a is not type(None)]
    if kind is Transform:
        _check_pose(path, value, key_path)
    elif kind is ModelDirective:  # Drake checks the directives themselves
        if not isinstance(value, dict):
            raise ScenarioError(f"{where}: expected a directive, got {_shown(value)}")
    elif dataclasses.is_dataclass(kind):
        if not isinstance(value, dict):
            raise ScenarioError(
                f"{where}: expected a mapping of keys, got {_shown(value)}"
            )
        _check_raw(path, value, typing.cast(type, kind), key_path)
    elif typing.get_origin(kind) is list:
        if not isinstance(value, list):
            raise ScenarioError(f"{where}: expected a list, got {_shown(value)}")
        (item,) = typing.get_args(kind)
        for index, entry in enumerate(value):
            _check_value(path, entry, item, f"{key_path}[{index}]")
    elif kind is float:
        _check_number(where, value)
    elif kind is int:
        if isinstance(value, bool) or not isinstance(value, int):
            raise ScenarioError(f"{where}: expected an integer, got {_shown(value)}")
    elif kind is str:
        if not isinstance(value, str):
            raise ScenarioError(f"{where}: expected a string, got {_shown(value)}")


def _check_number(where: str, value: Any) -> None:
    if not _is_number(value):
        raise ScenarioError(f"{where}: expected a number, got {_shown(value)}")
    if not _is_finite(value):
        raise ScenarioError(f"{where}: must be finite, got {value}")


def _check_pose(path: Path, value: Any, key_path: str) -> None:
    """A pose: a mapping whose ``translation`` and angle lists hold 3 numbers.

    Every number in it must be finite (``!Rpy``, ``!AngleAxis``, ... tags are
    left to the typed loader).
    """
    if not isinstance(value, dict):
        raise ScenarioError(
            f"{path}: key '{key_path}': expected a pose {{translation: [x, y, z], "
            f"rotation: ...}}, got {_shown(value)}"
        )
    for child, key, entry in _walk(value, key_path):
        if key in ("translation", "deg", "rad") and not (
            isinstance(entry, list) and len(entry) == 3 and all(map(_is_number, entry))
        ):
            raise ScenarioError(
                f"{path}: key '{child}': expected 3 numbers, got {_shown(entry)}"
            )
        if _is_number(entry) and not _is_finite(entry):
            raise ScenarioError(f"{path}: key '{child}': must be finite, got {entry}")


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


def _check_semantics(path: Path, scenario: Scenario) -> None:
    if not scenario.objects:
        raise ScenarioError(
            f"{path}: key 'objects': a scenario needs at least one object, got none"
        )
    names = [obj.name for obj in scenario.objects]
    for index, obj in enumerate(scenario.objects):
        where = f"{path}: key 'objects[{index}]"
        if not obj.name:
            raise ScenarioError(f"{where}.name': an object needs a name")
        if obj.name in names[:index]:
            raise ScenarioError(f"{where}.name': duplicate object name '{obj.name}'")
        if not model_file(obj.model).is_file():
            raise ScenarioError(
                f"{where}.model': unknown model '{obj.model}' (no such file)"
            )
        try:
            read_model_inertia(model_file(obj.model))
        except InputError as error:
            raise ScenarioError(f"{where}.model': {error}") from None
        if obj.approach_offset < 0:
            raise ScenarioError(
                f"{where}.approach_offset': must be >= 0 m, got {obj.approach_offset}"
            )
        for pose in ("start", "goal", "grasp"):
            if not getattr(obj, pose).IsDeterministic():
                raise ScenarioError(
                    f"{where}.{pose}': must be a fixed pose, not a random one"
                )
    _check_robot(path, scenario.robot)
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
    except InputError as error:
        raise ScenarioError(f"{path}: key 'cup': {error}") from None
    for field in ("attach_s", "detach_s"):
        value = getattr(scenario.timing, field)
        if value < 0:
            raise ScenarioError(
                f"{path}: key 'timing.{field}': must be >= 0 s, got {value}"
            )


def _check_robot(path: Path, robot: RobotConfig) -> None:
    """Limit lists are empty or as long as ``home``, and > 0."""
    joints = len(robot.home)
    for field in ("velocity_limits", "acceleration_limits", "torque_limits"):
        values = getattr(robot, field)
        key = f"{path}: key 'robot.{field}'"
        if values and len(values) != joints:
            raise ScenarioError(
                f"{key}: {len(values)} values but robot.home has {joints} joints"
            )
        if any(v <= 0 for v in values):
            raise ScenarioError(f"{key}: limits must be > 0, got {values}")
