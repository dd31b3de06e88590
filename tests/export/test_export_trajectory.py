"""``export_trajectory``: the files decode to the trajectory sampled at the period.

The reference is the retimed motion sampled every 1 ms by
``sample_trajectory`` (from the retimer's own trajectory); an export of the
``.npz`` rebuilds the motion from the file's path and s'(s) profile, so the
two agree only if both describe the same motion. Periods of 2 and 8 ms are
multiples of 1 ms: sample k of the export is sample ``k period / 1 ms`` of
the reference.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from rt_drake import export_trajectory
from rt_drake.export import (
    DEFAULT_TOPIC,
    JOINT_TRAJECTORY_DEFINITION,
    SCHEMA_NAME,
    plant_joint_names,
)
from rt_drake.retiming import TimeScaled

with warnings.catch_warnings():  # its docstring, warned as deprecated on import
    warnings.simplefilter("ignore", DeprecationWarning)
    from mcap_ros2.reader import read_ros2_messages

TOLERANCE = 1e-9


def reference(saved, period):
    """(t, q, qd, qdd) every ``period`` (a multiple of 1 ms) while moving."""
    step = round(period / 1e-3)
    assert math.isclose(step * 1e-3, period)
    rows = slice(None, len(saved.t) - 1, step)  # the last 1 ms sample is at D
    return saved.t[rows], saved.q[rows], saved.qd[rows], saved.qdd[rows]


def read_bag(path):
    messages = list(read_ros2_messages(str(path)))
    assert len(messages) == 1  # one JointTrajectory with every point
    return messages[0]


@pytest.mark.parametrize("period", [0.002, 0.008])
def test_the_bag_reads_back_as_the_trajectory_sampled_at_the_period(
    tmp_path, npz, saved, plant, period
):
    out = export_trajectory(
        npz, tmp_path / "move.mcap", format="mcap", period=period, plant=plant
    )
    message = read_bag(out)
    assert message.channel.topic == DEFAULT_TOPIC
    assert message.schema.name == SCHEMA_NAME
    assert message.schema.data.decode() == JOINT_TRAJECTORY_DEFINITION
    msg = message.ros_msg
    assert list(msg.joint_names) == [f"joint{i}" for i in range(1, 7)]
    t = np.array(
        [p.time_from_start.sec + 1e-9 * p.time_from_start.nanosec for p in msg.points]
    )
    q, qd, qdd = (
        np.array([getattr(p, field) for p in msg.points])
        for field in ("positions", "velocities", "accelerations")
    )
    t_ref, q_ref, qd_ref, qdd_ref = reference(saved, period)
    moving = len(t_ref)
    np.testing.assert_allclose(t[:moving], t_ref, rtol=0, atol=TOLERANCE)
    np.testing.assert_allclose(q[:moving], q_ref, rtol=0, atol=TOLERANCE)
    np.testing.assert_allclose(qd[:moving], qd_ref, rtol=0, atol=TOLERANCE)
    np.testing.assert_allclose(qdd[:moving], qdd_ref, rtol=0, atol=TOLERANCE)
    assert np.abs(qdd[:moving]).max() > 1.0  # the comparison saw motion
    # the end: at rest at the last pose, on the grid
    assert t[moving - 1] < saved.duration <= t[-1] < saved.duration + period
    np.testing.assert_allclose(
        q[moving:], saved.q[-1][None].repeat(len(q) - moving, 0), atol=TOLERANCE
    )
    assert np.all(qd[moving:] == 0.0) and np.all(qdd[moving:] == 0.0)


@pytest.mark.parametrize("period", [0.002, 0.008])
def test_the_csv_decodes_to_the_trajectory_sampled_at_the_period(
    tmp_path, npz, saved, period
):
    names = [f"axis_{i}" for i in range(6)]
    out = export_trajectory(
        npz, tmp_path / "move.csv", format="csv", period=period, joint_names=names
    )
    header = out.read_text().splitlines()[0].split(",")
    assert header == ["t"] + [f"{p}_{n}" for p in ("q", "qd", "qdd") for n in names]
    table = np.loadtxt(out, delimiter=",", skiprows=1)
    t, q, qd, qdd = table[:, 0], table[:, 1:7], table[:, 7:13], table[:, 13:19]
    t_ref, q_ref, qd_ref, qdd_ref = reference(saved, period)
    moving = len(t_ref)
    for got, expected in ((t, t_ref), (q, q_ref), (qd, qd_ref), (qdd, qdd_ref)):
        np.testing.assert_allclose(got[:moving], expected, rtol=0, atol=TOLERANCE)
    np.testing.assert_allclose(q[-1], saved.q[-1], rtol=0, atol=TOLERANCE)
    assert np.all(qd[moving:] == 0.0) and np.all(qdd[moving:] == 0.0)


@pytest.mark.parametrize("period", [0.0021, 0.008, 0.0333])
def test_the_grid_is_padded_at_rest_to_a_multiple_of_the_period_never_cut(
    tmp_path, retimed, period
):
    """The retimer's own trajectory, at periods that do not divide its duration."""
    out = export_trajectory(
        retimed.trajectory, tmp_path / "m.csv", format="csv", period=period,
        joint_names=list("abcdef"),
    )  # fmt: skip
    table = np.loadtxt(out, delimiter=",", skiprows=1)
    t = table[:, 0]
    steps = t / period
    np.testing.assert_allclose(steps, np.arange(len(t)), rtol=0, atol=1e-9)
    duration = retimed.duration
    assert duration % period > 1e-6  # the duration is off the grid
    assert t[-2] < duration <= t[-1]  # one rest sample past the end, no more
    q_end = retimed.trajectory.value(retimed.trajectory.end_time()).ravel()
    np.testing.assert_allclose(table[-1, 1:7], q_end, rtol=0, atol=TOLERANCE)
    assert np.all(table[-1, 7:] == 0.0)
    # the moving samples follow each other: velocities integrate to positions
    q, qd = table[:-1, 1:7], table[:-1, 7:13]
    trapezoid = q[0] + np.cumsum((qd[1:] + qd[:-1]) / 2 * period, axis=0)
    assert np.abs(trapezoid - q[1:]).max() < 50 * period**2


def test_the_bag_is_what_ros2_bag_and_foxglove_read(tmp_path, retimed, plant):
    """The ros2 profile, CDR messages, a ros2msg schema (the MCAP spec's names)."""
    from mcap.reader import make_reader

    out = export_trajectory(
        retimed.trajectory, tmp_path / "m.mcap", period=0.008, plant=plant
    )
    with out.open("rb") as stream:
        reader = make_reader(stream)
        assert reader.get_header().profile == "ros2"
        summary = reader.get_summary()
    assert summary is not None and summary.statistics.message_count == 1
    (channel,) = summary.channels.values()
    (schema,) = summary.schemas.values()
    assert channel.message_encoding == "cdr" and schema.encoding == "ros2msg"
    assert channel.topic == DEFAULT_TOPIC and schema.name == SCHEMA_NAME
    # every type the definition uses is defined in it, after a separator
    text = schema.data.decode()
    for name in (
        "std_msgs/Header",
        "builtin_interfaces/Time",
        "trajectory_msgs/JointTrajectoryPoint",
        "builtin_interfaces/Duration",
    ):
        assert f"{'=' * 80}\nMSG: {name}\n" in text, name


def test_the_names_are_the_plants_by_default(tmp_path, retimed, plant):
    assert plant_joint_names(plant) == [f"joint{i}" for i in range(1, 7)]
    out = export_trajectory(
        retimed.trajectory, tmp_path / "m.mcap", period=0.004, plant=plant
    )
    assert list(read_bag(out).ros_msg.joint_names) == plant_joint_names(plant)


def test_a_motion_played_faster_is_exported_as_played(tmp_path, retimed):
    """``run --speed f`` plays ``q(f t)``: velocities scale by f, accelerations f^2."""
    factor = 1.5
    faster = TimeScaled(retimed.trajectory, factor)
    out = export_trajectory(
        faster,
        tmp_path / "m.csv",
        format="csv",
        period=0.004,
        joint_names=list("abcdef"),
    )
    table = np.loadtxt(out, delimiter=",", skiprows=1)
    moving = table[:, 0] < faster.end_time()
    q, qd, qdd = retimed.trajectory.sample(factor * table[moving, 0], order=2)
    np.testing.assert_allclose(table[moving, 1:7], q, rtol=0, atol=TOLERANCE)
    np.testing.assert_allclose(table[moving, 7:13], factor * qd, rtol=0, atol=TOLERANCE)
    np.testing.assert_allclose(
        table[moving, 13:], factor**2 * qdd, rtol=0, atol=TOLERANCE
    )
    assert table[-1, 0] >= faster.end_time() and not table[-1, 7:].any()
