"""The ``.npz`` trajectory format: a retimed motion anyone can re-check.

A file holds (SI units; C the cup frame, W the world):

- ``t`` (M,), ``q``, ``qd``, ``qdd`` (M, n): samples every ``period`` s
  (s, rad, rad/s, rad/s^2), the last one at ``duration`` (s);
- ``X_WC`` (M, 4, 4): pose of the cup frame C in W at each sample;
- ``object_name``, ``object_mass`` (kg), ``p_CoScm_C`` (m), ``I_Scm_C``
  (kg m^2): the held object's inertia in C;
- ``F``, ``g``: the grasp constraint ``F w <= g`` used ((0, 6) and (0,)
  without one); ``cup_names``, ``cup_values``: the cup parameters;
- ``waypoints``, ``knots``, ``gridpoints``, ``sd``: the path and the s'(s)
  profile; ``format_version``.

:func:`sample_trajectory` builds one from a :class:`~.solve.RetimeResult`,
:func:`save_trajectory` writes it (atomically, never over an input of the
caller's choosing: that is the caller's check) and :func:`load_trajectory`
reads it back with every key checked.
"""

from __future__ import annotations

import dataclasses
import os
import tempfile
import zipfile
from pathlib import Path

import numpy as np
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import Frame

from rt_drake.contact import CupParameters
from rt_drake.cup_frame import CupFrame
from rt_drake.dynamics import HeldObject
from rt_drake.errors import InputError
from rt_drake.retiming.limits import GraspConstraint
from rt_drake.retiming.solve import RetimeResult

#: Version of the layout below; bumped when a key changes meaning.
FORMAT_VERSION = 1
#: s, default sampling period.
SAMPLE_PERIOD = 1e-3


@dataclasses.dataclass(frozen=True, eq=False)
class SavedTrajectory:
    """The arrays of a trajectory file (see the module docstring)."""

    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray
    duration: float
    X_WC: np.ndarray
    object_name: str
    object_mass: float
    p_CoScm_C: np.ndarray
    I_Scm_C: np.ndarray
    F: np.ndarray
    g: np.ndarray
    cup_names: np.ndarray
    cup_values: np.ndarray
    waypoints: np.ndarray
    knots: np.ndarray
    gridpoints: np.ndarray
    sd: np.ndarray


def sample_trajectory(
    plant: MultibodyPlant,
    result: RetimeResult,
    held: HeldObject,
    grasp: GraspConstraint | None,
    cup: CupParameters,
    object_name: str,
    waypoints: np.ndarray,
    knots: np.ndarray,
    period: float = SAMPLE_PERIOD,
    cup_frame: Frame | None = None,
) -> SavedTrajectory:
    """Sample ``result`` every ``period`` s (and at its end) for a file.

    Args:
        plant: The retimer's plant (positions = the path's joints).
        result: The retimed path.
        held: The held object's inertia in C (recorded even without a grasp).
        grasp: The grasp constraint used, or None.
        cup: The cup's parameters (recorded).
        object_name: The held object's name.
        waypoints: (K, n) the path's waypoints (rad).
        knots: (K,) their path parameters s.
        period: Sampling period, s.
        cup_frame: The cup frame C (default: the plant's ``suction_cup``).
    """
    t = np.append(np.arange(0.0, result.duration, period), result.duration)
    q, qd, qdd = result.trajectory.sample(t, order=2)
    context = plant.CreateDefaultContext()
    frame = cup_frame if cup_frame is not None else CupFrame.of(plant).frame
    X_WC = np.empty((len(t), 4, 4))
    for i, qi in enumerate(q):
        plant.SetPositions(context, qi)
        X_WC[i] = frame.CalcPoseInWorld(context).GetAsMatrix4()
    parameters = cup.as_dict()
    return SavedTrajectory(
        t=t,
        q=q,
        qd=qd,
        qdd=qdd,
        duration=result.duration,
        X_WC=X_WC,
        object_name=object_name,
        object_mass=held.mass,
        p_CoScm_C=held.p_CoScm_C,
        I_Scm_C=held.I_Scm_C,
        F=np.zeros((0, 6)) if grasp is None else grasp.F,
        g=np.zeros(0) if grasp is None else grasp.g,
        cup_names=np.array(list(parameters)),
        cup_values=np.array(list(parameters.values()), dtype=float),
        waypoints=np.asarray(waypoints, dtype=float),
        knots=np.asarray(knots, dtype=float),
        gridpoints=result.gridpoints,
        sd=result.sd,
    )


def save_trajectory(path: str | Path, saved: SavedTrajectory) -> Path:
    """Write ``saved`` to ``path`` (must end in ``.npz``) atomically.

    The arrays go to a temporary file beside ``path``, renamed over it once
    complete; on any failure the temporary file is removed.

    Raises:
        InputError: the suffix is not ``.npz``.
    """
    path = Path(path)
    if path.suffix != ".npz":
        raise InputError(f"trajectory file '{path}' must end in .npz")
    arrays = {f.name: getattr(saved, f.name) for f in dataclasses.fields(saved)}
    handle, temporary = tempfile.mkstemp(
        dir=path.parent, prefix=f".{path.name}.", suffix=".tmp"
    )
    try:
        with os.fdopen(handle, "wb") as stream:
            np.savez(stream, format_version=FORMAT_VERSION, **arrays)
        os.replace(temporary, path)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise
    return path


def load_trajectory(path: str | Path) -> SavedTrajectory:
    """Read a trajectory file written by :func:`save_trajectory`.

    Raises:
        InputError: no such file, not an ``.npz`` archive, another format
            version, or a key missing (each message names the file and key).
    """
    path = Path(path)
    if not path.is_file():
        raise InputError(f"trajectory file '{path}' does not exist")
    try:
        data = np.load(path, allow_pickle=False)
    except (OSError, ValueError, zipfile.BadZipFile) as error:
        raise InputError(f"{path}: not an .npz trajectory file ({error})") from None
    with data:
        version = int(data["format_version"]) if "format_version" in data else None
        if version != FORMAT_VERSION:
            raise InputError(
                f"{path}: key 'format_version': expected {FORMAT_VERSION}, "
                f"got {version}"
            )
        values = {}
        for field in dataclasses.fields(SavedTrajectory):
            if field.name not in data:
                raise InputError(f"{path}: key '{field.name}' is missing")
            values[field.name] = data[field.name]
    values["duration"] = float(values["duration"])
    values["object_mass"] = float(values["object_mass"])
    values["object_name"] = str(values["object_name"])
    return SavedTrajectory(**values)


__all__ = [
    "FORMAT_VERSION",
    "SAMPLE_PERIOD",
    "SavedTrajectory",
    "load_trajectory",
    "sample_trajectory",
    "save_trajectory",
]
