"""Every kind of bad input: exit code 2, one stderr line naming it, nothing lost.

One test (or parametrized family) per kind of the bad-input campaign
(``tools/bad_inputs.py``): silent wrong answers, hangs and blown
memory, data loss, tracebacks, poor messages. Each asserts the exit code,
that stderr is ONE line ``rt-drake <command>: error: ...`` naming the flag,
key or file and the value, and, where files are involved, that inputs are
byte-identical afterwards and no temporary file is left.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from rt_drake.cli import main
from rt_drake.model.resources import (
    models_dir,
    scenarios_dir,
)

BASE = (scenarios_dir() / "random_transport.yaml").read_text()
SDF = (models_dir() / "objects" / "notebook.sdf").read_text()
SWING = "0,0.35,1.75,0,1.04,0\n-0.4,0.45,1.55,0,1.14,-0.5\n-1.2,0.25,1.95,0,0.94,-0.8\n"
MODEL = "package://rt_drake/objects/notebook.sdf"
RETIME = ("retime", "random_transport", "--object", "notebook")


@pytest.fixture(autouse=True)
def _in_tmp(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("RT_DRAKE_CACHE_DIR", str(tmp_path / "cache"))


def edited(old: str, new: str, text: str = BASE) -> str:
    assert old in text, old
    return text.replace(old, new, 1)


def refused(capsys, argv: list[str], *words: str) -> str:
    """Run ``rt-drake argv``: exit 2, one line naming the command and ``words``."""
    assert main(argv) == 2
    err = capsys.readouterr().err
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith(f"rt-drake {argv[0]}"), lines[0]
    for word in words:
        assert word in lines[0], (word, lines[0])
    return lines[0]


def files_in(directory: Path) -> set[str]:
    return {str(p.relative_to(directory)) for p in directory.rglob("*")}


# -- silent wrong -------------------------------------------------------------


@pytest.mark.parametrize(
    "flag,value,words",
    [
        ("--radius", "1e-300", ["radius", "1e-300"]),  # was an all-zero F
        ("--radius", "1e300", ["radius", "1e+300"]),  # was vertices off the H-rep
        ("--suction-force", "1e300", ["suction_force", "1e+300"]),
        ("--friction", "100", ["friction", "100"]),
    ],
)
def test_unphysical_cup_parameters_are_refused(capsys, tmp_path, flag, value, words):
    refused(capsys, ["constraint", "--no-cache", flag, value, "--out", "o.npz"], *words)
    assert not (tmp_path / "o.npz").exists()


@pytest.mark.parametrize("value", ["0", "-5", "nan", "inf"])
def test_a_budget_that_is_not_a_positive_time_is_refused(capsys, value):
    argv = ["plan", "random_transport", "--object", "notebook", "--budget", value]
    refused(capsys, argv, "--budget", value)


@pytest.mark.parametrize(
    "argv,words",
    [
        (["run", "--time-step", "1e-9"], ["--time-step", "1e-9"]),
        (["run", "--speed", "1e300"], ["--speed", "1e300"]),
        (["run", "--seed", "-1"], ["--seed", "-1"]),
        (["experiment", "transport", "--n", "1000000", "--out", "o"], ["--n"]),
        (["experiment", "transport", "--workers", "500", "--out", "o"], ["--workers"]),
        (
            ["experiment", "transport", "--robust", "--optimize", "--out", "o"],
            ["--robust", "--optimize"],
        ),
    ],
)
def test_flags_asking_for_endless_work_are_refused(capsys, argv, words):
    refused(capsys, argv, *words)


def test_retime_out_with_another_suffix_is_refused_not_renamed(capsys, tmp_path):
    (tmp_path / "w.csv").write_text(SWING)
    refused(
        capsys, [*RETIME, "--waypoints", "w.csv", "--out", "x.csv"], "x.csv", ".npz"
    )
    assert files_in(tmp_path) == {"w.csv"}  # neither x.csv nor x.csv.npz


@pytest.mark.parametrize(
    "mass,words",
    [("0", ["mass", "0.0"]), ("-1", ["mass", "-1.0"]), ("nan", ["mass", "nan"])],
)
def test_an_object_of_invalid_mass_is_refused_not_taken_as_1_kg(
    capsys, tmp_path, mass, words
):
    (tmp_path / "obj.sdf").write_text(
        edited("<mass>0.551</mass>", f"<mass>{mass}</mass>", SDF)
    )
    (tmp_path / "s.yaml").write_text(edited(MODEL, str(tmp_path / "obj.sdf")))
    (tmp_path / "w.csv").write_text(SWING)
    argv = ["retime", "s.yaml", "--waypoints", "w.csv", "--object", "notebook"]
    refused(capsys, [*argv, "--out", "o.npz"], "s.yaml", "objects[0].model", *words)


def test_an_invalid_inertia_in_the_model_is_refused(capsys, tmp_path):
    inertia = "<ixx>0.000928</ixx><iyy>0.00211</iyy><izz>0.00298</izz>"
    triangle = "<ixx>0.001</ixx><iyy>0.001</iyy><izz>0.01</izz>"
    (tmp_path / "obj.sdf").write_text(edited(inertia, triangle, SDF))
    (tmp_path / "s.yaml").write_text(edited(MODEL, str(tmp_path / "obj.sdf")))
    argv = ["plan", "s.yaml", "--object", "notebook"]
    refused(capsys, argv, "obj.sdf", "triangle inequality")


NO_OBJECTS = BASE[: BASE.index("\nobjects:")] + "\nobjects: []\n"
DUPLICATE_CUP = edited("cup:\n", "cup:\n  radius: 0.02\ncup:\n")


@pytest.mark.parametrize(
    "text,words",
    [
        (DUPLICATE_CUP, ["line", "duplicate key 'cup'"]),
        (NO_OBJECTS, ["objects", "at least one object"]),
    ],
    ids=["duplicate key", "no objects"],
)
def test_a_scenario_that_would_be_read_wrongly_is_refused(
    capsys, tmp_path, text, words
):
    (tmp_path / "s.yaml").write_text(text)
    refused(capsys, ["run", "s.yaml", "--out", "out"], "s.yaml", *words)
    assert not (tmp_path / "out").exists()


# -- hang or out of memory ------------------------------------------------------


@pytest.mark.parametrize(
    "flags,words",
    [
        (["--points", "12"], ["12 points", "GB", "largest accepted: 10 points"]),
        (["--sides", "64"], ["64 sides", "GB", "12 sides at 6 points"]),
        (["--points", "40"], ["40 points", "GB"]),
        (["--points", "10", "--max-memory", "1"], ["limit 1 GB", "9 points"]),
    ],
)
def test_an_exact_set_too_large_is_refused_with_the_estimate(capsys, flags, words):
    refused(capsys, ["constraint", *flags, "--out", "o.npz"], "estimated", *words)


@pytest.mark.parametrize(
    "flags,words",
    [
        (["--approximate", "100000000"], ["--approximate", "100000000"]),
        (["--approximate", "20", "--samples", "1000000000"], ["--samples"]),
    ],
)
def test_an_approximation_too_large_is_refused(capsys, flags, words):
    refused(capsys, ["constraint", *flags, "--out", "o.npz"], *words)


def test_a_yaml_alias_bomb_is_refused_before_it_expands(capsys, tmp_path):
    bomb = "".join(
        f"{c}: &{c} [{', '.join([f'*{p}'] * 9) if p else 'lol'}]\n"
        for p, c in zip(["", *"abcdefgh"], "abcdefghi", strict=True)
    )
    (tmp_path / "s.yaml").write_text(bomb + BASE)
    refused(capsys, ["plan", "s.yaml", "--object", "notebook"], "s.yaml", "alias")


def test_a_waypoint_far_beyond_any_joint_range_is_refused(capsys, tmp_path):
    (tmp_path / "w.csv").write_text("0,0.35,1.75,0,1.04,0\n1e6,0.35,1.75,0,1.04,0\n")
    argv = [*RETIME, "--waypoints", "w.csv", "--out", "o.npz"]
    refused(capsys, argv, "waypoint 1", "1e+06")


def test_too_many_gridpoints_are_refused(capsys, tmp_path):
    (tmp_path / "w.csv").write_text(SWING)
    argv = [*RETIME, "--waypoints", "w.csv", "--gridpoints", "1000000000"]
    refused(capsys, [*argv, "--out", "o.npz"], "--gridpoints", "1000000000")


# -- data loss -------------------------------------------------------------------


@pytest.mark.parametrize(
    "argv,victim",
    [
        (["plan", "v.yaml", "--object", "notebook", "--out", "v.yaml"], "v.yaml"),
        (["plan", "v.csv", "--object", "notebook", "--out", "v.csv"], "v.csv"),
        (["constraint", "--scenario", "v.npz", "--out", "v.npz"], "v.npz"),
        (["show", "v.html", "--html", "v.html"], "v.html"),
        (["run", "d/report.json", "--out", "d"], "d/report.json"),
        (
            ["experiment", "transport", "--scenario", "d/report.md", "--out", "d"],
            "d/report.md",
        ),
    ],
)
def test_an_output_never_writes_over_an_input(capsys, tmp_path, argv, victim):
    path = tmp_path / victim
    path.parent.mkdir(exist_ok=True)
    path.write_text(BASE)
    before = path.read_bytes()
    flag = "--html" if "--html" in argv else "--out"
    refused(capsys, argv, flag, "input of this command")
    assert path.read_bytes() == before
    assert files_in(tmp_path) <= {victim, "d"}  # nothing written, no temporary


def test_retime_never_writes_over_its_waypoints(capsys, tmp_path):
    (tmp_path / "w.npz").write_text(SWING)  # a CSV named .npz
    argv = [*RETIME, "--waypoints", "w.npz", "--out", "w.npz"]
    refused(capsys, argv, "--out", "waypoint file", "input")
    assert (tmp_path / "w.npz").read_text() == SWING


def test_an_output_onto_a_directory_leaves_no_temporary_file(capsys, tmp_path):
    (tmp_path / "d.npz").mkdir()
    refused(capsys, ["constraint", "--out", "d.npz"], "--out", "d.npz", "directory")
    assert files_in(tmp_path) == {"d.npz"}


def test_run_checks_its_output_before_simulating(capsys, tmp_path):
    (tmp_path / "o").write_text("keep")
    refused(
        capsys, ["run", "random_transport", "--out", "o"], "--out", "not a directory"
    )
    assert (tmp_path / "o").read_text() == "keep"


# -- tracebacks ------------------------------------------------------------------


@pytest.mark.parametrize(
    "argv,flag",
    [
        (["constraint", "--out", "{target}.npz"], "--out"),
        ([*RETIME, "--waypoints", "w.csv", "--out", "{target}.npz"], "--out"),
        (
            [
                "plan",
                "random_transport",
                "--object",
                "notebook",
                "--out",
                "{target}.csv",
            ],
            "--out",
        ),
        (["show", "random_transport", "--html", "{target}.html"], "--html"),
        (["run", "random_transport", "--out", "{target}"], "--out"),
        (["experiment", "transport", "--n", "1", "--out", "{target}"], "--out"),
    ],
)
@pytest.mark.parametrize("where", ["directory", "under a file"])
def test_an_output_path_that_cannot_be_written_is_refused(
    capsys, tmp_path, argv, flag, where
):
    (tmp_path / "w.csv").write_text(SWING)
    (tmp_path / "f").write_text("a file")
    if where == "directory":
        target = "d"
        for suffix in ("", ".npz", ".csv", ".html"):
            (tmp_path / f"d{suffix}").mkdir(exist_ok=True)
        if argv[0] in ("run", "experiment"):  # a directory is wanted: a file
            target, words = "f", ["not a directory"]
        else:
            words = ["directory"]
    else:
        target, words = "f/sub", ["'f' is not a directory"]
    before = files_in(tmp_path)
    refused(capsys, [a.replace("{target}", target) for a in argv], flag, *words)
    assert files_in(tmp_path) == before
    assert (tmp_path / "f").read_text() == "a file"


@pytest.mark.parametrize(
    "content,words",
    [
        ("hello, I am not XML\n", ["obj.sdf", "not an SDF or URDF"]),
        ("<robot name='x'><link name='other'/></robot>", ["no link named 'body'"]),
    ],
)
def test_an_object_model_that_is_not_an_object_sdf_is_refused(
    capsys, tmp_path, content, words
):
    (tmp_path / "obj.sdf").write_text(content)
    (tmp_path / "s.yaml").write_text(edited(MODEL, str(tmp_path / "obj.sdf")))
    refused(
        capsys, ["plan", "s.yaml", "--object", "notebook"], "objects[0].model", *words
    )


def test_a_null_object_entry_is_refused(capsys, tmp_path):
    (tmp_path / "s.yaml").write_text(edited("objects:\n", "objects:\n- null\n"))
    refused(capsys, ["run", "s.yaml"], "objects[0]", "null")


# -- poor messages -----------------------------------------------------------------


@pytest.mark.parametrize(
    "old,new,words",
    [
        ("home: [0.0,", "home: [.nan,", ["robot.home[0]", "nan"]),
        (
            "goal: {translation: [0.35,",
            "goal: {translation: [.nan,",
            ["objects[0].goal", "nan"],
        ),
        (
            "start: {translation: [0.42,",
            "start: {translation: [.inf,",
            ["objects[0].start", "inf"],
        ),
        ("points: 6", "points: six", ["cup.points", "'six'", "integer"]),
        ("points: 6", "points: 6.5", ["cup.points", "6.5", "integer"]),
        ("- name: notebook", "- name: 5", ["objects[0].name", "string"]),
        (
            "home: [0.0, 0.35, 1.75, 0.0, 1.04, 0.0]",
            "home: [0.0, 0.35]",
            # the scenario's jerk_limits have 6: the two keys are named
            ["robot.home", "robot.jerk_limits", "2 values"],
        ),
        (
            "home: [0.0, 0.35, 1.75, 0.0, 1.04, 0.0]",
            "home: [0, 0, 0, 0, 0, 0]\n  velocity_limits: [1, 2]",
            ["robot.velocity_limits", "2 values"],
        ),
        (
            "home: [0.0, 0.35, 1.75, 0.0, 1.04, 0.0]",
            "home: [0, 0, 0, 0, 0, 0]\n  torque_limits: [0, 1, 1, 1, 1, 1]",
            ["robot.torque_limits", "> 0"],
        ),
    ],
)
def test_a_bad_scenario_value_names_file_key_and_value(
    capsys, tmp_path, old, new, words
):
    (tmp_path / "s.yaml").write_text(edited(old, new))
    (tmp_path / "w.csv").write_text(SWING)
    argv = ["retime", "s.yaml", "--waypoints", "w.csv", "--object", "notebook"]
    refused(capsys, [*argv, "--out", "o.npz"], "s.yaml", *words)


def test_drakes_info_line_does_not_precede_the_error(tmp_path):
    # In a real process (pytest captures Python logging, where Drake logs): the
    # start is out of reach, refused after the collision checker is built.
    far = edited("start: {translation: [0.42,", "start: {translation: [3.0,")
    (tmp_path / "s.yaml").write_text(far)
    done = subprocess.run(
        [
            sys.executable,
            "-m",
            "rt_drake.cli",
            "plan",
            "s.yaml",
            "--object",
            "notebook",
        ],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        check=False,
    )
    assert done.returncode == 2
    assert done.stderr.splitlines() == [done.stderr.strip()], done.stderr
    assert done.stderr.startswith("rt-drake plan: error: APPROACH notebook:")
