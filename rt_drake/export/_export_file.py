"""``export_trajectory``: a trajectory as a controller's file, at its period.

The samples lie on the controller's grid and end at rest
(:mod:`._grid_samples`); the file is a ROS 2 bag (:mod:`._ros2_bag`) or a
CSV (:mod:`._csv_table`), written atomically and never over its input.
"""

from __future__ import annotations

import enum
from collections.abc import Sequence
from pathlib import Path

from pydrake.multibody.plant import MultibodyPlant

from rt_drake import arguments
from rt_drake.atomic_file import output_problem
from rt_drake.errors import InputError
from rt_drake.export._csv_table import write_csv_table
from rt_drake.export._grid_samples import Sampleable, as_trajectory, sample_on_grid
from rt_drake.export._ros2_bag import DEFAULT_TOPIC, write_ros2_bag
from rt_drake.export.controller_names import check_joint_names, controller_joint_names
from rt_drake.retiming import load_trajectory


class ExportFormat(enum.Enum):
    """The file formats of an export (the value is the file's suffix)."""

    MCAP = "mcap"
    CSV = "csv"

    @property
    def suffix(self) -> str:
        """``.mcap`` or ``.csv``."""
        return f".{self.value}"


def export_format(value: ExportFormat | str, what: str) -> ExportFormat:
    """``value`` as an :class:`ExportFormat` (``"mcap"`` or ``"csv"``).

    Raises:
        InputError: another value, naming ``what``.
    """
    if isinstance(value, ExportFormat):
        return value
    known = ", ".join(f.value for f in ExportFormat)
    try:
        return ExportFormat(value)
    except ValueError:
        raise InputError(f"{what} must be one of {known}, got {value!r}") from None


def export_trajectory(
    trajectory: Sampleable | str | Path,
    out: str | Path,
    *,
    format: ExportFormat | str = ExportFormat.MCAP,  # noqa: A002
    period: float,
    joint_names: Sequence[str] | None = None,
    plant: MultibodyPlant | None = None,
    topic: str = DEFAULT_TOPIC,
) -> Path:
    """Write ``trajectory`` sampled every ``period`` s to ``out``; return ``out``.

    Samples at ``t_k = k period`` (s from the start), padded at the end with
    rest samples (last pose, zero velocity and acceleration) up to the first
    multiple of ``period`` at or after the duration; never cut short.

    Args:
        trajectory: A Drake ``Trajectory`` with derivatives (e.g. a
            ``RetimeResult.trajectory``), a ``SavedTrajectory``, or the path
            of a trajectory ``.npz`` file.
        out: The file: ``.mcap`` (a ROS 2 bag of one
            ``trajectory_msgs/msg/JointTrajectory``) or ``.csv``
            (``t, q_*, qd_*, qdd_*``), as ``format`` says.
        format: ``"mcap"`` or ``"csv"`` (an :class:`ExportFormat`).
        period: The controller's period, s: finite, > 0, a whole number of
            nanoseconds, at most the trajectory's duration.
        joint_names: The controller's joint names, one per joint (default:
            the ``plant``'s).
        plant: The plant whose joints the trajectory moves, for its names.
        topic: The bag's topic (mcap only).

    Raises:
        InputError: any bad argument, ``out`` equal to the input file or not
            writable, a trajectory that does not end at rest.
        TooLargeError: more than a million samples.
    """
    where = "export_trajectory"
    kind = export_format(format, f"{where}: format")
    arguments.number(period, "period", where=where, above=0.0)
    out = arguments.path(out, "out", where=where)
    if out.suffix != kind.suffix:
        raise InputError(f"{where}: out '{out}' must end in {kind.suffix}")
    if isinstance(trajectory, (str, Path)):
        source = Path(trajectory)
        if out.resolve() == source.resolve() or (
            out.exists() and source.exists() and out.samefile(source)
        ):
            raise InputError(
                f"{where}: out '{out}' is the input trajectory file: refusing to "
                "write over it"
            )
        trajectory = load_trajectory(source)
        where = f"{where}: {source}"
    problem = output_problem(out)
    if problem is not None:
        raise InputError(f"{where}: cannot write out '{out}': {problem}")
    arguments.instance(topic, "topic", str, where=where)
    if not topic.startswith("/"):
        raise InputError(f"{where}: topic must start with '/', got {topic!r}")
    motion = as_trajectory(trajectory, where)
    rows = motion.rows()
    if joint_names is not None:
        names = check_joint_names(joint_names, rows, f"{where}: joint_names")
    elif plant is not None:
        arguments.instance(plant, "plant", MultibodyPlant, where=where)
        names = check_joint_names(
            controller_joint_names(plant), rows, f"{where}: the plant's joints"
        )
    else:
        raise InputError(
            f"{where}: give joint_names, or the plant whose joint names to use"
        )
    samples = sample_on_grid(motion, period, where)
    if kind is ExportFormat.MCAP:
        return write_ros2_bag(out, samples, names, topic)
    return write_csv_table(out, samples, names)


__all__ = ["ExportFormat", "export_format", "export_trajectory"]
