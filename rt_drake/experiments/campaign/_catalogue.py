"""The objects and cups of a campaign, resolved from its file.

Each object is an SDF whose link ``body`` is the object; it is held at a
grasp X_OC (the cup frame C in the object frame O). By default the grasp is
the centre of the top face of the SDF's first box collision (cup +z
pointing down into the object), so a catalogue of boxes needs no grasp
poses; an object without a box takes the base scenario's grasp.

An object may name an uncertainty set file, for the ``robust`` variant: a
YAML mapping with the fields of
:class:`~rt_drake.types.object_uncertainty.ObjectUncertainty`
(the scenario key ``objects[].uncertainty``), e.g.::

    mass: 0.2                   # relative half-width of the mass
    com: [0.01, 0.01, 0.005]    # m, half-widths of the centre of mass (axes O)
    inertia: 0.2                # relative half-width of each principal moment
"""

from __future__ import annotations

import dataclasses
import xml.etree.ElementTree as ElementTree
from pathlib import Path

import numpy as np
from pydrake.common.schema import Transform
from pydrake.common.yaml import yaml_load_typed
from pydrake.math import RigidTransform, RotationMatrix

from rt_drake.contact import CupParameters, ToolParameters
from rt_drake.errors import InputError, ScenarioError
from rt_drake.experiments.campaign._campaign_errors import CampaignError
from rt_drake.model.object_model import OBJECT_BODY
from rt_drake.model.resources import models_dir
from rt_drake.model.scenario import (
    MAX_SCENARIO_BYTES,
    ToolConfig,
)
from rt_drake.model.yaml_schema import (
    check_schema,
    locate,
    read_yaml,
)
from rt_drake.types.object_uncertainty import ObjectUncertainty

#: The URL prefix of the shipped models.
PACKAGE_PREFIX = "package://rt_drake/"


@dataclasses.dataclass(frozen=True, eq=False)
class CampaignObject:
    """One object of the catalogue.

    Attributes:
        name: Its name (a model instance name in the trial's plant).
        model: ``package://rt_drake/...`` or ``file:///...`` URL of its SDF.
        file: The SDF on this machine.
        X_OC: The grasp: pose of the cup frame C in the object frame O.
        uncertainty: Its uncertainty set file, if any.
        uncertainty_set: That file's set (None: no file).
    """

    name: str
    model: str
    file: Path
    X_OC: RigidTransform
    uncertainty: Path | None
    uncertainty_set: ObjectUncertainty | None = None


@dataclasses.dataclass(frozen=True, eq=False)
class CampaignCup:
    """One cup or multi-cup tool of the campaign: a name and its contact model.

    Attributes:
        name: Its name in the rows (``cup`` column) and the report.
        parameters: The cup (a tool's scenarios keep the default cup, unused,
            as a scenario with ``tool`` does).
        tool: A tool of several cups posed in the tool frame (the
            scenario's ``tool``), or None for the single cup ``parameters``.
    """

    name: str
    parameters: CupParameters
    tool: ToolConfig | None = None

    def tool_parameters(self) -> ToolParameters:
        """Its cups and their poses in the tool frame (one cup: at the frame)."""
        if self.tool is None:
            return ToolParameters.single(self.parameters)
        return self.tool.parameters()

    def as_dict(self) -> dict[str, object]:
        """Its name and model as plain data (for the campaign's content hash).

        A cup: its name and CupParameters fields; a tool: its name and
        ``tool``, each cup's fields and ``X_TC`` (3 x 4, rounded to 1e-12).
        """
        if self.tool is None:
            return {"name": self.name, **self.parameters.as_dict()}
        cups = [
            {
                **mount.cup.as_dict(),
                "X_TC": np.hstack([mount.R_TC, mount.p_TC[:, None]]).round(12).tolist(),
            }
            for mount in self.tool_parameters().cups
        ]
        return {"name": self.name, "tool": cups}


def resolve_file(base: Path, text: str) -> tuple[str, Path]:
    """(URL for Drake, file on this machine) of a model or directory name.

    ``package://rt_drake/...`` is a shipped model; anything else is a path,
    relative to the directory ``base`` unless absolute.
    """
    if text.startswith(PACKAGE_PREFIX):
        return text, models_dir() / text[len(PACKAGE_PREFIX) :]
    file = (base / text).resolve()
    return f"file://{file}", file


def top_face_grasp(sdf: Path) -> RigidTransform | None:
    """X_OC at the centre of the top face of the SDF's box, cup pointing down.

    The first ``<collision>`` of link ``body`` with a ``<box>`` whose
    ``<pose>`` has no rotation: ``p_OC = p_OB + [0, 0, size_z / 2]`` and
    ``R_OC`` the half turn about x (C's +z points down into the object).
    None if there is no such box.
    """
    try:
        root = ElementTree.parse(sdf).getroot()
    except (OSError, ElementTree.ParseError):
        return None
    for link in root.iter("link"):
        if link.get("name") != OBJECT_BODY:
            continue
        for collision in link.iter("collision"):
            size = collision.find("geometry/box/size")
            if size is None or size.text is None:
                continue
            pose = collision.find("pose")
            values = [0.0] * 6
            if pose is not None and pose.text:
                values = [float(v) for v in pose.text.split()]
            if len(values) != 6 or any(values[3:]):
                return None
            height = float(size.text.split()[2])
            p_OC = np.array(values[:3]) + [0.0, 0.0, height / 2]
            return RigidTransform(RotationMatrix.MakeXRotation(np.pi), p_OC)
    return None


def _object(
    path: Path,
    where: str,
    entry: tuple[str, str, Transform | None, str],
    base_grasp: Transform,
) -> CampaignObject:
    model, name, grasp, uncertainty = entry
    if not model:
        raise CampaignError(f"{path}: key '{where}.model': an object needs a model")
    url, file = resolve_file(path.parent, model)
    if not file.is_file():
        raise CampaignError(
            f"{path}: key '{where}.model': unknown model '{model}' (no such file)"
        )
    uncertainty_file: Path | None = None
    uncertainty_set: ObjectUncertainty | None = None
    name = name or file.stem
    if uncertainty:
        _, uncertainty_file = resolve_file(path.parent, uncertainty)
        if not uncertainty_file.is_file():
            raise CampaignError(
                f"{path}: key '{where}.uncertainty': no such file '{uncertainty}'"
            )
        try:
            uncertainty_set = read_uncertainty(uncertainty_file, name, url)
        except CampaignError as error:
            raise CampaignError(f"{path}: key '{where}.uncertainty': {error}") from None
    if grasp is not None:
        X_OC = grasp.GetDeterministicValue()
    else:
        X_OC = top_face_grasp(file) or base_grasp.GetDeterministicValue()
    return CampaignObject(name, url, file, X_OC, uncertainty_file, uncertainty_set)


def read_uncertainty(file: Path, name: str, model: str) -> ObjectUncertainty:
    """The uncertainty set in ``file`` (module docstring) of object ``name``.

    Read with the scenario loader's strict reader and schema check; the
    widths in range and the centre-of-mass box inside the model's box.

    Raises:
        CampaignError: ``file: ...`` naming the key and value.
    """
    size = file.stat().st_size
    if size > MAX_SCENARIO_BYTES:
        raise CampaignError(f"{file}: {size} bytes; at most {MAX_SCENARIO_BYTES}")
    try:
        text = file.read_bytes().decode("utf-8")
    except UnicodeDecodeError:
        raise CampaignError(f"{file}: not UTF-8 text") from None
    try:
        raw = read_yaml(file, text)
        check_schema(file, raw, ObjectUncertainty)
        uncertainty = yaml_load_typed(schema=ObjectUncertainty, data=text)
        uncertainty.validate()  # yaml_load_typed sets fields after __init__
    except ScenarioError as error:
        raise CampaignError(str(error)) from None
    except (RuntimeError, ValueError, TypeError) as error:
        raise CampaignError(locate(file, raw, str(error))) from None
    except InputError as error:  # a width out of range
        raise CampaignError(f"{file}: {error}") from None
    if any(uncertainty.com):
        from rt_drake.model.object_geometry import object_box  # parses the model: Drake

        try:
            p_OoScm_O, half_extents = object_box(model, name)
            uncertainty.check_inside(p_OoScm_O, half_extents)
        except InputError as error:
            raise CampaignError(f"{file}: {error}") from None
    return uncertainty


def resolve_objects(
    path: Path,
    entries: list[tuple[str, str, Transform | None, str]],
    object_dir: str,
    base_grasp: Transform,
) -> tuple[CampaignObject, ...]:
    """The listed objects (model, name, grasp, uncertainty), then ``object_dir``'s.

    Raises:
        CampaignError: no object at all, an unknown file or directory, a
            duplicate name.
    """
    objects = [
        _object(path, f"objects[{i}]", entry, base_grasp)
        for i, entry in enumerate(entries)
    ]
    if object_dir:
        _, directory = resolve_file(path.parent, object_dir)
        if not directory.is_dir():
            raise CampaignError(
                f"{path}: key 'object_dir': no such directory '{object_dir}'"
            )
        prefix = object_dir.rstrip("/") + "/"
        for file in sorted(directory.glob("*.sdf")):
            entry = (prefix + file.name, "", None, "")
            objects.append(_object(path, "object_dir", entry, base_grasp))
    if not objects:
        raise CampaignError(
            f"{path}: key 'objects': list at least one object (or an object_dir)"
        )
    names = [obj.name for obj in objects]
    for index, name in enumerate(names):
        if name in names[:index]:
            raise CampaignError(f"{path}: key 'objects': duplicate object '{name}'")
    return tuple(objects)


__all__ = [
    "CampaignCup",
    "CampaignObject",
    "read_uncertainty",
    "resolve_file",
    "resolve_objects",
    "top_face_grasp",
]
