"""Scenarios: typed dataclasses loaded with ``yaml_load_typed``.

A scenario file names the cell (Drake model directives), the robot's home
configuration and limits, the suction cup, the objects with their start and
goal poses, and the vacuum (:mod:`rt_drake.model.vacuum`: attach and
detach behaviour) and how MOVEs are planned (``planning``: the MOVE path
optimiser of issue 13). This module holds the whole :class:`Scenario` and
:func:`load_scenario`; :mod:`rt_drake.model.scenario_sections` the
dataclass of each section (re-exported here) and
:mod:`rt_drake.model.scenario_checks` the check of each section's values.
:func:`load_scenario` refuses,
with a one-line :class:`~rt_drake.errors.ScenarioError` that names the file,
the key path (``objects[1].start.translation``) and the offending value:
unknown keys, a value of the wrong type, null where a value is needed, NaN
or inf anywhere, duplicate keys (YAML would keep the last one silently),
aliases (``*name``: an alias bomb expands exponentially), nesting deeper
than :data:`MAX_DEPTH` (:mod:`rt_drake.model.yaml_schema`), files over
:data:`MAX_SCENARIO_BYTES` or not UTF-8,
a scenario without objects, object models whose inertia is missing or not
physically valid (:mod:`rt_drake.model.object_model`), and inconsistent names.

Poses are ``pydrake.common.schema.Transform`` (metres, and degrees in
``!Rpy {deg: [roll, pitch, yaw]}``), expressed in the world frame W unless a
field says otherwise.
"""

import dataclasses
from pathlib import Path

from pydrake.common.yaml import yaml_load_typed
from pydrake.multibody.parsing import ModelDirective

from rt_drake import arguments
from rt_drake.contact import CupParameters, ToolParameters
from rt_drake.contact.tool import is_identity_pose
from rt_drake.errors import ScenarioError
from rt_drake.model.cup_physics import CupPhysicsConfig
from rt_drake.model.scenario_checks import (
    check_cup,
    check_cup_physics,
    check_objects,
    check_planning,
    check_random_transport,
    check_robot,
    check_tool,
)
from rt_drake.model.scenario_sections import (
    AUTO,
    MOVE_EVALUATIONS,
    RING,
    ObjectConfig,
    PlanningConfig,
    RandomTransport,
    Region,
    RobotConfig,
    ToolConfig,
    ToolCupConfig,
)
from rt_drake.model.vacuum import (
    Vacuum,
    VacuumModel,
    check_renamed,
    check_vacuum,
)
from rt_drake.model.yaml_schema import (
    MAX_DEPTH,
    check_schema,
    locate,
    read_yaml,
)

#: Largest scenario file read, bytes (the shipped ones are about 3 kB).
MAX_SCENARIO_BYTES = 2**20


@dataclasses.dataclass
class Scenario:
    """Everything a cycle needs; see ``scenarios/stack_four_objects.yaml``.

    ``cup`` is one cup whose frame is the tool frame; ``tool`` (instead of
    ``cup``) a tool of several cups, each posed in the tool frame.
    """

    directives: list[ModelDirective] = dataclasses.field(default_factory=list)
    robot: RobotConfig = dataclasses.field(default_factory=RobotConfig)
    cup: CupParameters = dataclasses.field(default_factory=CupParameters)
    tool: ToolConfig | None = None
    objects: list[ObjectConfig] = dataclasses.field(default_factory=list)
    vacuum: Vacuum = dataclasses.field(default_factory=Vacuum)
    random_transport: RandomTransport | None = None
    planning: PlanningConfig = dataclasses.field(default_factory=PlanningConfig)
    #: The simulation's cup model (``rim`` or ``bellows``), independent of
    #: the planner's ``cup`` (:mod:`rt_drake.model.cup_physics`).
    cup_physics: CupPhysicsConfig = dataclasses.field(default_factory=CupPhysicsConfig)
    #: The file it was loaded from, for messages (set by load_scenario; not
    #: a YAML key).
    source: str = dataclasses.field(default="", metadata={"yaml": False})

    def key(self, key_path: str) -> str:
        """``"<file>: key '<key_path>'"``, the start of a message about a key."""
        where = f"key '{key_path}'"
        return f"{self.source}: {where}" if self.source else where

    def tool_parameters(self) -> ToolParameters:
        """The tool's cups and poses: ``tool``, or ``cup`` at the tool frame."""
        if self.tool is None:
            return ToolParameters.single(self.cup)
        return self.tool.parameters()

    def single_cup(self, what: str) -> CupParameters:
        """The one cup, for the parts that model a single cup (``what``).

        Raises:
            ScenarioError: the scenario's ``tool`` has several cups (or one
                cup away from the tool frame): ``what`` does not take them
                yet; retime such a tool with ``rt-drake retime`` or
                ``GraspConstraint.for_tool``.
        """
        if self.tool is None:
            return self.cup
        tool = self.tool_parameters()
        mount = tool.cups[0]
        if len(tool.cups) == 1 and is_identity_pose(mount):
            return mount.cup
        raise ScenarioError(
            f"{self.key('tool')}: {what} takes one cup at the tool frame, got "
            f"{len(tool.cups)} cup(s); retime a multi-cup tool with "
            "rt-drake retime or GraspConstraint.for_tool"
        )

    def approach_offset(self, name: str) -> float | None:
        """Object ``name``'s line length (m), or None for ``"auto"``."""
        value = self.object(name).approach_offset
        if value is None:
            value = self.planning.approach_offset
        return None if value == AUTO else float(value)

    def with_cup_physics(self, kind: str | None) -> "Scenario":
        """This scenario simulated with ``kind`` of cup (None: unchanged).

        Raises:
            ScenarioError: ``kind`` is not rim or bellows.
        """
        if kind is None:
            return self
        config = dataclasses.replace(self.cup_physics, kind=kind)
        check_cup_physics(self.source or "cup physics", config)
        return dataclasses.replace(self, cup_physics=config)

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
    path = arguments.path(path, "path", where="load_scenario", error=ScenarioError)
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
    raw = read_yaml(path, text)
    check_renamed(path, raw)
    check_schema(path, raw, Scenario)
    if "cup" in raw and "tool" in raw:
        raise ScenarioError(
            f"{path}: keys 'cup' and 'tool': give one cup ('cup') or a tool of "
            "several cups ('tool'), not both"
        )
    try:
        scenario = yaml_load_typed(schema=Scenario, data=text)
    except (RuntimeError, ValueError, TypeError) as error:
        raise ScenarioError(locate(path, raw, str(error))) from None
    scenario.source = str(path)
    _check_semantics(path, scenario)
    return scenario


def _check_semantics(path: Path, scenario: Scenario) -> None:
    """Each section's values (:mod:`rt_drake.model.scenario_checks`)."""
    check_objects(path, scenario.objects)
    check_robot(path, scenario.robot)
    if scenario.random_transport is not None:
        names = [obj.name for obj in scenario.objects]
        check_random_transport(path, scenario.random_transport, names)
    check_cup(path, scenario.cup)
    if scenario.tool is not None:
        check_tool(path, scenario.tool)
    check_vacuum(path, scenario.vacuum)
    check_planning(path, scenario.planning)
    check_cup_physics(path, scenario.cup_physics)


__all__ = [
    "AUTO",
    "MAX_DEPTH",
    "MAX_SCENARIO_BYTES",
    "MOVE_EVALUATIONS",
    "RING",
    "ObjectConfig",
    "PlanningConfig",
    "RandomTransport",
    "Region",
    "RobotConfig",
    "Scenario",
    "ToolConfig",
    "ToolCupConfig",
    "Vacuum",
    "VacuumModel",
    "check_cup_physics",
    "check_tool",
    "load_scenario",
]
