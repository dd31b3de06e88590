"""The simulated cup's physics: the scenario's ``cup_physics`` key and its catalogue.

The planner holds the object with the cup model of :mod:`rt_drake.contact`
(``cup``: rim points, a friction coefficient, a suction force). The
simulation may hold it with another, independent model, chosen by the
scenario's ``cup_physics`` key (:class:`CupPhysicsConfig`):

- ``kind: rim`` (the default): rigid spheres at the planner's rim points,
  with the planner's friction (:func:`rt_drake.model.plant.add_cup_rim`);
- ``kind: bellows``: a compliant bellows cup whose parameters come from a
  catalogue file ``models/cups/<name>.yaml`` (:class:`BellowsCup`), none of
  them read from the planner's ``cup``.

A catalogue file gives every parameter as ``{value: ..., source: "..."}``:
where the number comes from (a datasheet, Drake's suction-gripper example,
a derivation) or ``"no source"``. :func:`load_bellows_cup` refuses, with a
one-line :class:`~rt_drake.errors.ScenarioError` naming file, key and value,
unknown or missing keys, a value without a source, and values out of range.
(No ``from __future__ import annotations``: ``yaml_load_typed`` reads the
field types.)
"""

import dataclasses
import enum
import math
from pathlib import Path

from pydrake.common.yaml import yaml_load_typed

from rt_drake.errors import ScenarioError
from rt_drake.model.resources import models_dir
from rt_drake.model.yaml_schema import check_schema, locate, read_yaml

#: The catalogue cup of the shipped VS-060 scenarios.
DEFAULT_BELLOWS_CUP = "vs060_bellows"
#: Fewest lip points: the issue asks for a ring of at least 24.
MIN_LIP_POINTS = 24
#: Largest catalogue file read, bytes.
MAX_CUP_BYTES = 2**16


class CupPhysics(enum.Enum):
    """Which model holds the object in the simulation."""

    RIM = "rim"  # rigid spheres at the planner's rim points (the planner's mu)
    BELLOWS = "bellows"  # a compliant bellows cup from the catalogue


@dataclasses.dataclass
class CupPhysicsConfig:
    """The scenario's ``cup_physics`` key.

    Attributes:
        kind: ``rim`` or ``bellows`` (:class:`CupPhysics`).
        cup: The bellows cup: a catalogue name (``models/cups/<cup>.yaml``)
            or a path to such a file; read only when ``kind`` is bellows.
    """

    kind: str = CupPhysics.RIM.value
    cup: str = DEFAULT_BELLOWS_CUP

    @property
    def physics(self) -> CupPhysics:
        """``kind`` as the enum (ScenarioError if unknown)."""
        return cup_physics(self.kind, "cup_physics.kind")


@dataclasses.dataclass
class Sourced:
    """A number and where it comes from."""

    value: float = math.nan
    source: str = ""


@dataclasses.dataclass
class _CupFile:
    """The catalogue file's schema: every parameter sourced."""

    name: str = ""
    radius: Sourced = dataclasses.field(default_factory=Sourced)
    lip_points: Sourced = dataclasses.field(default_factory=Sourced)
    lip_stiffness: Sourced = dataclasses.field(default_factory=Sourced)
    lip_relaxation_time: Sourced = dataclasses.field(default_factory=Sourced)
    friction: Sourced = dataclasses.field(default_factory=Sourced)
    pressure: Sourced = dataclasses.field(default_factory=Sourced)
    effective_area: Sourced = dataclasses.field(default_factory=Sourced)
    vacuum_range: Sourced = dataclasses.field(default_factory=Sourced)
    leak_gap: Sourced = dataclasses.field(default_factory=Sourced)
    lip_mass: Sourced = dataclasses.field(default_factory=Sourced)
    lip_inertia: Sourced = dataclasses.field(default_factory=Sourced)
    axial_stiffness: Sourced = dataclasses.field(default_factory=Sourced)
    lateral_stiffness: Sourced = dataclasses.field(default_factory=Sourced)
    tilt_stiffness: Sourced = dataclasses.field(default_factory=Sourced)
    torsion_stiffness: Sourced = dataclasses.field(default_factory=Sourced)
    axial_damping: Sourced = dataclasses.field(default_factory=Sourced)
    lateral_damping: Sourced = dataclasses.field(default_factory=Sourced)
    tilt_damping: Sourced = dataclasses.field(default_factory=Sourced)
    torsion_damping: Sourced = dataclasses.field(default_factory=Sourced)


@dataclasses.dataclass(frozen=True)
class BellowsCup:
    """A compliant bellows suction cup, for the simulation only.

    Frames: T the tool's cup frame (``robot.cup_frame``), L the lip: a body
    whose frame coincides with T at rest, origin at the centre of the lip's
    contact face, +z out of the cup toward the object.

    Attributes:
        name: Catalogue name.
        radius: m, radius of the lip ring.
        lip_points: Compliant contact points on the ring (>= 24).
        lip_stiffness: N/m, normal stiffness of the whole ring (each point
            ``lip_stiffness / lip_points``).
        lip_relaxation_time: s, dissipation of the lip points in Drake's SAP
            contact (``material/relaxation_time``: the normal force is
            ``k (x - tau_d x')``; Hunt-Crossley is not used by SAP).
        friction: Lip-object friction coefficient (Coulomb, Drake's SAP).
        pressure: Pa, the vacuum below ambient while sealed.
        effective_area: m^2; the sealed pull is ``pressure * effective_area``.
        vacuum_range: m, centre gap over which the pull falls linearly to 0.
        leak_gap: m, a lip point lifted farther than this from the face
            breaks the seal (and the vacuum with it).
        lip_mass: kg, the lip body.
        lip_inertia: kg m^2, the lip body's moment of inertia about each of
            its axes through its origin.
        axial_stiffness, lateral_stiffness: N/m, bellows along z_L and in
            x_L, y_L.
        tilt_stiffness, torsion_stiffness: N m/rad, about x_L, y_L and z_L.
        axial_damping, lateral_damping: N s/m.
        tilt_damping, torsion_damping: N m s/rad.
        sources: Per parameter, where its value comes from.
    """

    name: str
    radius: float
    lip_points: int
    lip_stiffness: float
    lip_relaxation_time: float
    friction: float
    pressure: float
    effective_area: float
    vacuum_range: float
    leak_gap: float
    lip_mass: float
    lip_inertia: float
    axial_stiffness: float
    lateral_stiffness: float
    tilt_stiffness: float
    torsion_stiffness: float
    axial_damping: float
    lateral_damping: float
    tilt_damping: float
    torsion_damping: float
    sources: dict[str, str] = dataclasses.field(default_factory=dict, compare=False)

    @property
    def suction_force(self) -> float:
        """N, the full sealed pull ``P A``."""
        return self.pressure * self.effective_area

    def scaled(self, **factors: float) -> "BellowsCup":
        """This cup with some parameters multiplied (a sensitivity sweep)."""
        return dataclasses.replace(
            self, **{k: getattr(self, k) * f for k, f in factors.items()}
        )


def cup_physics(kind: str, key: str) -> CupPhysics:
    """``kind`` as :class:`CupPhysics`; ScenarioError naming ``key`` if unknown."""
    choices = [c.value for c in CupPhysics]
    if kind not in choices:
        raise ScenarioError(
            f"key '{key}': must be one of {', '.join(choices)}, got {kind!r}"
        )
    return CupPhysics(kind)


def cup_catalogue_path(name: str) -> Path:
    """The catalogue file of ``name``: a path, else ``models/cups/<name>.yaml``."""
    path = Path(name)
    if path.suffix in (".yaml", ".yml") and path.is_file():
        return path
    return models_dir() / "cups" / f"{name}.yaml"


def load_bellows_cup(name: str) -> BellowsCup:
    """Load and check a bellows cup of the catalogue (a name or a file path).

    Raises:
        ScenarioError: ``<file>: key '<parameter>.value': ...`` for a value
            out of range, a missing source, an unknown key; or no such cup.
    """
    path = cup_catalogue_path(name)
    if not path.is_file():
        known = sorted(p.stem for p in (models_dir() / "cups").glob("*.yaml"))
        raise ScenarioError(
            f"bellows cup '{name}': no such catalogue file (known: {', '.join(known)})"
        )
    if path.stat().st_size > MAX_CUP_BYTES:
        raise ScenarioError(f"{path}: larger than {MAX_CUP_BYTES} bytes")
    text = path.read_text(encoding="utf-8", errors="replace")
    raw = read_yaml(path, text)
    check_schema(path, raw, _CupFile)
    try:
        data = yaml_load_typed(schema=_CupFile, data=text)
    except (RuntimeError, ValueError, TypeError) as error:
        raise ScenarioError(locate(path, raw, str(error))) from None
    values: dict[str, float] = {}
    sources: dict[str, str] = {}
    for field in dataclasses.fields(_CupFile):
        if field.name == "name":
            continue
        entry: Sourced = getattr(data, field.name)
        if field.name not in raw or not math.isfinite(entry.value):
            raise ScenarioError(f"{path}: key '{field.name}.value': missing")
        if not entry.source.strip():
            raise ScenarioError(
                f"{path}: key '{field.name}.source': every value needs a source "
                '(or "no source")'
            )
        values[field.name] = entry.value
        sources[field.name] = entry.source
    _check_ranges(path, values)
    points = values.pop("lip_points")
    return BellowsCup(
        name=data.name or path.stem, lip_points=int(points), sources=sources, **values
    )


def _check_ranges(path: Path, values: dict[str, float]) -> None:
    """Every value > 0; lip_points an integer >= 24; friction < 2; leak < range."""
    for key, value in values.items():
        if not value > 0.0:
            raise ScenarioError(f"{path}: key '{key}.value': must be > 0, got {value}")
    points = values["lip_points"]
    if points != int(points) or points < MIN_LIP_POINTS:
        raise ScenarioError(
            f"{path}: key 'lip_points.value': must be an integer >= "
            f"{MIN_LIP_POINTS}, got {points}"
        )
    if not values["friction"] < 2.0:
        raise ScenarioError(
            f"{path}: key 'friction.value': must be < 2 (objects have friction 1), "
            f"got {values['friction']}"
        )
    if not values["leak_gap"] < values["vacuum_range"]:
        raise ScenarioError(
            f"{path}: key 'leak_gap.value': must be below vacuum_range "
            f"({values['vacuum_range']} m), got {values['leak_gap']}"
        )


__all__ = [
    "DEFAULT_BELLOWS_CUP",
    "MIN_LIP_POINTS",
    "BellowsCup",
    "CupPhysics",
    "CupPhysicsConfig",
    "Sourced",
    "cup_catalogue_path",
    "cup_physics",
    "load_bellows_cup",
]
