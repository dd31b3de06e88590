"""Checks of a scenario's sections, one function per section.

Each raises a one-line :class:`~rt_drake.errors.ScenarioError` naming the
file, the key path (``objects[1].model``) and the offending value; the YAML
reader (:mod:`rt_drake.model.yaml_schema`) has already refused unknown keys
and wrong types. :func:`rt_drake.model.scenario.load_scenario` calls them in
this order: objects, robot, random transport, cup, tool, vacuum
(:func:`rt_drake.model.vacuum.check_vacuum`), planning, cup physics. Units
(m, deg, s, rad/s...) are those of each field in
:mod:`rt_drake.model.scenario_sections`.
"""

from collections.abc import Sequence
from pathlib import Path

from rt_drake.contact import CupParameters, LoadSharing
from rt_drake.contact.load_sharing import rim_springs
from rt_drake.errors import InputError, ScenarioError
from rt_drake.model.cup_physics import CupPhysics, CupPhysicsConfig, load_bellows_cup
from rt_drake.model.object_geometry import object_box
from rt_drake.model.object_model import model_file, read_model_inertia
from rt_drake.model.scenario_sections import (
    AUTO,
    MOVE_EVALUATIONS,
    RING,
    ObjectConfig,
    PlanningConfig,
    RandomTransport,
    RobotConfig,
    ToolConfig,
    ToolCupConfig,
)

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


def check_objects(path: Path, objects: Sequence[ObjectConfig]) -> None:
    """At least one object, each valid.

    Each object is named once, has a model file whose inertia is valid,
    fixed poses, an approach offset and an uncertainty in range.
    """
    if not objects:
        raise ScenarioError(
            f"{path}: key 'objects': a scenario needs at least one object, got none"
        )
    names = [obj.name for obj in objects]
    for index, obj in enumerate(objects):
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


def check_random_transport(
    path: Path, transport: RandomTransport, names: Sequence[str]
) -> None:
    """A known object (one of ``names``) and well-formed regions.

    Each region has 3-number ``lower`` <= ``upper`` (m, world) and a
    ``yaw_deg`` interval [low, high] (deg).
    """
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
            raise ScenarioError(f"{key}': lower {region.lower} > upper {region.upper}")
        if len(region.yaw_deg) != 2 or region.yaw_deg[0] > region.yaw_deg[1]:
            raise ScenarioError(
                f"{key}.yaw_deg': expected [low, high], got {region.yaw_deg}"
            )


def check_cup(path: Path, cup: CupParameters) -> None:
    """The one cup's parameters in range and a friction > 0."""
    try:
        cup.validate()
    except InputError as error:
        raise ScenarioError(f"{path}: key 'cup': {error}") from None
    _check_grip(path, "cup", cup.friction, cup.friction_min)


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


def check_planning(path: Path, planning: PlanningConfig) -> None:
    """``max_tilt_deg`` in [0, 90), ``max_evaluations`` >= 1, no ``budget_s``.

    And the approach keys, ``grasp_margin`` in [0, 0.9] or ``ring``, and
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
    margin = planning.grasp_margin
    if (
        isinstance(margin, str)
        and margin != RING
        or not (isinstance(margin, str) or 0.0 <= margin <= 0.9)
    ):
        raise ScenarioError(
            f"{path}: key 'planning.grasp_margin': must be in [0, 0.9] (a share "
            f"of g) or '{RING}', got {margin!r}"
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
    planar rims it needs (:func:`~rt_drake.contact.load_sharing.rim_springs`);
    for ``stiffness``, every cup's ``stiffness`` (four values > 0); a cup's
    ``peel_fraction`` on a tool of several cups only with ``stiffness``.

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
        _check_stiffness(where, entry, tool.load_sharing)
        sharing = tool.load_sharing
        if entry.peel_fraction is not None and len(tool.cups) > 1:
            if sharing != LoadSharing.STIFFNESS.value:
                raise ScenarioError(
                    f"{where}.peel_fraction': needs '{key}.load_sharing: "
                    f"stiffness' (each cup's share in its own set with its peel "
                    f"rows), got load_sharing {sharing!r}"
                )
    parameters = tool.parameters()
    if tool.load_sharing == LoadSharing.ELASTIC.value and len(parameters.cups) > 1:
        try:
            rim_springs(parameters)
        except InputError as error:
            raise ScenarioError(f"{path}: key '{key}.load_sharing': {error}") from None


def _check_stiffness(where: str, entry: ToolCupConfig, load_sharing: str) -> None:
    """A stated stiffness is four values > 0; ``stiffness`` sharing needs it."""
    if entry.stiffness is None:
        if load_sharing == LoadSharing.STIFFNESS.value:
            raise ScenarioError(
                f"{where}.stiffness': load_sharing 'stiffness' needs every cup's "
                "stiffness {axial, lateral, tilt, torsion}, got none"
            )
        return
    try:
        entry.stiffness.parameters()
    except InputError as error:
        name = str(error).removeprefix("cup stiffness ").split(" ", 1)[0]
        raise ScenarioError(f"{where}.stiffness.{name}': {error}") from None


def check_robot(path: Path, robot: RobotConfig) -> None:
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
    "MAX_APPROACH_CLEARANCE",
    "MAX_GRASP_RAMP_S",
    "check_cup",
    "check_cup_physics",
    "check_objects",
    "check_planning",
    "check_random_transport",
    "check_robot",
    "check_tool",
]
