"""Scenarios: typed dataclasses loaded with ``yaml_load_typed``.

A scenario file names the cell (Drake model directives), the robot's home
configuration and limits, the suction cup, the objects with their start and
goal poses, and the vacuum (:mod:`rt_drake.model.vacuum`: attach and
detach behaviour) and how MOVEs are planned (``planning``: the MOVE path
optimiser of issue 13). :func:`load_scenario` refuses,
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

from pydrake.common.schema import Transform
from pydrake.common.yaml import yaml_load_typed
from pydrake.multibody.parsing import ModelDirective

from rt_drake import arguments
from rt_drake.contact import CupMount, CupParameters, LoadSharing, ToolParameters
from rt_drake.contact.load_sharing import rim_springs
from rt_drake.contact.tool import is_identity_pose
from rt_drake.errors import InputError, ScenarioError
from rt_drake.model.cup_physics import CupPhysics, CupPhysicsConfig, load_bellows_cup
from rt_drake.model.frames import DEFAULT_CUP_FRAME
from rt_drake.model.object_geometry import object_box
from rt_drake.model.object_model import (
    model_file,
    read_model_inertia,
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
from rt_drake.types.object_uncertainty import ObjectUncertainty

#: Largest scenario file read, bytes (the shipped ones are about 3 kB).
MAX_SCENARIO_BYTES = 2**20


@dataclasses.dataclass
class RobotConfig:
    """The arm: its model instance, home configuration and limit overrides.

    ``cup_frame`` names the frame C of the cup (or tool) the arm carries,
    possibly scoped (``"suction_tool::suction_cup"``).

    Empty limit lists mean "take them from the model" (URDF ``velocity``,
    ``drake:acceleration`` and ``effort``). Units: rad, rad/s, rad/s^2, N m,
    rad/s^3. ``jerk_limits`` empty: the jerk is not limited (a URDF has none).
    ``limit_torques``: retime under the torque limits too (inverse dynamics,
    held object included), for an arm whose maker publishes torque limits
    rather than acceleration limits (e.g. the UR5e).
    ``joint_names``: the controller's name of each plant joint it renames
    (plant name -> controller name), for exports; the others keep the
    plant's name. Every key must be a joint of the plant (checked when a
    plant is at hand, by :mod:`rt_drake.export`); the names are distinct.
    ``command_period_s``: s, the simulated controller receives the motion
    sampled at this period and interpolates between the samples
    (:mod:`rt_drake.simulation`; e.g. 0.008 for Denso b-CAP slave mode);
    None: the command is continuous.
    """

    model_instance: str = "vs060"
    home: list[float] = dataclasses.field(default_factory=list)
    cup_frame: str = DEFAULT_CUP_FRAME
    joint_names: dict[str, str] = dataclasses.field(default_factory=dict)
    velocity_limits: list[float] = dataclasses.field(default_factory=list)
    acceleration_limits: list[float] = dataclasses.field(default_factory=list)
    torque_limits: list[float] = dataclasses.field(default_factory=list)
    limit_torques: bool = False
    command_period_s: float | None = None
    jerk_limits: list[float] = dataclasses.field(default_factory=list)


@dataclasses.dataclass
class ObjectConfig:
    """One object to pick and place.

    Attributes:
        name: model instance name in the plant (unique in the scenario).
        model: ``package://rt_drake/...`` URL (or file path) of its SDF.
        start: X_WO, pose of the object's body frame in the world at the start.
        goal: X_WO at the place pose.
        approach_offset: m, the length of the vertical lines above the pick
            and the place (the approach pose is the grasp pose raised by
            it); ``"auto"``: the shortest lines that keep the cup and the
            object ``planning.approach_clearance`` clear of the cell
            (:mod:`rt_drake.planning._line_heights`); absent: the scenario's
            ``planning.approach_offset``.
        grasp: X_OC, pose of the cup frame C in the object frame O while held
            (cup +z pointing into the object).
        uncertainty: What is not known about its inertia (None: known
            exactly): the MOVE is then retimed to hold every object of the
            set (:class:`~rt_drake.types.object_uncertainty.ObjectUncertainty`).
    """

    name: str = ""
    model: str = ""
    start: Transform = dataclasses.field(default_factory=Transform)
    goal: Transform = dataclasses.field(default_factory=Transform)
    approach_offset: float | str | None = None
    grasp: Transform = dataclasses.field(default_factory=Transform)
    uncertainty: ObjectUncertainty | None = None


@dataclasses.dataclass
class Region:
    """An axis-aligned box of object positions (m, world) and a yaw range (deg)."""

    lower: list[float] = dataclasses.field(default_factory=lambda: [0.0, 0.0, 0.0])
    upper: list[float] = dataclasses.field(default_factory=lambda: [0.0, 0.0, 0.0])
    yaw_deg: list[float] = dataclasses.field(default_factory=lambda: [0.0, 0.0])


@dataclasses.dataclass
class RandomTransport:
    """Where Table I's random start and goal poses of ``object`` are sampled.

    Attributes:
        object: The object carried.
        start_region, goal_region: Where its start and goal poses are drawn.
        start_on_cup: Start each trial with the object already sealed on the
            cup at its start pose (an object in free space, as the paper's
            regions): the arm starts at a grasp configuration found by IK
            instead of picking the object from home.
    """

    object: str = ""
    start_region: Region = dataclasses.field(default_factory=Region)
    goal_region: Region = dataclasses.field(default_factory=Region)
    start_on_cup: bool = False


#: Candidate paths the MOVE optimiser scores per MOVE by default (its search
#: budget; a median of 0.13-0.14 s of CPU on Table I's transports,
#: BENCHMARKS.md "The shaped MOVE against the KTO reference").
MOVE_EVALUATIONS = 240


@dataclasses.dataclass
class PlanningConfig:
    """How MOVEs are planned (issues 13 and 27).

    Attributes:
        optimize_move: Shape each MOVE path for speed under the grasp
            constraint (:func:`rt_drake.shaping.optimize_move`)
            instead of keeping the planner's spline through its anchors
            (default on).
        max_tilt_deg: Largest angle (deg) between the cup axis and gravity
            an optimised MOVE may reach, in [0, 90); 0 keeps the cup
            vertical (open containers).
        max_evaluations: The optimiser's budget per MOVE, in candidate
            paths scored (>= 1): no clock is read, so the same scenario and
            seed give the same path on an idle or a loaded machine.
        budget_s: Removed (a wall-clock budget made the path depend on the
            machine's load); a file that sets it is refused with a message
            naming ``max_evaluations``.
        approach_offset: The objects' ``approach_offset`` where they give
            none: metres, or ``"auto"``.
        approach_clearance: m, how far the cup and the held object stay from
            the rest of the cell at the top of an ``auto`` line, in (0, 0.2].
        grasp_margin: Share m of the grasp set kept free, in [0, 0.9]: MOVEs
            are retimed under ``F w <= (1 - m) g``, so that a controller's
            interpolation between samples stays in the set (docs: the export
            guide gives the m that covers each interpolation and period).
        grasp_ramp_s: s, a margin for a compliant cup (None: none). The MOVE
            retimed under the grasp constraint reaches each joint's
            acceleration limit a_j in this time at the earliest: its jerk
            limit is ``min(robot.jerk_limits[j], a_j / grasp_ramp_s)``, so that
            an acceleration ramp as long as the cup's longest natural period
            leaves its modes no residual vibration
            (``tools/bellows_jerk_limits.py``, docs: the bellows cup guide).
            Applied with or without ``robot.jerk_limits`` (it is part of the
            grasp's margin, not a robot limit); motions without the grasp
            constraint keep the robot's own jerk limits. In (0, 2] s.
    """

    optimize_move: bool = True
    max_tilt_deg: float = 45.0
    max_evaluations: int = MOVE_EVALUATIONS
    budget_s: float | None = None
    approach_offset: float | str = 0.2
    approach_clearance: float = 0.02
    grasp_margin: float = 0.0
    grasp_ramp_s: float | None = None


@dataclasses.dataclass
class ToolCupConfig:
    """One cup of a multi-cup tool: its pose in the tool frame and its model.

    Attributes:
        pose: X_TC, pose of the cup frame C in the tool frame T (the frame
            ``robot.cup_frame`` names); C's +z points out of the cup.
        radius, points, friction, sides, suction_force, max_normal_force:
            The cup's :class:`~rt_drake.contact.CupParameters` (same defaults).
    """

    pose: Transform = dataclasses.field(default_factory=Transform)
    radius: float = CupParameters.radius
    points: int = CupParameters.points
    friction: float = CupParameters.friction
    sides: int = CupParameters.sides
    suction_force: float = CupParameters.suction_force
    max_normal_force: float = CupParameters.max_normal_force

    def parameters(self) -> CupParameters:
        """The cup's point-contact model (validated)."""
        return CupParameters(
            radius=self.radius,
            points=self.points,
            friction=self.friction,
            sides=self.sides,
            suction_force=self.suction_force,
            max_normal_force=self.max_normal_force,
        )


@dataclasses.dataclass
class ToolConfig:
    """A tool carrying several suction cups (``tool: {cups: [...]}``).

    Attributes:
        cups: The cups, each posed in the tool frame.
        load_sharing: How the cups split the load, ``elastic`` (a rigid tool:
            the rims as equal springs; the cups in the tool frame's z = 0
            plane, axes along z) or ``any`` (every split; over-claims for a
            rigid tool); see :class:`~rt_drake.contact.LoadSharing`.
    """

    cups: list[ToolCupConfig] = dataclasses.field(default_factory=list)
    load_sharing: str = "elastic"

    def parameters(self) -> ToolParameters:
        """The tool's cups and their poses X_TC (validated)."""
        mounts = []
        for entry in self.cups:
            X_TC = entry.pose.GetDeterministicValue()
            mounts.append(
                CupMount(
                    entry.parameters(),
                    X_TC.rotation().matrix(),
                    X_TC.translation(),
                )
            )
        return ToolParameters(cups=tuple(mounts))


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


#: The word of ``approach_offset`` for lines from the cell's geometry.
AUTO = "auto"
#: m, the largest ``planning.approach_clearance``.
MAX_APPROACH_CLEARANCE = 0.2
#: s, the longest ``planning.grasp_ramp_s``.
MAX_GRASP_RAMP_S = 2.0


def _check_offset(where: str, value: float | str | None) -> None:
    """An approach offset: None, ``"auto"`` or a number >= 0 (m)."""
    if value is None or value == AUTO:
        return
    if isinstance(value, str):
        raise ScenarioError(
            f"{where}: must be a length in m or '{AUTO}', got {value!r}"
        )
    if value < 0:
        raise ScenarioError(f"{where}: must be >= 0 m, got {value}")


def _check_uncertainty(path: Path, key: str, obj: ObjectConfig) -> None:
    """The widths in range and the CoM box inside the object's box."""
    assert obj.uncertainty is not None
    try:
        obj.uncertainty.validate()
        if any(obj.uncertainty.com):
            p_OoScm_O, half_extents = object_box(obj.model, obj.name)
            obj.uncertainty.check_inside(p_OoScm_O, half_extents)
    except InputError as error:
        raise ScenarioError(f"{path}: key '{key}': {error}") from None


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
        _check_offset(f"{where}.approach_offset'", obj.approach_offset)
        for pose in ("start", "goal", "grasp"):
            if not getattr(obj, pose).IsDeterministic():
                raise ScenarioError(
                    f"{where}.{pose}': must be a fixed pose, not a random one"
                )
        if obj.uncertainty is not None:
            _check_uncertainty(path, f"objects[{index}].uncertainty", obj)
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
    _check_grip(path, "cup", scenario.cup.friction, scenario.cup.friction_min)
    if scenario.tool is not None:
        check_tool(path, scenario.tool)
    check_vacuum(path, scenario.vacuum)
    _check_planning(path, scenario.planning)
    check_cup_physics(path, scenario.cup_physics)


def check_cup_physics(path: Path | str, config: CupPhysicsConfig) -> None:
    """A known ``cup_physics.kind``; for bellows, a loadable catalogue cup.

    Raises:
        ScenarioError: ``<path>: key 'cup_physics.<field>': ...``.
    """
    try:
        physics = config.physics
    except ScenarioError as error:
        raise ScenarioError(f"{path}: {error}") from None
    if physics is CupPhysics.BELLOWS:
        try:
            load_bellows_cup(config.cup)
        except ScenarioError as error:
            raise ScenarioError(f"{path}: key 'cup_physics.cup': {error}") from None


def _check_grip(
    path: Path, key: str, friction: float, friction_min: float | None
) -> None:
    """Refuse friction <= 0: such a cup holds no object.

    A frictionless rim exerts no sideways force, so its wrench set has no
    interior and no grasp constraint can be built from it.
    """
    for name, value in (("friction", friction), ("friction_min", friction_min)):
        if value is not None and not value > 0.0:
            raise ScenarioError(
                f"{path}: key '{key}.{name}': must be > 0 to hold an object (a "
                f"frictionless rim exerts no sideways force), got {value!r}"
            )


def _check_planning(path: Path, planning: PlanningConfig) -> None:
    """``max_tilt_deg`` in [0, 90), ``max_evaluations`` >= 1, no ``budget_s``.

    And the approach keys, ``grasp_margin`` in [0, 0.9] and
    ``grasp_ramp_s`` None or in (0, :data:`MAX_GRASP_RAMP_S`].
    """
    if not 0 <= planning.max_tilt_deg < 90:
        raise ScenarioError(
            f"{path}: key 'planning.max_tilt_deg': must be in [0, 90) deg, got "
            f"{planning.max_tilt_deg}"
        )
    if planning.budget_s is not None:
        raise ScenarioError(
            f"{path}: key 'planning.budget_s' is no longer read (a wall-clock "
            f"budget made the MOVE depend on the machine's load): set "
            f"'planning.max_evaluations' (paths scored, default {MOVE_EVALUATIONS})"
        )
    if not planning.max_evaluations >= 1:
        raise ScenarioError(
            f"{path}: key 'planning.max_evaluations': must be >= 1, got "
            f"{planning.max_evaluations}"
        )
    _check_offset(f"{path}: key 'planning.approach_offset'", planning.approach_offset)
    if not 0 < planning.approach_clearance <= MAX_APPROACH_CLEARANCE:
        raise ScenarioError(
            f"{path}: key 'planning.approach_clearance': must be in "
            f"(0, {MAX_APPROACH_CLEARANCE}] m, got {planning.approach_clearance}"
        )
    if not 0.0 <= planning.grasp_margin <= 0.9:
        raise ScenarioError(
            f"{path}: key 'planning.grasp_margin': must be in [0, 0.9] (a share "
            f"of g), got {planning.grasp_margin}"
        )
    ramp = planning.grasp_ramp_s
    if ramp is not None and not 0.0 < ramp <= MAX_GRASP_RAMP_S:
        raise ScenarioError(
            f"{path}: key 'planning.grasp_ramp_s': must be in "
            f"(0, {MAX_GRASP_RAMP_S}] s, got {ramp}"
        )


def check_tool(path: Path, tool: ToolConfig, key: str = "tool") -> None:
    """Check a tool: its cups, their parameters and poses, its load sharing.

    At least one cup; each cup's parameters in range and its pose fixed; a
    known ``load_sharing``, and for ``elastic`` with several cups, the
    planar rims it needs (:func:`~rt_drake.contact.load_sharing.rim_springs`).

    Args:
        path: The file, for messages.
        tool: The tool as loaded.
        key: Its key path in the file (a campaign's ``cups[1].tool``).

    Raises:
        ScenarioError: ``<path>: key '<key>.cups[i].<field>': ...``.
    """
    if not tool.cups:
        raise ScenarioError(f"{path}: key '{key}.cups': a tool needs at least one cup")
    choices = tuple(m.value for m in LoadSharing)
    if tool.load_sharing not in choices:
        raise ScenarioError(
            f"{path}: key '{key}.load_sharing': must be one of "
            f"{', '.join(choices)}, got {tool.load_sharing!r}"
        )
    for index, entry in enumerate(tool.cups):
        where = f"{path}: key '{key}.cups[{index}]"
        if not entry.pose.IsDeterministic():
            raise ScenarioError(
                f"{where}.pose': must be a fixed pose, not a random one"
            )
        try:
            entry.parameters()
        except InputError as error:
            message = str(error).removeprefix("cup ")
            name = message.split(" ", 1)[0]
            raise ScenarioError(f"{where}.{name}': {message}") from None
        _check_grip(path, f"{key}.cups[{index}]", entry.friction, None)
    parameters = tool.parameters()
    if tool.load_sharing == LoadSharing.ELASTIC.value and len(parameters.cups) > 1:
        try:
            rim_springs(parameters)
        except InputError as error:
            raise ScenarioError(f"{path}: key '{key}.load_sharing': {error}") from None


def _check_robot(path: Path, robot: RobotConfig) -> None:
    """Limit lists are empty or as long as ``home``, and > 0."""
    joints = len(robot.home)
    period = robot.command_period_s
    if period is not None and not 0.0 < period <= 0.1:
        raise ScenarioError(
            f"{path}: key 'robot.command_period_s': must be in (0, 0.1] s, got {period}"
        )
    for field in (
        "velocity_limits",
        "acceleration_limits",
        "torque_limits",
        "jerk_limits",
    ):
        values = getattr(robot, field)
        key = f"{path}: key 'robot.{field}'"
        if values and len(values) != joints:
            raise ScenarioError(
                f"{key}: {len(values)} values but key 'robot.home' has "
                f"{joints} values: give one per joint in each"
            )
        if any(v <= 0 for v in values):
            raise ScenarioError(f"{key}: limits must be > 0, got {values}")
    key = f"{path}: key 'robot.joint_names'"
    for plant_name, name in robot.joint_names.items():
        if not plant_name.strip() or not name.strip():
            raise ScenarioError(f"{key}: empty joint name in {plant_name!r}: {name!r}")
    names = list(robot.joint_names.values())
    repeated = sorted({name for name in names if names.count(name) > 1})
    if repeated:
        raise ScenarioError(f"{key}: controller name '{repeated[0]}' is given twice")


__all__ = [
    "MAX_DEPTH",
    "MAX_SCENARIO_BYTES",
    "MOVE_EVALUATIONS",
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
