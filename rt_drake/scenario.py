"""Scenarios: typed dataclasses loaded with ``yaml_load_typed``.

A scenario file names the cell (Drake model directives), the robot's home
configuration and limits, the suction cup, the objects with their start and
goal poses, and the vacuum (attach and detach behaviour). ``yaml_load_typed`` rejects
misspelled keys; :func:`load_scenario` turns every error into a one-line
:class:`~rt_drake.errors.ScenarioError` that names the file, the key path
(``objects[1].start.translation``) and the offending value.

Poses are ``pydrake.common.schema.Transform`` (metres, and degrees in
``!Rpy {deg: [roll, pitch, yaw]}``), expressed in the world frame W unless a
field says otherwise.
"""

import dataclasses
import enum
import math
import re
from pathlib import Path
from typing import Any

import yaml
from pydrake.common.schema import Transform
from pydrake.common.yaml import yaml_load_typed
from pydrake.multibody.parsing import ModelDirective

from rt_drake.contact import CupParameters
from rt_drake.errors import ScenarioError
from rt_drake.resources import models_dir


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
    """

    name: str = ""
    model: str = ""
    start: Transform = dataclasses.field(default_factory=Transform)
    goal: Transform = dataclasses.field(default_factory=Transform)
    approach_offset: float = 0.2
    grasp: Transform = dataclasses.field(default_factory=Transform)


class VacuumModel(enum.Enum):
    """How the suction force follows the valve."""

    FIXED = "fixed"  # full force at once; fixed attach and detach waits
    FIRST_ORDER = "first_order"  # first-order build-up and release


@dataclasses.dataclass
class Vacuum:
    """The vacuum: how fast the suction force P A builds up and releases.

    ``model: fixed`` (the paper's, the default): the force is P A while the
    valve is on and 0 when it is off; ATTACH waits ``attach_s`` and DETACH
    ``detach_s`` seconds (the paper: 1 s each).

    ``model: first_order``: the vacuum level lambda in [0, 1] (force
    lambda P A) follows a first-order lag, ``d lambda/dt = (1 - lambda) /
    build_up_tau_s`` while the valve is on and the cup sealed on a face, and
    ``-lambda / release_tau_s`` otherwise. A vacuum switch reports "part
    present" once ``lambda >= part_present_fraction``: ATTACH ends then
    (``t = build_up_tau_s ln(1 / (1 - part_present_fraction))`` after the
    valve opens) and the MOVE is retimed for the force guaranteed from then
    on, ``part_present_fraction P A``. DETACH ends when the force is below
    the object's weight and the object is at rest. ``attach_s`` and
    ``detach_s`` are then time-outs: a cycle that waits longer stops with a
    VacuumTimeout (no seal, or the object sticks).

    The default time constants are assumptions, not measurements: an
    ejector evacuating a volume V at a suction flow q through the valve is a
    first-order lag of ``tau = V / q`` (isothermal, flow proportional to the
    remaining pressure difference; evacuating from p0 to p1 takes
    ``(V / q) ln(p0 / p1)``). For the paper's 25 mm cup, V is about 15 cm^3
    (cup and 1 m of 4 mm hose) and q about 9 l/min (0.15 l/s) at the cup,
    so tau is about 0.1 s; venting with a blow-off pulse is assumed twice
    as fast (0.05 s). Vacuum switches are commonly set to 60-80 % of the
    working vacuum: 0.8.

    Attributes:
        model: ``fixed`` or ``first_order``.
        attach_s, detach_s: s, the waits (fixed) or time-outs (first_order).
        build_up_tau_s: s, time constant of the build-up (first_order).
        release_tau_s: s, time constant of the release (first_order).
        part_present_fraction: fraction of P A at which "part present" fires.
    """

    model: str = VacuumModel.FIXED.value
    attach_s: float = 1.0
    detach_s: float = 1.0
    build_up_tau_s: float = 0.1
    release_tau_s: float = 0.05
    part_present_fraction: float = 0.8

    @property
    def kind(self) -> VacuumModel:
        """``model`` as the enum (ScenarioError if unknown)."""
        try:
            return VacuumModel(self.model)
        except ValueError:
            known = ", ".join(m.value for m in VacuumModel)
            raise ScenarioError(
                f"key 'vacuum.model': unknown model {self.model!r} (known: {known})"
            ) from None

    @property
    def move_force_fraction(self) -> float:
        """Fraction of P A a MOVE may rely on (1 fixed, the switch's first_order)."""
        if self.kind is VacuumModel.FIXED:
            return 1.0
        return self.part_present_fraction


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
    vacuum: Vacuum = dataclasses.field(default_factory=Vacuum)
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
    _check_renamed(path, raw)
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


def _check_renamed(path: Path, raw: dict) -> None:
    """``timing: {attach_s, detach_s}`` (before 0.2.0) is now ``vacuum``."""
    timing = raw.get("timing")
    if timing is None:
        return
    waits = timing if isinstance(timing, dict) else {}
    attach, detach = waits.get("attach_s", 1.0), waits.get("detach_s", 1.0)
    raise ScenarioError(
        f"{path}: key 'timing' was renamed 'vacuum': write vacuum: "
        f"{{model: fixed, attach_s: {attach}, detach_s: {detach}}}"
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
    _check_vacuum(path, scenario.vacuum)


def _check_vacuum(path: Path, vacuum: Vacuum) -> None:
    if vacuum.model not in {m.value for m in VacuumModel}:
        known = ", ".join(m.value for m in VacuumModel)
        raise ScenarioError(
            f"{path}: key 'vacuum.model': unknown model {vacuum.model!r} "
            f"(known: {known})"
        )
    bounds = {
        "attach_s": (0.0, False, "s"),
        "detach_s": (0.0, False, "s"),
        "build_up_tau_s": (0.0, True, "s"),
        "release_tau_s": (0.0, True, "s"),
    }
    for field, (low, strict, unit) in bounds.items():
        value = getattr(vacuum, field)
        if not (math.isfinite(value) and (value > low if strict else value >= low)):
            relation = ">" if strict else ">="
            raise ScenarioError(
                f"{path}: key 'vacuum.{field}': must be {relation} {low:g} {unit}, "
                f"got {value}"
            )
    fraction = vacuum.part_present_fraction
    if not (math.isfinite(fraction) and 0.0 < fraction < 1.0):
        raise ScenarioError(
            f"{path}: key 'vacuum.part_present_fraction': must be in (0, 1), "
            f"got {fraction}"
        )
