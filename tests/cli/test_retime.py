"""``rt-drake retime``: the .npz it writes, and one-line errors on bad input."""

import argparse

import numpy as np
import pytest

from rt_drake.cli import _retime as command
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
    # A set of objects is retimed without jerk limits (not yet supported).
    base = ["--waypoints", str(csv), "--object", "notebook", "--no-jerk-limits"]
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


def test_retimes_under_a_multi_cup_tool(tmp_path, capsys):
    """A scenario ``tool:`` of two coarse cups: the motion stays in W_T.

    Checked by the LP of ``tests/tool_reference.py`` over every rim force
    of both cups, on wrenches from the written samples by Newton-Euler.
    """
    from tool_reference import residual

    from rt_drake import CupFrame, CupParameters, HeldObject, load_scenario
    from rt_drake.dynamics.newton_euler import reference_object_wrench
    from rt_drake.model.plant import make_arm_plant
    from rt_drake.model.resources import scenarios_dir

    text = (scenarios_dir() / "stack_four_objects.yaml").read_text()
    start, end = text.index("\ncup:\n"), text.index("max_normal_force: 33.3\n")
    tool = (
        "\ntool:\n  cups:\n"
        "    - {pose: {translation: [0.06, 0, 0]}, points: 4, sides: 3}\n"
        "    - {pose: {translation: [-0.06, 0, 0]}, points: 4, sides: 3}\n"
    )
    scenario = tmp_path / "two_cups.yaml"
    scenario.write_text(
        text[:start] + tool + text[end + len("max_normal_force: 33.3\n") :]
    )
    waypoints = tmp_path / "waypoints.csv"
    np.savetxt(waypoints, WAYPOINTS, delimiter=",")
    out = tmp_path / "out.npz"
    parser = argparse.ArgumentParser()
    command.register(parser.add_subparsers(dest="command"))
    args = parser.parse_args(
        ["retime", str(scenario), "--waypoints", str(waypoints)]
        + ["--object", "notebook", "--out", str(out)]
    )
    assert args.run(args) == 0
    assert "grasp constraint, a tool of 2 cups" in capsys.readouterr().out

    data = np.load(out)
    cup = dict(zip(data["cup_names"], data["cup_values"], strict=True))
    assert cup["cups[0].points"] == 4 and cup["cups[1].sides"] == 3
    assert cup["cups[1].p_TC[0]"] == -0.06 and cup["cups[1].R_TC[2][2]"] == 1.0
    plant = make_arm_plant(load_scenario(scenario))
    held = HeldObject(float(data["object_mass"]), data["p_CoScm_C"], data["I_Scm_C"])
    every = slice(None, None, max(1, len(data["t"]) // 80))
    wrenches = reference_object_wrench(
        plant,
        held,
        CupFrame.of(plant),
        data["q"][every],
        data["qd"][every],
        data["qdd"][every],
    )
    coarse = CupParameters(points=4, sides=3)
    two = [(coarse, np.array([0.06, 0.0, 0.0])), (coarse, np.array([-0.06, 0.0, 0.0]))]
    assert residual(wrenches, two).max() <= 1e-3
    # Too fast for one of these cups: the tool's set, not a cup's, was used.
    assert residual(wrenches, [(coarse, np.zeros(3))]).max() > 0.1


def test_jerk_limits_are_the_scenarios_unless_dropped(csv, tmp_path, capsys):
    """The .npz of a jerk-limited retime: its 1 kHz accelerations change by
    at most jerk x 1 ms per step; without jerk limits they jump."""
    from rt_drake.model.resources import scenarios_dir
    from rt_drake.model.scenario import load_scenario

    jerk = np.array(load_scenario(scenarios_dir() / "stack_four_objects.yaml")
                    .robot.jerk_limits)  # fmt: skip
    limited, free = tmp_path / "j.npz", tmp_path / "f.npz"
    base = ["--waypoints", str(csv), "--object", "notebook"]
    _run(*base, "--out", str(limited))
    _run(*base, "--no-jerk-limits", "--out", str(free))
    out = capsys.readouterr().out
    assert out.count("jerk limits") == 1
    for path, holds in ((limited, True), (free, False)):
        data = np.load(path)
        step = np.abs(np.diff(data["qdd"], axis=0)) / np.diff(data["t"])[:, None]
        assert bool(np.all(step <= jerk * (1 + 1e-3))) is holds


def test_ring_margin_is_found_for_the_waypoints(tmp_path, capsys):
    """``planning.grasp_margin: ring``: the margin the bellows' ring needs.

    The swing retimed with it is slower than with no margin, and the
    reported margin is the one the retimer's set was shrunk by.
    """
    from rt_drake.model.resources import scenarios_dir

    text = (scenarios_dir() / "random_transport_bellows.yaml").read_text()
    assert "grasp_margin: 0.18" in text
    waypoints = tmp_path / "waypoints.csv"
    np.savetxt(waypoints, WAYPOINTS, delimiter=",")
    durations = {}
    for margin in ("0", "ring"):
        scenario = tmp_path / f"margin_{margin}.yaml"
        scenario.write_text(
            text.replace("grasp_margin: 0.18", f"grasp_margin: {margin}")
        )
        out = tmp_path / f"{margin}.npz"
        parser = argparse.ArgumentParser()
        command.register(parser.add_subparsers(dest="command"))
        args = parser.parse_args(
            ["retime", str(scenario), "--waypoints", str(waypoints), "--no-jerk-limits"]
            + ["--object", "notebook", "--out", str(out)]
        )
        assert args.run(args) == 0
        printed = capsys.readouterr().out
        durations[margin] = float(np.load(out)["t"][-1])
    assert "for the bellows' ring" in printed
    found = float(printed.split("grasp margin ")[1].split()[0])
    assert 0.0 < found < 0.9
    assert durations["ring"] > durations["0"]


def test_jerk_torque_limits_and_an_uncertainty_set_together(tmp_path, capsys):
    """``random_transport_uncertain`` with jerk limits and ``limit_torques``:
    retimed (no longer refused), the 1 kHz accelerations changing by at
    most jerk x 1 ms per step; torque limits tight on joints 2 and 3 (a
    little above their gravity load) lengthen the motion, so they were
    applied."""
    from rt_drake.model.resources import scenarios_dir

    text = (scenarios_dir() / "random_transport_uncertain.yaml").read_text()
    jerk = [394.67, 336.89, 414.18, 419.33, 474.46, 670.21]
    robot = f"  jerk_limits: {jerk}\n  torque_limits: [150, 37.5, 24.8, 30, 30, 20]\n"
    assert "robot:\n" in text
    waypoints = tmp_path / "lift.csv"
    np.savetxt(waypoints, [HOME, HOME + [0.2, -0.3, -0.3, 0, 0.55, 0.1]], delimiter=",")
    durations = {}
    for torques in ("true", "false"):
        scenario = tmp_path / f"torques_{torques}.yaml"
        scenario.write_text(
            text.replace("robot:\n", f"robot:\n{robot}  limit_torques: {torques}\n", 1)
        )
        out = tmp_path / f"{torques}.npz"
        parser = argparse.ArgumentParser()
        command.register(parser.add_subparsers(dest="command"))
        args = parser.parse_args(
            ["retime", str(scenario), "--waypoints", str(waypoints)]
            + ["--object", "notebook", "--gridpoints", "30", "--out", str(out)]
        )
        assert args.run(args) == 0
        assert "every object of the set" in capsys.readouterr().out
        data = np.load(out)
        step = np.abs(np.diff(data["qdd"], axis=0)) / np.diff(data["t"])[:, None]
        assert np.all(step <= np.array(jerk) * (1 + 1e-3))
        durations[torques] = float(data["t"][-1])
    assert durations["true"] > 1.01 * durations["false"]
