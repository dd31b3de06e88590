"""A ROS 2 bag (MCAP) of one ``trajectory_msgs/msg/JointTrajectory``.

The bag holds one message on :data:`DEFAULT_TOPIC` with every sample as a
point, which is what ROS 2's ``joint_trajectory_controller`` takes on its
``~/joint_trajectory`` topic (``ros2 bag play`` sends it once):
``header.stamp = 0`` (start on receipt), ``joint_names``, and per sample
``positions`` (rad), ``velocities`` (rad/s), ``accelerations`` (rad/s^2),
``effort`` empty and ``time_from_start`` (``k period`` as whole
nanoseconds). The message is logged at time 0.

The schema is the message definition as ``ros2 bag record`` stores it: the
top-level ``.msg`` text, then each dependency after a line of 80 ``=`` and
``MSG: pkg/Type`` (std_msgs/Header, builtin_interfaces/Time,
trajectory_msgs/JointTrajectoryPoint, builtin_interfaces/Duration), so
Foxglove and ``ros2 bag`` decode it without the ROS packages installed.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import BinaryIO

from mcap_ros2.writer import Writer

from rt_drake.atomic_file import write_atomically
from rt_drake.export._grid_samples import GridSamples

#: The message type.
SCHEMA_NAME = "trajectory_msgs/msg/JointTrajectory"
#: The command topic of a controller named ``joint_trajectory_controller``.
DEFAULT_TOPIC = "/joint_trajectory_controller/joint_trajectory"

_SEPARATOR = "=" * 80
_DEFINITIONS = (
    (
        None,
        "std_msgs/Header header\nstring[] joint_names\nJointTrajectoryPoint[] points",
    ),
    ("std_msgs/Header", "builtin_interfaces/Time stamp\nstring frame_id"),
    ("builtin_interfaces/Time", "int32 sec\nuint32 nanosec"),
    (
        "trajectory_msgs/JointTrajectoryPoint",
        "float64[] positions\nfloat64[] velocities\nfloat64[] accelerations\n"
        "float64[] effort\nbuiltin_interfaces/Duration time_from_start",
    ),
    ("builtin_interfaces/Duration", "int32 sec\nuint32 nanosec"),
)
#: The concatenated definition text of :data:`SCHEMA_NAME`.
JOINT_TRAJECTORY_DEFINITION = "\n".join(
    text if name is None else f"{_SEPARATOR}\nMSG: {name}\n{text}"
    for name, text in _DEFINITIONS
)

_NS_PER_S = 1_000_000_000


def joint_trajectory_message(
    samples: GridSamples, joint_names: Sequence[str]
) -> dict[str, object]:
    """The JointTrajectory of ``samples`` as the dict the CDR encoder takes."""
    points = [
        {
            "positions": q.tolist(),
            "velocities": qd.tolist(),
            "accelerations": qdd.tolist(),
            "effort": [],
            "time_from_start": {
                "sec": int(ns // _NS_PER_S),
                "nanosec": int(ns % _NS_PER_S),
            },
        }
        for q, qd, qdd, ns in zip(
            samples.q, samples.qd, samples.qdd, samples.time_ns, strict=True
        )
    ]
    return {
        "header": {"stamp": {"sec": 0, "nanosec": 0}, "frame_id": ""},
        "joint_names": list(joint_names),
        "points": points,
    }


def write_ros2_bag(
    path: Path,
    samples: GridSamples,
    joint_names: Sequence[str],
    topic: str = DEFAULT_TOPIC,
) -> Path:
    """Write the bag of ``samples`` to ``path`` (atomically); return ``path``."""
    message = joint_trajectory_message(samples, joint_names)

    def write(stream: BinaryIO) -> None:
        writer = Writer(stream)
        schema = writer.register_msgdef(SCHEMA_NAME, JOINT_TRAJECTORY_DEFINITION)
        writer.write_message(topic, schema, message, log_time=0, publish_time=0)
        writer.add_metadata(
            "rt_drake",
            {
                "period_s": repr(samples.period),
                "duration_s": repr(samples.duration),
                "samples": str(len(samples.t)),
            },
        )
        writer.finish()

    return write_atomically(path, write)


__all__ = [
    "DEFAULT_TOPIC",
    "JOINT_TRAJECTORY_DEFINITION",
    "SCHEMA_NAME",
    "joint_trajectory_message",
    "write_ros2_bag",
]
