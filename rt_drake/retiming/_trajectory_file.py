"""The ``.npz`` trajectory format: a retimed motion anyone can re-check.

A file holds (SI units; C the cup frame, W the world):

- ``t`` (M,), ``q``, ``qd``, ``qdd`` (M, n): samples every ``period`` s
  (s, rad, rad/s, rad/s^2), the last one at ``duration`` (s);
- ``X_WC`` (M, 4, 4): pose of the cup frame C in W at each sample;
- ``object_name``, ``object_mass`` (kg), ``p_CoScm_C`` (m), ``I_Scm_C``
  (kg m^2): the held object's inertia in C;
- ``F``, ``g``: the grasp constraint ``F w <= g`` used ((0, 6) and (0,)
  without one); ``cup_names``, ``cup_values``: the cup parameters (for a
  multi-cup tool, every cup's as ``cups[i].radius``, ..., and its pose in
  the tool frame T as ``cups[i].R_TC[r][c]``, ``cups[i].p_TC[r]``; C is
  then T);
- ``waypoints``, ``knots``, ``gridpoints``, ``sd``: the path and the s'(s)
  profile; ``format_version``;
- ``path_acceleration``: with jerk limits, s'' at the grid points (its
  motion is :class:`~._jerk_timed_path.JerkTimedPath`'s); empty without
  (s'' constant per segment, :class:`~._timed_path.TimedPath`). Optional:
  a file without the key reads as empty.

:func:`sample_trajectory` builds one from a :class:`~._solve.RetimeResult`,
:func:`save_trajectory` writes it (atomically, never over an input of the
caller's choosing: that is the caller's check) and :func:`load_trajectory`
reads it back with every key checked.
"""

from __future__ import annotations

import dataclasses
import math
import zipfile
from pathlib import Path
from typing import BinaryIO

import numpy as np
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import Frame

from rt_drake import arguments
from rt_drake.atomic_file import output_problem, write_atomically
from rt_drake.contact import CupParameters, ToolParameters
from rt_drake.dynamics.cup_frame import CupFrame
from rt_drake.errors import InputError, TooLargeError
from rt_drake.retiming._solve import RetimeResult
from rt_drake.retiming.limits import GRASP_ATTRIBUTES, GraspConstraint
from rt_drake.types.held_object import HeldObject

#: Version of the layout below; bumped when a key changes meaning.
FORMAT_VERSION = 1
#: s, default sampling period.
SAMPLE_PERIOD = 1e-3
#: Most samples a file holds (1000 s at 1 kHz; 892 s of a 6-joint arm took
#: 7 s and 0.64 GB); a longer trajectory is refused before sampling.
MAX_SAMPLES = 1_000_000


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
    path_acceleration: np.ndarray = dataclasses.field(
        default_factory=lambda: np.zeros(0)
    )


def sample_trajectory(
    plant: MultibodyPlant,
    result: RetimeResult,
    held: HeldObject,
    grasp: GraspConstraint | None,
    cup: CupParameters | ToolParameters,
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
        cup: The cup's parameters, or a multi-cup tool's (recorded).
        object_name: The held object's name.
        waypoints: (K, n) the path's waypoints (rad).
        knots: (K,) their path parameters s.
        period: Sampling period, s.
        cup_frame: The cup frame C (default: the plant's ``suction_cup``).

    Raises:
        InputError: ``period`` not finite and > 0.
        TooLargeError: more than :data:`MAX_SAMPLES` samples (estimated from
            the duration before anything is allocated).
    """
    where = "sample_trajectory"
    arguments.instance(plant, "plant", MultibodyPlant, where=where)
    arguments.having(
        result, "result", "RetimeResult", ("duration", "trajectory"), where=where
    )
    arguments.instance(held, "held", HeldObject, where=where)
    if grasp is not None:
        arguments.having(
            grasp, "grasp", "GraspConstraint", GRASP_ATTRIBUTES, where=where
        )
    arguments.instance(cup, "cup", (CupParameters, ToolParameters), where=where)
    arguments.instance(object_name, "object_name", str, where=where)
    waypoints = arguments.array(waypoints, "waypoints", ("K", "n"), where=where)
    knots = arguments.array(knots, "knots", ("K",), where=where)
    if len(knots) != len(waypoints):
        raise InputError(
            f"{where}: knots must have one value per waypoint ({len(waypoints)}), "
            f"got {len(knots)}"
        )
    arguments.number(period, "period", where=where, above=0.0)
    if cup_frame is not None:
        arguments.instance(cup_frame, "cup_frame", Frame, where=where)
    count = math.ceil(result.duration / period) + 1
    if count > MAX_SAMPLES:
        n = result.trajectory.rows()
        size = count * 8 * (1 + 3 * n + 16)
        raise TooLargeError(
            f"sampling a {result.duration:.4g} s trajectory every {period:g} s "
            f"gives {count:.3g} samples (about {size / 2**30:.3g} GB); at most "
            f"{MAX_SAMPLES} samples ({MAX_SAMPLES * period:g} s at this period) "
            "are accepted"
        )
    t = np.append(np.arange(0.0, result.duration, period), result.duration)
    q, qd, qdd = result.trajectory.sample(t, order=2)
    context = plant.CreateDefaultContext()
    frame = cup_frame if cup_frame is not None else CupFrame.of(plant).frame
    X_WC = np.empty((len(t), 4, 4))
    for i, qi in enumerate(q):
        plant.SetPositions(context, qi)
        X_WC[i] = frame.CalcPoseInWorld(context).GetAsMatrix4()
    parameters = _flat_parameters(cup)
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
        path_acceleration=(
            np.zeros(0)
            if result.path_acceleration is None
            else np.asarray(result.path_acceleration, dtype=float)
        ),
    )


def _flat_parameters(cup: CupParameters | ToolParameters) -> dict[str, float]:
    """Name -> number: a cup's fields, or every cup's fields and pose."""
    if isinstance(cup, CupParameters):
        return {name: float(value) for name, value in cup.as_dict().items()}
    flat: dict[str, float] = {}
    for i, mount in enumerate(cup.cups):
        for name, value in mount.cup.as_dict().items():
            flat[f"cups[{i}].{name}"] = float(value)
        for r in range(3):
            for c in range(3):
                flat[f"cups[{i}].R_TC[{r}][{c}]"] = float(mount.R_TC[r, c])
        for r in range(3):
            flat[f"cups[{i}].p_TC[{r}]"] = float(mount.p_TC[r])
    return flat


def save_trajectory(path: str | Path, saved: SavedTrajectory) -> Path:
    """Write ``saved`` to ``path`` (must end in ``.npz``) atomically.

    The arrays go to a temporary file beside ``path``, renamed over it once
    complete; on any failure the temporary file is removed.

    Raises:
        InputError: the suffix is not ``.npz``, or ``path`` cannot be
            written (a directory, under a file).
    """
    path = arguments.path(path, "path", where="save_trajectory")
    if path.suffix != ".npz":
        raise InputError(f"trajectory file '{path}' must end in .npz")
    problem = output_problem(path)
    if problem is not None:
        raise InputError(f"cannot write trajectory file '{path}': {problem}")
    arguments.instance(saved, "saved", SavedTrajectory, where="save_trajectory")
    arrays = {f.name: getattr(saved, f.name) for f in dataclasses.fields(saved)}

    def write(stream: BinaryIO) -> None:
        np.savez(stream, format_version=FORMAT_VERSION, **arrays)

    return write_atomically(path, write)


def load_trajectory(path: str | Path) -> SavedTrajectory:
    """Read a trajectory file written by :func:`save_trajectory`.

    Raises:
        InputError: no such file, not an ``.npz`` archive, another format
            version, or a key missing (each message names the file and key).
    """
    path = arguments.path(path, "path", where="load_trajectory")
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
            if field.name == "path_acceleration" and field.name not in data:
                continue  # optional: files without jerk limits may lack it
            if field.name not in data:
                raise InputError(f"{path}: key '{field.name}' is missing")
            values[field.name] = data[field.name]
    values["duration"] = float(values["duration"])
    values["object_mass"] = float(values["object_mass"])
    values["object_name"] = str(values["object_name"])
    return SavedTrajectory(**values)


__all__ = [
    "FORMAT_VERSION",
    "MAX_SAMPLES",
    "SAMPLE_PERIOD",
    "SavedTrajectory",
    "load_trajectory",
    "sample_trajectory",
    "save_trajectory",
]
