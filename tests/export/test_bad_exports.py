"""Bad exports are refused in one line naming the problem; inputs survive."""

from __future__ import annotations

import numpy as np
import pytest
from pydrake.trajectories import PiecewisePolynomial

from rt_drake import export_trajectory, load_scenario
from rt_drake.errors import InputError, ScenarioError, TooLargeError
from rt_drake.export import controller_joint_names
from rt_drake.model.plant import make_arm_plant
from rt_drake.model.resources import scenarios_dir

NAMES = list("abcdef")
UR_NAMES = [
    "shoulder_pan_joint",
    "shoulder_lift_joint",
    "elbow_joint",
    "wrist_1_joint",
    "wrist_2_joint",
    "wrist_3_joint",
]


def refused(call, *words, error=InputError):
    with pytest.raises(error) as info:
        call()
    message = str(info.value)
    assert "\n" not in message, message
    for word in words:
        assert word in message, (word, message)
    return message


@pytest.mark.parametrize(
    "period,words",
    [
        (0.0, ["period must be a finite number > 0", "0.0"]),
        (-0.008, ["period must be a finite number > 0", "-0.008"]),
        (float("nan"), ["period must be a finite number > 0", "nan"]),
        ("8 ms", ["period must be a finite number", "'8 ms'"]),
        (1e-10, ["whole number of nanoseconds", "1e-10"]),
        (5.0, ["period 5 s is longer than the trajectory"]),
        (1e-9, ["at most 1000000 are exported"]),
    ],
)
def test_a_bad_period_is_refused(tmp_path, retimed, period, words):
    error = TooLargeError if period == 1e-9 else InputError
    out = tmp_path / "m.csv"
    refused(
        lambda: export_trajectory(
            retimed.trajectory, out, format="csv", period=period, joint_names=NAMES
        ),
        *words,
        error=error,
    )
    assert not out.exists()


def test_an_unknown_format_or_suffix_is_refused(tmp_path, retimed):
    def export(out, kind):
        return lambda: export_trajectory(
            retimed.trajectory, out, format=kind, period=0.008, joint_names=NAMES
        )

    refused(
        export(tmp_path / "m.bag", "bag"), "format must be one of mcap, csv", "'bag'"
    )
    refused(export(tmp_path / "m.csv", "mcap"), "out", "must end in .mcap")


@pytest.mark.parametrize(
    "names,words",
    [
        (NAMES[:5], ["5 joint names for a trajectory of 6 joints"]),
        ([*NAMES[:5], "a"], ["joint name 'a' is given twice"]),
        ([*NAMES[:5], " "], ["joint name 6 is empty"]),
        ([*NAMES[:5], "f,g"], ["joint name 'f,g' holds a comma"]),
        ("abcdef", ["must be a list of strings"]),
    ],
)
def test_wrong_joint_names_are_refused(tmp_path, retimed, names, words):
    refused(
        lambda: export_trajectory(
            retimed.trajectory, tmp_path / "m.csv", format="csv", period=0.008,
            joint_names=names,
        ),
        "joint_names", *words,
    )  # fmt: skip


def test_names_are_needed(tmp_path, retimed):
    refused(
        lambda: export_trajectory(
            retimed.trajectory, tmp_path / "m.mcap", period=0.008
        ),
        "give joint_names, or the plant",
    )


def test_the_input_file_is_never_overwritten(tmp_path, npz):
    before = npz.read_bytes()
    twin = npz.with_suffix(".csv")
    twin.hardlink_to(npz)  # another name of the same file
    refused(
        lambda: export_trajectory(
            npz, twin, format="csv", period=0.008, joint_names=NAMES
        ),
        "is the input trajectory file", "refusing to write over it",
    )  # fmt: skip
    assert npz.read_bytes() == before


def test_a_trajectory_that_ends_moving_is_not_padded_with_rest(tmp_path):
    ramp = PiecewisePolynomial.FirstOrderHold([0.0, 1.0], np.array([[0.0, 1.0]] * 6))
    refused(
        lambda: export_trajectory(
            ramp, tmp_path / "m.csv", format="csv", period=0.01, joint_names=NAMES
        ),
        "trajectory ends moving", "1 rad/s",
    )  # fmt: skip


def test_a_trajectory_at_rest_of_any_drake_type_is_sampled_exactly(tmp_path):
    """A quintic that starts and ends at rest: values against its closed form."""
    times = np.array([0.0, 0.5])
    q0, q1 = np.zeros((6, 1)), np.linspace(0.1, 0.6, 6)[:, None]
    quintic = PiecewisePolynomial.CubicWithContinuousSecondDerivatives(
        times, np.hstack([q0, q1]), np.zeros((6, 1)), np.zeros((6, 1))
    )
    out = export_trajectory(
        quintic, tmp_path / "m.csv", format="csv", period=0.03, joint_names=NAMES
    )
    table = np.loadtxt(out, delimiter=",", skiprows=1)
    t = table[:, 0]
    assert t[-1] == pytest.approx(0.51) and len(t) == 18
    # the clamped cubic through two points: q = q0 + (q1 - q0)(3 x^2 - 2 x^3)
    x = np.clip(t / 0.5, 0.0, 1.0)[:, None]
    q = q1.T * (3 * x**2 - 2 * x**3)
    qd = q1.T * (6 * x - 6 * x**2) / 0.5 * (t[:, None] < 0.5)
    np.testing.assert_allclose(table[:, 1:7], q, atol=1e-12)
    np.testing.assert_allclose(table[:, 7:13], qd, atol=1e-12)


def test_the_ur5e_map_names_its_joints_as_urs_ros2_driver():
    scenario = load_scenario(scenarios_dir() / "ur5e_transport.yaml")
    plant = make_arm_plant(scenario)
    assert controller_joint_names(plant, scenario.robot.joint_names) == UR_NAMES
    # a partial map renames what it names and keeps the plant's other names
    partial = controller_joint_names(plant, {"joint3": "elbow"})
    assert partial == ["joint1", "joint2", "elbow", "joint4", "joint5", "joint6"]


def test_a_map_key_that_is_not_a_plant_joint_is_refused(plant):
    refused(
        lambda: controller_joint_names(plant, {"joint7": "wrist_4_joint"}),
        "robot.joint_names", "'joint7' is not a joint of the plant", "joint6",
    )  # fmt: skip
    refused(
        lambda: controller_joint_names(plant, {"joint1": "joint2"}),
        "robot.joint_names", "'joint2' is given twice",
    )  # fmt: skip


@pytest.mark.parametrize(
    "entry,words",
    [
        ("  joint_names: [a, b]\n", ["robot.joint_names", "expected a mapping"]),
        (
            "  joint_names: {joint1: 3}\n",
            ["robot.joint_names.joint1", "expected a string"],
        ),
        (
            "  joint_names: {joint1: a, joint2: a}\n",
            ["robot.joint_names", "controller name 'a' is given twice"],
        ),
    ],
)
def test_a_malformed_scenario_map_is_refused(tmp_path, entry, words):
    text = (scenarios_dir() / "ur5e_transport.yaml").read_text()
    start = text.index("  joint_names:")
    end = text.index("\n", text.index("joint6:", start)) + 1
    path = tmp_path / "bad.yaml"
    path.write_text(text[:start] + entry + text[end:])
    refused(lambda: load_scenario(path), "bad.yaml", *words, error=ScenarioError)


@pytest.mark.parametrize(
    "key,change,words",
    [
        ("sd", lambda sd: np.where(np.arange(len(sd)) == 3, np.nan, sd),
         ["key 'sd' must be", "finite", "nan"]),
        ("sd", lambda sd: np.zeros_like(sd), ["key 'sd'", "zero at both ends"]),
        ("sd", lambda sd: sd[:-1], ["key 'sd' must be a"]),
        ("knots", lambda k: k[:-1], ["key 'knots' has 2 values for 3 waypoints"]),
        ("knots", lambda k: k[::-1], ["key 'knots' must increase strictly"]),
        ("gridpoints", lambda s: 2 * s, ["key 'gridpoints' must increase strictly"]),
        ("waypoints", lambda w: w[:, :1].ravel(), ["key 'waypoints' must be a (K, n)"]),
    ],
)  # fmt: skip
def test_a_corrupt_trajectory_file_is_refused_naming_file_and_key(
    tmp_path, npz, key, change, words
):
    """A file whose arrays do not describe a motion: never NaN samples."""
    with np.load(npz) as data:
        arrays = dict(data)
    arrays[key] = change(arrays[key])
    bad = tmp_path / "bad.npz"
    np.savez(bad, **arrays)
    out = tmp_path / "m.csv"
    refused(
        lambda: export_trajectory(
            bad, out, format="csv", period=0.008, joint_names=NAMES
        ),
        "bad.npz", *words,
    )  # fmt: skip
    assert not out.exists()
