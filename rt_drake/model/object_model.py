"""An object's model file: its body's mass and inertia, read and checked.

An object of a scenario is a model file (SDF or URDF) whose body named
:data:`OBJECT_BODY` carries the object's inertia. SDFormat and Drake's
parser fill in 1 kg and a unit inertia when ``<mass>`` or ``<inertia>`` is
missing, and parse ``<mass>0</mass>``, ``-1`` or ``nan`` without complaint, so
an object would silently be retimed as a 1 kg object: the values are read here
from the file itself and refused unless physically valid.

Physically valid (:func:`rt_drake.types.held_object.check_inertia`): the mass
is finite and > 0; the
rotational inertia about the centre of mass is finite, symmetric and positive
definite, and its principal moments satisfy the triangle inequality
``I_a + I_b >= I_c`` (a real mass distribution's do). Units: kg, kg m^2.
Numpy and the standard library only.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

from rt_drake.errors import InputError
from rt_drake.model.resources import models_dir
from rt_drake.types.held_object import check_inertia

#: Name of each object's body in its model file.
OBJECT_BODY = "body"
#: Largest object model file read, bytes.
MAX_MODEL_BYTES = 10 * 2**20


def model_file(url: str) -> Path:
    """Return the file a ``package://rt_drake/...`` URL or a path points to."""
    prefix = "package://rt_drake/"
    if url.startswith(prefix):
        return models_dir() / url[len(prefix) :]
    return Path(url.removeprefix("file://"))


def read_model_inertia(path: str | Path) -> tuple[float, np.ndarray]:
    """Return ``(mass, I)`` of body :data:`OBJECT_BODY` as written in the file.

    ``I`` is the (3, 3) rotational inertia about the centre of mass, in the
    inertial frame (kg m^2). Both are checked with :func:`check_inertia`.

    Raises:
        InputError: naming the file: not readable, not an SDF or URDF, no body
            :data:`OBJECT_BODY`, ``<mass>`` or the diagonal of ``<inertia>``
            missing (the parser's 1 kg default would be used), a value that is
            not a number, or an invalid inertia.
    """
    path = Path(path)
    if not path.is_file():
        raise InputError(f"object model '{path}' does not exist")
    if path.stat().st_size > MAX_MODEL_BYTES:
        raise InputError(
            f"object model '{path}' is {path.stat().st_size} bytes; an object "
            f"model is at most {MAX_MODEL_BYTES} bytes"
        )
    try:
        root = ET.parse(path).getroot()
    except (ET.ParseError, OSError, UnicodeDecodeError) as error:
        raise InputError(
            f"object model '{path}' is not an SDF or URDF: {error}"
        ) from None
    where = f"object model '{path}'"
    if root.tag == "sdf":
        mass, inertia = _sdf_inertial(root, where)
    elif root.tag == "robot":
        mass, inertia = _urdf_inertial(root, where)
    else:
        raise InputError(f"{where} is not an SDF or URDF (root element <{root.tag}>)")
    check_inertia(mass, inertia, f"{where}: body '{OBJECT_BODY}'")
    return mass, inertia


def _body(root: ET.Element, where: str) -> ET.Element:
    for link in root.iter("link"):
        if link.get("name") == OBJECT_BODY:
            return link
    raise InputError(f"{where} has no link named '{OBJECT_BODY}'")


def _number(text: str | None, where: str, name: str) -> float:
    try:
        return float((text or "").strip())
    except ValueError:
        raise InputError(f"{where}: {name} {text!r} is not a number") from None


def _sdf_inertial(root: ET.Element, where: str) -> tuple[float, np.ndarray]:
    body = _body(root, where)
    where = f"{where}: link '{OBJECT_BODY}'"
    inertial = body.find("inertial")
    mass_node = None if inertial is None else inertial.find("mass")
    if mass_node is None:
        raise InputError(f"{where} has no <inertial><mass> (the parser would use 1 kg)")
    mass = _number(mass_node.text, where, "<mass>")
    assert inertial is not None
    tensor = inertial.find("inertia")
    values = {}
    for name in ("ixx", "iyy", "izz", "ixy", "ixz", "iyz"):
        node = None if tensor is None else tensor.find(name)
        if node is None and name in ("ixx", "iyy", "izz"):
            raise InputError(
                f"{where} has no <inertia><{name}> (the parser would use 1 kg m^2)"
            )
        values[name] = 0.0 if node is None else _number(node.text, where, f"<{name}>")
    return mass, _matrix(values)


def _urdf_inertial(root: ET.Element, where: str) -> tuple[float, np.ndarray]:
    body = _body(root, where)
    where = f"{where}: link '{OBJECT_BODY}'"
    inertial = body.find("inertial")
    mass_node = None if inertial is None else inertial.find("mass")
    tensor = None if inertial is None else inertial.find("inertia")
    if mass_node is None or tensor is None:
        raise InputError(f"{where} has no <inertial> with <mass> and <inertia>")
    mass = _number(mass_node.get("value"), where, "mass value")
    values = {}
    for name in ("ixx", "iyy", "izz", "ixy", "ixz", "iyz"):
        text = tensor.get(name)
        if text is None:
            raise InputError(f"{where}: <inertia> has no attribute {name}")
        values[name] = _number(text, where, f"<inertia {name}>")
    return mass, _matrix(values)


def _matrix(v: dict[str, float]) -> np.ndarray:
    return np.array(
        [
            [v["ixx"], v["ixy"], v["ixz"]],
            [v["ixy"], v["iyy"], v["iyz"]],
            [v["ixz"], v["iyz"], v["izz"]],
        ]
    )


__all__ = [
    "OBJECT_BODY",
    "model_file",
    "read_model_inertia",
]
