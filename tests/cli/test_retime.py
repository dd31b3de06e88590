"""``rt-drake retime``: the .npz it writes, and one-line errors on bad input."""

import argparse

import numpy as np
import pytest

from rt_drake.cli import retime as command
from rt_drake.errors import RtDrakeError

HOME = np.array([0.0, 0.35, 1.75, 0.0, 1.04, 0.0])
WAYPOINTS = np.array(
    [
        HOME,
        HOME + [-0.4, 0.1, -0.2, 0.0, 0.1, -0.5],
        HOME + [-1.2, -0.1, 0.2, 0, -0.1, -0.8],
    ]
)


def _run(*argv):
    parser = argparse.ArgumentParser()
    command.register(parser.add_subparsers(dest="command"))
    args = parser.parse_args(["retime", "stack_four_objects", *argv])
    return args.run(args)


@pytest.fixture()
def csv(tmp_path):
    path = tmp_path / "waypoints.csv"
    np.savetxt(path, WAYPOINTS, delimiter=",", header="joint1..joint6, rad")
    return path


def test_writes_a_checkable_npz(csv, tmp_path, capsys):
    out = tmp_path / "out.npz"
    assert _run("--waypoints", str(csv), "--object", "notebook", "--out", str(out)) == 0
    assert "retimed to" in capsys.readouterr().out
    data = np.load(out)
    t, q, qd, qdd = data["t"], data["q"], data["qd"], data["qdd"]
    assert t[0] == 0.0 and t[-1] == pytest.approx(float(data["duration"]))
    assert np.allclose(np.diff(t)[:-1], 1e-3)
    np.testing.assert_allclose(q[[0, -1]], WAYPOINTS[[0, -1]], atol=1e-9)
    # q' is q's derivative (up to O(h^2) where s'' switches).
    np.testing.assert_allclose(
        np.gradient(q, t, axis=0)[1:-2], qd[1:-2], atol=1e-2 * np.abs(qd).max()
    )
    assert data["X_WC"].shape == (len(t), 4, 4)
    np.testing.assert_allclose(data["X_WC"][:, 3], [[0, 0, 0, 1]] * len(t))
    assert data["F"].shape == (len(data["g"]), 6) and len(data["g"]) > 100
    assert float(data["object_mass"]) == pytest.approx(0.551)
    cup = dict(zip(data["cup_names"], data["cup_values"], strict=True))
    assert cup["suction_force"] == 20.0
    assert np.isfinite(qdd).all()


def test_grasp_constraint_slows_the_motion(csv, tmp_path):
    with_grasp, without = tmp_path / "a.npz", tmp_path / "b.npz"
    _run("--waypoints", str(csv), "--object", "notebook", "--out", str(with_grasp))
    _run(
        "--waypoints",
        str(csv),
        "--object",
        "notebook",
        "--no-grasp-constraint",
        "--out",
        str(without),
    )
    a, b = np.load(with_grasp), np.load(without)
    assert float(a["duration"]) > float(b["duration"])
    assert b["F"].shape == (0, 6) and b["g"].shape == (0,)


@pytest.mark.parametrize(
    "content, message",
    [
        (None, "does not exist"),
        ("0,0,0,0,0\n1,1,1,1,1\n", "5 columns but the robot has 6 joints"),
        ("0,0,0,0,0,0\n1,nan,1,1,1,1\n", "waypoint 2 is not finite"),
        ("0,0,0,0,0,0\n", "at least 2 waypoints"),
        ("a,b,c,d,e,f\n0,0,0,0,0,0\n", "not a CSV of numbers"),
    ],
)
def test_bad_waypoint_files(tmp_path, content, message):
    path = tmp_path / "w.csv"
    if content is not None:
        path.write_text(content)
    with pytest.raises(ValueError, match=message):
        _run(
            "--waypoints",
            str(path),
            "--object",
            "notebook",
            "--out",
            str(tmp_path / "o.npz"),
        )


def test_unknown_object(csv, tmp_path):
    with pytest.raises(RtDrakeError, match="unknown object 'teapot'"):
        _run(
            "--waypoints",
            str(csv),
            "--object",
            "teapot",
            "--out",
            str(tmp_path / "o.npz"),
        )


def test_uncertainty_flags_retime_for_every_object_of_the_set(csv, tmp_path, capsys):
    nominal, robust = tmp_path / "n.npz", tmp_path / "r.npz"
    base = ["--waypoints", str(csv), "--object", "notebook"]
    _run(*base, "--out", str(nominal))
    flags = ["--mass-uncertainty", "0.2", "--com-uncertainty", "0.01,0.01,0.005"]
    _run(*base, *flags, "--inertia-uncertainty", "0.2", "--out", str(robust))
    out = capsys.readouterr().out
    assert "robust grasp constraint: every object of the set (mass +-20 %" in out
    assert float(np.load(robust)["duration"]) > float(np.load(nominal)["duration"])


@pytest.mark.parametrize(
    ("flags", "message"),
    [
        (["--mass-uncertainty", "1.0"], r"uncertainty.mass must be in \[0, 1\).*1.0"),
        (["--inertia-uncertainty", "-0.1"], r"uncertainty.inertia .*-0.1"),
        (["--com-uncertainty", "0.01,-0.01,0"], r"uncertainty.com .*-0.01"),
        (["--com-uncertainty", "0,0,0.02"], r"com\[2\] = 0.02 m .*outside the object"),
    ],
)
def test_bad_uncertainty_flags_are_one_line_errors(csv, tmp_path, flags, message):
    with pytest.raises(RtDrakeError, match=message) as error:
        _run(
            *["--waypoints", str(csv), "--object", "notebook"],
            *flags,
            "--out",
            str(tmp_path / "o.npz"),
        )
    assert "\n" not in str(error.value)
