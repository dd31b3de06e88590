"""The sections of a scenario file, as typed dataclasses.

One dataclass per YAML section that is not the whole scenario
(:class:`~rt_drake.model.scenario.Scenario` holds them): ``robot``
(:class:`RobotConfig`), each of ``objects`` (:class:`ObjectConfig`),
``random_transport`` (:class:`RandomTransport` and its :class:`Region`),
``planning`` (:class:`PlanningConfig`) and ``tool``
(:class:`ToolConfig` of :class:`ToolCupConfig`). Their fields are the keys
``yaml_load_typed`` accepts; their values are checked by
:mod:`rt_drake.model.scenario_checks`.

Poses are ``pydrake.common.schema.Transform`` (metres, and degrees in
``!Rpy {deg: [roll, pitch, yaw]}``), expressed in the world frame W unless a
field says otherwise.
"""

import dataclasses
import math

from pydrake.common.schema import Transform

from rt_drake.contact import CupMount, CupParameters, CupStiffness, ToolParameters
from rt_drake.model.frames import DEFAULT_CUP_FRAME
from rt_drake.types.object_uncertainty import ObjectUncertainty

#: The word of ``approach_offset`` for lines from the cell's geometry.
AUTO = "auto"

#: The word of ``planning.grasp_margin`` for a margin chosen per MOVE from
#: the bellows cup's ring (:func:`rt_drake.retiming.retime_for_ring`).
RING = "ring"


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
#: BENCHMARKS.md "The KTO reference").
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
            Or ``"ring"``: m chosen per MOVE, the least (within 0.01) for
            which the linear modes of the bellows cup ``cup_physics.cup``
            (with the held object) driven by that MOVE's planned wrench keep
            the wrench they carry in the unshrunk set
            (:func:`rt_drake.retiming.retime_for_ring`).
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
        shape_picks: With ``optimize_move``, also shape each blended pick's
            transit between its retreat and descent lines
            (:func:`rt_drake.shaping.shape_pick`; default off: it gains
            0-1.8 % of a pick on the paper's cell and none under the
            shipped cell's jerk limits, for 0.1-0.7 s of CPU per pick,
            which the vacuum-sensor cell's short waits put on the
            critical path, BENCHMARKS.md).
    """

    optimize_move: bool = True
    max_tilt_deg: float = 45.0
    max_evaluations: int = MOVE_EVALUATIONS
    budget_s: float | None = None
    approach_offset: float | str = 0.2
    approach_clearance: float = 0.02
    grasp_margin: float | str = 0.0
    grasp_ramp_s: float | None = None
    shape_picks: bool = False

    @property
    def ring_margin(self) -> bool:
        """Whether ``grasp_margin`` is chosen per MOVE from the bellows' ring."""
        return self.grasp_margin == RING

    @property
    def fixed_margin(self) -> float:
        """``grasp_margin`` as a number; 0 with ``ring`` (its search starts there)."""
        return 0.0 if isinstance(self.grasp_margin, str) else float(self.grasp_margin)


@dataclasses.dataclass
class StiffnessConfig:
    """A bellows cup's stiffness as the planner states it (``stiffness:``).

    About the cup frame C's origin, in C (:class:`~rt_drake.contact.
    CupStiffness`); every field is required (NaN: not given).

    Attributes:
        axial: N/m, along the cup's axis.
        lateral: N/m, across it.
        tilt: N m/rad, about an axis across it.
        torsion: N m/rad, about it.
    """

    axial: float = math.nan
    lateral: float = math.nan
    tilt: float = math.nan
    torsion: float = math.nan

    def parameters(self) -> CupStiffness:
        """The stiffness (validated: each value finite and > 0)."""
        return CupStiffness(
            axial=self.axial,
            lateral=self.lateral,
            tilt=self.tilt,
            torsion=self.torsion,
        )


@dataclasses.dataclass
class ToolCupConfig:
    """One cup of a multi-cup tool: its pose in the tool frame and its model.

    Attributes:
        pose: X_TC, pose of the cup frame C in the tool frame T (the frame
            ``robot.cup_frame`` names); C's +z points out of the cup.
        radius, points, friction, sides, suction_force, max_normal_force:
            The cup's :class:`~rt_drake.contact.CupParameters` (same defaults).
        stiffness: The bellows' stiffness, for ``tool.load_sharing:
            stiffness`` (None: not stated).
        peel_fraction: The cup's compliant lip (``cup.peel_fraction``): each
            cup's share of the load keeps its tilting moment within ``c r
            (P A + f_z)``; only with ``load_sharing: stiffness``, which
            gives each cup its share (None: the rigid rim).
    """

    pose: Transform = dataclasses.field(default_factory=Transform)
    radius: float = CupParameters.radius
    points: int = CupParameters.points
    friction: float = CupParameters.friction
    sides: int = CupParameters.sides
    suction_force: float = CupParameters.suction_force
    max_normal_force: float = CupParameters.max_normal_force
    stiffness: StiffnessConfig | None = None
    peel_fraction: float | None = None

    def parameters(self) -> CupParameters:
        """The cup's point-contact model (validated)."""
        return CupParameters(
            radius=self.radius,
            points=self.points,
            friction=self.friction,
            sides=self.sides,
            suction_force=self.suction_force,
            max_normal_force=self.max_normal_force,
            peel_fraction=self.peel_fraction,
        )


@dataclasses.dataclass
class ToolConfig:
    """A tool carrying several suction cups (``tool: {cups: [...]}``).

    Attributes:
        cups: The cups, each posed in the tool frame.
        load_sharing: How the cups split the load, ``elastic`` (a rigid tool:
            the rims as equal springs; the cups in the tool frame's z = 0
            plane, axes along z), ``stiffness`` (compliant cups: the whole
            wrench split by each cup's ``stiffness``, every cup's share in its
            own set) or ``any`` (every split; over-claims for a rigid tool);
            see :class:`~rt_drake.contact.LoadSharing`.
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
                    None if entry.stiffness is None else entry.stiffness.parameters(),
                )
            )
        return ToolParameters(cups=tuple(mounts))


__all__ = [
    "AUTO",
    "RING",
    "MOVE_EVALUATIONS",
    "ObjectConfig",
    "PlanningConfig",
    "RandomTransport",
    "Region",
    "RobotConfig",
    "StiffnessConfig",
    "ToolConfig",
    "ToolCupConfig",
]
