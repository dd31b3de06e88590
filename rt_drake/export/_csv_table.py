"""A CSV of samples: one row per sample, one column per quantity.

Header ``t,q_<j1>,...,q_<jn>,qd_<j1>,...,qd_<jn>,qdd_<j1>,...,qdd_<jn>``
(``<j>`` the exported joint names), then one row per sample: t (s from the
trajectory's start), positions (rad), velocities (rad/s), accelerations
(rad/s^2), each written with 17 significant digits, so that a float64 read
back (``numpy.loadtxt(path, delimiter=",", skiprows=1)``) is the sample.
"""

from __future__ import annotations

import io
from collections.abc import Sequence
from pathlib import Path
from typing import BinaryIO

import numpy as np

from rt_drake.atomic_file import write_atomically
from rt_drake.export._grid_samples import GridSamples


def csv_header(joint_names: Sequence[str]) -> str:
    """The header line (no newline): ``t``, then q_, qd_, qdd_ of each joint."""
    columns = ["t"] + [
        f"{prefix}_{name}" for prefix in ("q", "qd", "qdd") for name in joint_names
    ]
    return ",".join(columns)


def write_csv_table(
    path: Path, samples: GridSamples, joint_names: Sequence[str]
) -> Path:
    """Write ``samples`` as the CSV above to ``path`` (atomically)."""
    table = np.column_stack([samples.t, samples.q, samples.qd, samples.qdd])

    def write(stream: BinaryIO) -> None:
        text = io.TextIOWrapper(stream, encoding="utf-8", newline="\n")
        np.savetxt(
            text, table, fmt="%.17g", delimiter=",",
            header=csv_header(joint_names), comments="",
        )  # fmt: skip
        text.flush()
        text.detach()

    return write_atomically(path, write)


__all__ = ["csv_header", "write_csv_table"]
