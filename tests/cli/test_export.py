"""``rt-drake export`` and ``rt-drake run --export``: files, names, exit codes."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from rt_drake.cli import main
from rt_drake.cli._run_export import RecordingMotions, export_motions
from rt_drake.export import ExportFormat
from rt_drake.model.resources import scenarios_dir
from rt_drake.simulation.motion import Motion

with warnings.catch_warnings():  # its docstring, warned as deprecated on import
    warnings.simplefilter("ignore", DeprecationWarning)
    from mcap_ros2.reader import read_ros2_messages

HOME = np.array([0.0, 0.35, 1.75, 0.0, 1.04, 0.0])
WAYPOINTS = np.array([HOME, HOME + [-0.4, 0.1, -0.2, 0.0, 0.1, -0.5]])
UR_NAMES = "shoulder_pan_joint,shoulder_lift_joint,elbow_joint,wrist_1_joint,"
UR_NAMES += "wrist_2_joint,wrist_3_joint"


@pytest.fixture(scope="module")
def npz(tmp_path_factory):
    """A trajectory file written by ``rt-drake retime``."""
    folder = tmp_path_factory.mktemp("export")
    csv = folder / "waypoints.csv"
    np.savetxt(csv, WAYPOINTS, delimiter=",")
    out = folder / "move.npz"
    argv = ["retime", "stack_four_objects", "--waypoints", str(csv)]
    assert main([*argv, "--object", "notebook", "--out", str(out)]) == 0
    return out


def bag_names(path):
    (message,) = list(read_ros2_messages(str(path)))
    return list(message.ros_msg.joint_names), message.ros_msg.points


@pytest.mark.parametrize(
    "flags,names",
    [
        (
            ["--scenario", "stack_four_objects"],
            "joint1,joint2,joint3,joint4,joint5,joint6",
        ),
        (["--scenario", "ur5e_transport"], UR_NAMES),  # the scenario's map
        (
            ["--scenario", "ur5e_transport", "--joint-names", "a,b,c,d,e,f"],
            "a,b,c,d,e,f",
        ),
    ],
)
def test_export_writes_a_bag_with_the_plants_or_the_maps_names(
    tmp_path, npz, capsys, flags, names
):
    out = tmp_path / "move.mcap"
    argv = ["export", str(npz), "--period", "0.008", "--out", str(out), *flags]
    assert main(argv) == 0
    assert "wrote ROS 2 bag" in capsys.readouterr().out
    got, points = bag_names(out)
    assert got == names.split(",")
    data = np.load(npz)
    assert len(points) == int(np.ceil(float(data["duration"]) / 0.008)) + 1
    np.testing.assert_allclose(points[0].positions, data["q"][0], rtol=0, atol=1e-9)


def test_export_writes_a_csv_when_asked(tmp_path, npz):
    out = tmp_path / "move.csv"
    argv = ["export", str(npz), "--format", "csv", "--period", "0.004"]
    assert main([*argv, "--out", str(out), "--joint-names", "a,b,c,d,e,f"]) == 0
    table = np.loadtxt(out, delimiter=",", skiprows=1)
    data = np.load(npz)
    np.testing.assert_allclose(table[:-1, 1:7], data["q"][:-1:4][: len(table) - 1],
                               rtol=0, atol=1e-9)  # fmt: skip


@pytest.mark.parametrize(
    "flags,words",
    [
        (["--period", "0", "--out", "m.mcap"], ["--period", "must be"]),
        (["--period", "nan", "--out", "m.mcap"], ["--period", "nan"]),
        (["--period", "9", "--out", "m.mcap"], ["longer than the trajectory"]),
        (
            ["--period", "0.008", "--out", "m.bag"],
            ["must be one of mcap, csv", "'bag'"],
        ),
        (["--period", "0.008", "--out", "m.mcap", "--format", "csv"], ["end in .csv"]),
        (
            ["--period", "0.008", "--out", "m.mcap"],
            ["give --scenario", "--joint-names"],
        ),
        (
            ["--period", "0.008", "--out", "m.mcap", "--joint-names", "a,b"],
            ["2 joint names for a trajectory of 6 joints"],
        ),
    ],
)
def test_bad_input_exits_2_with_one_line(tmp_path, npz, capsys, flags, words):
    flags = [str(tmp_path / f) if f.startswith("m.") else f for f in flags]
    names = [] if "--joint-names" in flags or "give --scenario" in words else None
    argv = ["export", str(npz), *flags]
    if names is None:
        argv += ["--joint-names", "a,b,c,d,e,f"]
    assert main(argv) == 2
    error = capsys.readouterr().err.strip()
    assert error.startswith("rt-drake export: error:") and "\n" not in error, error
    for word in words:
        assert word in error, (word, error)


def test_export_never_writes_over_its_input(tmp_path, npz, capsys):
    before = npz.read_bytes()
    twin = tmp_path / "twin.mcap"
    twin.hardlink_to(npz)
    argv = ["export", str(npz), "--period", "0.008", "--out", str(twin)]
    assert main([*argv, "--joint-names", "a,b,c,d,e,f"]) == 2
    assert "refusing to write over it" in capsys.readouterr().err
    assert npz.read_bytes() == before


def test_a_map_naming_no_joint_of_the_plant_exits_2(tmp_path, npz, capsys):
    text = (scenarios_dir() / "ur5e_transport.yaml").read_text()
    assert "    joint6: wrist_3_joint" in text
    scenario = tmp_path / "ur.yaml"
    scenario.write_text(text.replace("    joint6: wrist_3_joint", "    joint7: x"))
    argv = ["export", str(npz), "--period", "0.008", "--out", str(tmp_path / "m.mcap")]
    assert main([*argv, "--scenario", str(scenario)]) == 2
    error = capsys.readouterr().err
    assert "ur.yaml" in error and "'joint7' is not a joint of the plant" in error


def test_run_checks_its_export_directory_before_simulating(tmp_path, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("not a directory")
    argv = ["run", "stack_four_objects", "--out", str(tmp_path / "run")]
    assert main([*argv, "--export", str(blocker)]) == 2
    assert "--export" in capsys.readouterr().err


class _Source:
    """Hands out one retimed trajectory as every motion (a MotionSource)."""

    def __init__(self, trajectory):
        self.trajectory = trajectory

    def pick(self, q_start, obj, retreat):
        return Motion(self.trajectory)

    def move(self, q_start, obj, pick):
        return Motion(self.trajectory)


def test_every_motion_handed_out_is_exported_by_object_and_kind(
    tmp_path, scenario, plant
):
    from rt_drake import JointLimits, retime

    trajectory = retime(
        plant, WAYPOINTS, JointLimits.from_plant(plant, scenario.robot)
    ).trajectory
    recorder = RecordingMotions(_Source(trajectory))
    first, second = scenario.objects[:2]
    recorder.pick(HOME, first, False)
    recorder.move(HOME, first, None)
    recorder.pick(HOME, second, True)
    names = list("abcdef")
    written = export_motions(
        recorder.motions, tmp_path, ExportFormat.MCAP, 0.002, names
    )
    expected = {
        f"{o.name}_{kind}.mcap"
        for o, kind in ((first, "pick"), (first, "move"), (second, "pick"))
    }
    assert {path.name for path in written} == expected
    assert {path.name for path in tmp_path.iterdir()} == expected
    for path in written:
        got, points = bag_names(path)
        assert got == names
        assert len(points) == int(np.ceil(trajectory.duration / 0.002)) + 1
