"""Campaign files: typed dataclasses loaded with ``yaml_load_typed``.

A campaign names a base scenario (with a ``random_transport`` section: the
regions where transports are sampled), a catalogue of objects, a list of
cups or multi-cup tools, the trials per combination with a seed, and the
comparisons to run (see ``scenarios/campaigns/two_objects_two_cups.yaml``)::

    scenario: random_transport          # a file beside this one, or a shipped name
    objects:
    - model: package://rt_drake/objects/notebook.sdf
    - {name: kindle, model: ../models/kindle.sdf, uncertainty: kindle_set.yaml}
    object_dir: package://rt_drake/objects   # and/or every *.sdf of a directory
    cups:
    - {name: paper}              # CupParameters fields; default: the paper's cup
    - {name: small, radius: 0.01, suction_force: 4.0}
    - name: pair                 # a tool: the scenario's `tool:` key
      tool:
        cups:
        - {pose: {translation: [0.04, 0, 0]}, points: 4}
        - {pose: {translation: [-0.04, 0, 0]}, points: 4}
    trials: 20
    seed: 0
    variants: [constrained, unconstrained, speed_sweep]
    cup_physics: bellows         # the simulated cup (default: the scenario's)

An entry of ``cups`` is a cup (its :class:`CupParameters` fields) or a tool
of several cups (``tool``, the schema of a scenario's ``tool`` key, checked
by the scenario's own :func:`~rt_drake.model.scenario.check_tool`), never both;
its ``name`` names the rows of either.

``yaml_load_typed`` rejects misspelled keys; :func:`load_campaign` turns every
error into a one-line :class:`CampaignError` naming the file, key and value.
Relative paths are relative to the campaign file.
"""

# No ``from __future__ import annotations``: yaml_load_typed reads the
# dataclass field types, which must be real types, not strings.
import dataclasses
from pathlib import Path

from pydrake.common.schema import Transform
from pydrake.common.yaml import yaml_load_typed

from rt_drake.contact import CupParameters
from rt_drake.errors import InputError, ScenarioError
from rt_drake.experiments.campaign._campaign_errors import CampaignError
from rt_drake.experiments.campaign._catalogue import (
    CampaignCup,
    CampaignObject,
    resolve_objects,
)
from rt_drake.experiments.campaign._row_types import Variant
from rt_drake.model.scenario import (
    MAX_SCENARIO_BYTES,
    ToolConfig,
    check_tool,
)
from rt_drake.model.yaml_schema import (
    check_schema,
    locate,
    read_yaml,
)


@dataclasses.dataclass
class ObjectEntry:
    """One object of the catalogue.

    Attributes:
        model: SDF of the object (``package://rt_drake/...`` or a path); its
            link must be called ``body``.
        name: Its name in the results (default: the file's stem).
        grasp: X_OC, the cup frame in the object frame while held (default:
            the centre of the top face of the SDF's box, cup pointing down;
            else the base scenario's grasp).
        uncertainty: A file with the object's uncertainty set, held by the
            ``robust`` comparison only (the fields of
            :class:`~rt_drake.types.object_uncertainty.ObjectUncertainty`; see
            :mod:`._catalogue`).
    """

    model: str = ""
    name: str = ""
    grasp: Transform | None = None
    uncertainty: str = ""


@dataclasses.dataclass
class CupEntry(CupParameters):
    """A cup of the campaign (a name and the CupParameters fields), or a tool.

    Fields left out take the paper's cup values (:class:`CupParameters`).
    ``tool``: a tool of several cups instead (a scenario's ``tool`` key);
    then the entry has a name and the tool only.
    """

    name: str = ""
    tool: ToolConfig | None = None


#: The variants of a campaign file without ``variants``: the paper's Table I
#: comparisons. ``optimized`` and ``robust`` are asked for by name (``robust``
#: needs uncertainty sets, and adding either changes the campaign's hash).
DEFAULT_VARIANTS = (Variant.CONSTRAINED, Variant.UNCONSTRAINED, Variant.SPEED_SWEEP)


def _default_variants() -> list[str]:
    return [variant.value for variant in DEFAULT_VARIANTS]


@dataclasses.dataclass
class CampaignFile:
    """The schema of a campaign file (see the module docstring)."""

    scenario: str = ""
    objects: list[ObjectEntry] = dataclasses.field(default_factory=list)
    object_dir: str = ""
    cups: list[CupEntry] = dataclasses.field(default_factory=list)
    trials: int = 1
    seed: int = 0
    variants: list[str] = dataclasses.field(default_factory=_default_variants)
    cup_physics: str = ""


def read_campaign_file(path: Path) -> CampaignFile:
    """Parse ``path`` into a :class:`CampaignFile` (schema checks only).

    The scenario loader's strict YAML reader and schema check, so campaign
    errors read exactly like scenario errors.

    Raises:
        CampaignError: missing, too large or not UTF-8 file, bad YAML
            (duplicate keys and aliases included), unknown key, wrong type.
    """
    if not path.is_file():
        raise CampaignError(f"{path}: campaign file does not exist")
    size = path.stat().st_size
    if size > MAX_SCENARIO_BYTES:
        raise CampaignError(
            f"{path}: {size} bytes; a campaign file is at most "
            f"{MAX_SCENARIO_BYTES} bytes"
        )
    try:
        text = path.read_bytes().decode("utf-8")
    except UnicodeDecodeError as error:
        byte = error.object[error.start]
        raise CampaignError(
            f"{path}: not UTF-8 text (byte {error.start} is {byte:#04x})"
        ) from None
    try:
        raw = read_yaml(path, text)
        check_schema(path, raw, CampaignFile)
    except ScenarioError as error:
        raise CampaignError(str(error)) from None
    _check_cup_or_tool(path, raw.get("cups"))
    try:
        return yaml_load_typed(schema=CampaignFile, data=text)
    except (RuntimeError, ValueError, TypeError) as error:
        raise CampaignError(locate(path, raw, str(error))) from None


def _check_cup_or_tool(path: Path, entries: object) -> None:
    """A ``cups`` entry with ``tool`` has no cup parameter beside it.

    Raises:
        CampaignError: naming ``cups[i].<field>`` and its value.
    """
    if not isinstance(entries, list):
        return  # no cups, or a wrong type already refused by check_schema
    for index, entry in enumerate(entries):
        if not isinstance(entry, dict) or entry.get("tool") is None:
            continue
        extra = sorted(str(key) for key in entry if key not in ("name", "tool"))
        if extra:
            raise CampaignError(
                f"{path}: key 'cups[{index}].{extra[0]}': a tool entry takes "
                f"'name' and 'tool' only (each cup's parameters go in "
                f"tool.cups), got {extra[0]}: {entry[extra[0]]}"
            )


def parse_cups(path: Path, entries: list[CupEntry]) -> tuple[CampaignCup, ...]:
    """Named, validated cups and tools.

    A tool is checked by the scenario's :func:`~rt_drake.model.scenario.check_tool`
    (at least one cup, each in range, fixed poses).

    Raises:
        CampaignError: no cup, a cup or tool without a name or with a
            duplicate name, or a parameter out of range (naming ``cups[i]``,
            or ``cups[i].tool.cups[j].<field>``).
    """
    if not entries:
        raise CampaignError(f"{path}: key 'cups': list at least one cup")
    cups: list[CampaignCup] = []
    for index, entry in enumerate(entries):
        where = f"{path}: key 'cups[{index}]"
        what = "a cup" if entry.tool is None else "a tool"
        if not entry.name:
            raise CampaignError(f"{where}.name': {what} needs a name")
        if entry.name in (cup.name for cup in cups):
            raise CampaignError(f"{where}.name': duplicate cup name '{entry.name}'")
        if entry.tool is not None:
            try:
                check_tool(path, entry.tool, key=f"cups[{index}].tool")
            except ScenarioError as error:
                raise CampaignError(str(error)) from None
            cups.append(CampaignCup(entry.name, CupParameters(), entry.tool))
            continue
        fields = {f.name: getattr(entry, f.name) for f in dataclasses.fields(entry)}
        del fields["name"], fields["tool"]
        try:
            parameters = CupParameters(**fields)
        except InputError as error:
            raise CampaignError(f"{where}': {error}") from None
        cups.append(CampaignCup(entry.name, parameters))
    return tuple(cups)


def parse_variants(path: Path, names: list[str]) -> tuple[Variant, ...]:
    """The comparisons to run, in order.

    Raises:
        CampaignError: none, a duplicate, or an unknown name (listing the
            known ones).
    """
    if not names:
        raise CampaignError(f"{path}: key 'variants': list at least one variant")
    variants: list[Variant] = []
    for index, name in enumerate(names):
        try:
            variant = Variant.parse(name)
        except CampaignError as error:
            raise CampaignError(f"{path}: key 'variants[{index}]': {error}") from None
        if variant in variants:
            raise CampaignError(f"{path}: key 'variants[{index}]': duplicate {name!r}")
        variants.append(variant)
    return tuple(variants)


def parse_objects(
    path: Path, spec: CampaignFile, base_grasp: Transform
) -> tuple[CampaignObject, ...]:
    """The catalogue: ``objects`` then every ``*.sdf`` of ``object_dir``.

    Raises:
        CampaignError: no object, an unknown file, a duplicate name.
    """
    return resolve_objects(
        path,
        [(e.model, e.name, e.grasp, e.uncertainty) for e in spec.objects],
        spec.object_dir,
        base_grasp,
    )


__all__ = [
    "CampaignFile",
    "CupEntry",
    "ObjectEntry",
    "parse_cups",
    "parse_objects",
    "parse_variants",
    "read_campaign_file",
]
