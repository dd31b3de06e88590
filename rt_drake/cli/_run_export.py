"""``rt-drake run --export DIR``: every executed motion as a controller's file.

:class:`RecordingMotions` wraps the run's motion source and keeps each
motion the sequencer is handed, by object and kind: ``pick`` (APPROACH and
REACH, one motion) and ``move`` (MOVE, as played: with ``--speed`` the
faster trajectory). After the cycle :func:`export_motions` writes each as
``<object>_<kind>.mcap`` (or ``.csv``) in DIR, sampled at the export period
(:func:`rt_drake.export.export_trajectory`), with the controller's joint
names (the scenario's ``robot.joint_names`` applied).
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from rt_drake.export import ExportFormat, export_trajectory
from rt_drake.model.scenario import ObjectConfig
from rt_drake.simulation.motion import Motion, MotionSource

#: The kinds of motion an object gets, in the order they run.
KINDS = ("pick", "move")


def export_file_name(object_name: str, kind: str, format: ExportFormat) -> str:  # noqa: A002
    """``<object>_<kind>.<suffix>``, the object's name made safe for a file."""
    safe = re.sub(r"[^A-Za-z0-9._-]", "_", object_name)
    return f"{safe}_{kind}{format.suffix}"


class RecordingMotions:
    """A :class:`MotionSource` that keeps what ``source`` hands out.

    Attributes:
        motions: ``(object name, kind) -> Motion``, kind ``pick`` or
            ``move``; a motion asked for again replaces the earlier one.
    """

    def __init__(self, source: MotionSource) -> None:
        self._source = source
        self.motions: dict[tuple[str, str], Motion] = {}

    def pick(self, q_start: np.ndarray, obj: ObjectConfig, retreat: bool) -> Motion:
        """The source's pick, kept as ``(obj.name, "pick")``."""
        motion = self._source.pick(q_start, obj, retreat)
        self.motions[(obj.name, "pick")] = motion
        return motion

    def move(
        self, q_start: np.ndarray, obj: ObjectConfig, pick: Motion | None
    ) -> Motion:
        """The source's move, kept as ``(obj.name, "move")``."""
        motion = self._source.move(q_start, obj, pick)
        self.motions[(obj.name, "move")] = motion
        return motion


def export_motions(
    motions: dict[tuple[str, str], Motion],
    directory: Path,
    format: ExportFormat,  # noqa: A002
    period: float,
    joint_names: list[str],
) -> list[Path]:
    """Write each motion to ``directory`` (see the module docstring)."""
    return [
        export_trajectory(
            motion.trajectory,
            directory / export_file_name(name, kind, format),
            format=format,
            period=period,
            joint_names=joint_names,
        )
        for (name, kind), motion in motions.items()
    ]


__all__ = ["KINDS", "RecordingMotions", "export_file_name", "export_motions"]
