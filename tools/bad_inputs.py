# ruff: noqa: E501 (the cases are one per line; the API snippets are long)
"""A campaign of bad inputs through the ``rt-drake`` CLI and the Python API.

    python tools/bad_inputs.py [--only TEXT] [--timeout 60] [--memory-gb 4]
                                    [--json FILE] [--list]

Each case runs in its own process (``python -m rt_drake.cli ...`` or a short
API snippet) in a fresh temporary directory, with a wall-clock timeout and an
address-space limit (``resource.setrlimit(RLIMIT_AS)`` in the child), so a
blow-up cannot hurt the machine. Every case is a bad input: the expected
answer is a refusal, exit code 2 and ONE stderr line ``rt-drake <command>:
error: ...`` for the CLI, an ``RtDrakeError`` for the API, whose message
names the key, flag or file and the value (``expect``: every token, case
insensitive; ``a|b`` accepts either). Each case gets one verdict:

- ``hang or OOM``: timed out, killed, or ran out of memory;
- ``data loss``: an input file changed, or a temporary file was left behind;
- ``traceback``: a Python traceback, an exit code other than 0 and 2, or an
  API error that is not an ``RtDrakeError`` (``SystemExit`` included);
- ``silent wrong``: exit 0, or the API returned a value;
- ``poor message``: refused, but not in one line, or without the tokens
  (for the API, Drake's own log lines, e.g. ``INFO:drake:...``, are not
  counted: logging is the calling program's to configure);
- ``good``: refused in one line naming the problem.

A few controls (good inputs, ``control=True``) must succeed; they guard the
campaign against refusing everything and are reported apart.
"""

from __future__ import annotations

import argparse
import collections
import dataclasses
import hashlib
import json
import os
import re
import resource
import subprocess
import sys
import tempfile
import textwrap
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
VERDICTS = (
    "good",
    "poor message",
    "traceback",
    "silent wrong",
    "hang or OOM",
    "data loss",
)


@dataclasses.dataclass(frozen=True)
class Case:
    """One bad input.

    Attributes:
        name: Unique id (``area.what``).
        argv: CLI arguments after ``rt-drake``; ``{d}`` is the case directory.
        api: Python snippet (run with ``{d}`` substituted); it must raise.
        files: Files to create in the case directory: name -> text (``{d}``
            substituted) or bytes.
        expect: Tokens the error message must contain (``a|b``: either).
        inputs: Files (in the directory) that must be byte-identical after.
        absent: Files that must not exist after the run.
        control: A good input: must succeed (exit 0, no exception).
    """

    name: str
    argv: tuple[str, ...] = ()
    api: str = ""
    files: dict[str, str | bytes] = dataclasses.field(default_factory=dict)
    expect: tuple[str, ...] = ()
    inputs: tuple[str, ...] = ()
    absent: tuple[str, ...] = ()
    control: bool = False


# -- inputs -----------------------------------------------------------------

_BASE = (ROOT / "scenarios" / "random_transport.yaml").read_text()
_SDF = (ROOT / "models" / "objects" / "notebook.sdf").read_text()
_SWING = "# joint1..joint6 (rad)\n0,0.35,1.75,0,1.04,0\n-0.4,0.45,1.55,0,1.14,-0.5\n"
_SWING += "-1.2,0.25,1.95,0,0.94,-0.8\n"


def _edit(text: str, *pairs: tuple[str, str]) -> str:
    for old, new in pairs:
        if old not in text:
            raise SystemExit(f"campaign out of date: {old!r} not in the base file")
        text = text.replace(old, new, 1)
    return text


def scenario(*pairs: tuple[str, str]) -> str:
    """The shipped random_transport scenario with text replacements."""
    return _edit(_BASE, *pairs)


def sdf(*pairs: tuple[str, str]) -> str:
    """The notebook's SDF with text replacements."""
    return _edit(_SDF, *pairs)


_MODEL = ("package://rt_drake/objects/notebook.sdf", "{d}/obj.sdf")
_HOME = "home: [0.0, 0.35, 1.75, 0.0, 1.04, 0.0]"
_CUP = "cup:\n  radius: 0.0125\n  points: 6\n"
_GOAL = "goal: {translation: [0.35, 0.40, 0.043]"
_START = "start: {translation: [0.42, -0.345, -0.0055]"
_OBJECTS_ON = "objects:\n- name: notebook"
_DUP_CUP = _CUP.replace("radius: 0.0125", "radius: 0.02")
_NO_RT = ("random_transport:\n  object: notebook", "unused_tail:\n  object: notebook")
_ALIAS_BOMB = "".join(
    f"{c}: &{c} [{', '.join([f'*{p}'] * 9) if p else ', '.join(['lol'] * 9)}]\n"
    for p, c in zip(["", *"abcdefgh"], "abcdefghi", strict=True)
)


def _object_sdf_case(name: str, pairs, expect) -> Case:
    return Case(
        f"retime.object_sdf.{name}",
        (
            "retime",
            "s.yaml",
            "--waypoints",
            "w.csv",
            "--object",
            "notebook",
            "--out",
            "o.npz",
        ),
        files={"s.yaml": scenario(_MODEL), "obj.sdf": sdf(*pairs), "w.csv": _SWING},
        expect=expect,
    )


def _scenario_case(name: str, text: str, expect, command: str = "plan") -> Case:
    argv = {
        "plan": ("plan", "s.yaml", "--object", "notebook", "--phase", "approach"),
        "retime": (
            "retime",
            "s.yaml",
            "--waypoints",
            "w.csv",
            "--object",
            "notebook",
            "--out",
            "o.npz",
        ),
        "run": ("run", "s.yaml", "--out", "out"),
        "constraint": ("constraint", "--scenario", "s.yaml", "--out", "o.npz"),
    }[command]
    return Case(
        f"{command}.scenario.{name}",
        argv,
        files={"s.yaml": text, "w.csv": _SWING},
        expect=expect,
        inputs=("s.yaml",),
    )


def cli_cases() -> list[Case]:
    """Bad inputs through ``rt-drake``."""
    cases: list[Case] = []
    con = ("constraint", "--no-cache")
    # -- constraint: cup parameters (silent wrong, hang or OOM, messages)
    for flag, value, expect in [
        ("--radius", "1e-300", ("radius", "1e-300")),
        ("--radius", "1e300", ("radius", "1e300|1e+300")),
        ("--radius", "0", ("radius", "0")),
        ("--radius", "-0.01", ("radius", "-0.01")),
        ("--radius", "nan", ("radius", "nan")),
        ("--radius", "inf", ("radius", "inf")),
        ("--radius", "abc", ("radius", "abc")),
        ("--points", "2", ("points", "2")),
        ("--points", "1.5", ("points", "1.5")),
        ("--points", "12", ("points", "12", "GB")),
        ("--points", "40", ("points", "40")),
        ("--points", "100000", ("points", "100000")),
        ("--sides", "2", ("sides", "2")),
        ("--sides", "64", ("sides", "64")),
        ("--sides", "1000000", ("sides", "1000000")),
        ("--friction", "-0.1", ("friction", "-0.1")),
        ("--friction", "nan", ("friction", "nan")),
        ("--friction", "1e300", ("friction", "1e300|1e+300")),
        ("--suction-force", "0", ("suction", "0")),
        ("--suction-force", "1e300", ("suction", "1e300|1e+300")),
        ("--suction-force", "1e-300", ("suction", "1e-300")),
        ("--max-normal-force", "-5", ("normal", "-5")),
        ("--max-normal-force", "1e300", ("normal", "1e300|1e+300")),
        ("--max-normal-force", "1e-300", ("normal", "1e-300")),
    ]:
        cases.append(
            Case(
                f"constraint.{flag[2:]}={value}",
                (*con, flag, value, "--out", "o.npz"),
                expect=expect,
                absent=("o.npz",),
            )
        )
    for flag, value, expect in [
        ("--approximate", "3", ("approximate", "3")),
        ("--approximate", "-1", ("approximate", "-1")),
        ("--approximate", "100000000", ("approximate", "100000000")),
        ("--samples", "0", ("samples", "0")),
        ("--samples", "-5", ("samples", "-5")),
        ("--samples", "1000000000", ("samples", "1000000000")),
        ("--guide-mass", "-1", ("guide-mass|mass", "-1")),
        ("--guide-mass", "nan", ("guide-mass|mass", "nan")),
        ("--guide-acceleration", "-5", ("acceleration", "-5")),
        ("--seed", "-1", ("seed", "-1")),
    ]:
        extra = () if flag == "--approximate" else ("--approximate", "20")
        cases.append(
            Case(
                f"constraint.{flag[2:]}={value}",
                ("constraint", *extra, flag, value, "--out", "o.npz"),
                expect=expect,
                absent=("o.npz",),
            )
        )
    cases += [
        Case(
            "constraint.max-memory=0",
            ("constraint", "--max-memory", "0", "--out", "o.npz"),
            expect=("max-memory", "0"),
        ),
        # -- constraint: output paths (tracebacks, data loss, temporary files)
        Case(
            "constraint.out_is_directory",
            ("constraint", "--out", "d.npz"),
            files={"d.npz/keep": ""},
            expect=("--out", "d.npz", "directory"),
            inputs=("d.npz/keep",),
        ),
        Case(
            "constraint.out_under_a_file",
            ("constraint", "--out", "f/o.npz"),
            files={"f": "not a directory\n"},
            expect=("--out", "f", "not a directory"),
            inputs=("f",),
        ),
        Case(
            "constraint.out_suffix",
            ("constraint", "--out", "o.txt"),
            expect=("--out", "o.txt", ".npz"),
            absent=("o.txt",),
        ),
        Case(
            "constraint.out_is_the_scenario",
            ("constraint", "--scenario", "s.npz", "--out", "s.npz"),
            files={"s.npz": _BASE},
            expect=("--out", "s.npz", "input"),
            inputs=("s.npz",),
        ),
        Case(
            "constraint.scenario_missing",
            ("constraint", "--scenario", "nope.yaml", "--out", "o.npz"),
            expect=("nope.yaml",),
        ),
    ]
    # -- plan: flags and output paths
    plan = ("plan", "random_transport", "--object", "notebook", "--phase", "approach")
    for flag, value, expect in [
        ("--budget", "0", ("budget", "0")),
        ("--budget", "-5", ("budget", "-5")),
        ("--budget", "nan", ("budget", "nan")),
        ("--budget", "inf", ("budget", "inf")),
        ("--budget", "1e9", ("budget", "1e9|1e+09|1000000000")),
        ("--seed", "abc", ("seed", "abc")),
        ("--seed", "-1", ("seed", "-1")),
    ]:
        cases.append(
            Case(f"plan.{flag[2:]}={value}", (*plan, flag, value), expect=expect)
        )
    cases += [
        Case(
            "plan.object_unknown",
            ("plan", "random_transport", "--object", "nope"),
            expect=("nope",),
        ),
        Case(
            "plan.out_is_the_scenario",
            ("plan", "victim.yaml", "--object", "notebook", "--out", "victim.yaml"),
            files={"victim.yaml": _BASE},
            expect=("--out", "victim.yaml", "input"),
            inputs=("victim.yaml",),
        ),
        Case(
            "plan.out_is_directory",
            (*plan, "--out", "d"),
            files={"d/keep": ""},
            expect=("--out", "directory"),
        ),
        Case(
            "plan.out_under_a_file",
            (*plan, "--out", "f/w.csv"),
            files={"f": "x\n"},
            expect=("--out", "f", "not a directory"),
            inputs=("f",),
        ),
        Case(
            "plan.out_suffix",
            (*plan, "--out", "w.npz"),
            expect=("--out", "w.npz", ".csv"),
            absent=("w.npz",),
        ),
        Case(
            "plan.scenario_is_directory", ("plan", ".", "--object", "n"), expect=(".",)
        ),
    ]
    # -- retime: flags, waypoint files and output paths
    ret = ("retime", "random_transport", "--object", "notebook")
    for name, content, expect in [
        (
            "waypoint_1e6",
            "0,0.35,1.75,0,1.04,0\n1e6,0.35,1.75,0,1.04,0\n",
            ("1e6|1e+06|1000000",),
        ),
        ("waypoint_1e300", "0,0.35,1.75,0,1.04,0\n1e300,0,0,0,0,0\n", ("waypoint",)),
        ("waypoint_nan", "0,0.35,1.75,0,1.04,0\nnan,0,0,0,0,0\n", ("waypoint", "nan")),
        ("waypoint_text", "0,0.35,1.75,0,1.04,0\na,b,c,d,e,f\n", ("w.csv",)),
        (
            "waypoints_equal",
            "0,0.35,1.75,0,1.04,0\n0,0.35,1.75,0,1.04,0\n",
            ("w.csv", "equal"),
        ),
        ("waypoints_empty", "", ("w.csv",)),
        ("waypoints_ragged", "0,0,0,0,0,0\n1,1,1\n", ("w.csv",)),
        ("waypoints_binary", b"\x00\xff\xfe\x00garbage", ("w.csv",)),
    ]:
        cases.append(
            Case(
                f"retime.{name}",
                (*ret, "--waypoints", "w.csv", "--out", "o.npz"),
                files={"w.csv": content},
                expect=expect,
                inputs=("w.csv",),
                absent=("o.npz",),
            )
        )
    for flag, value, expect in [
        ("--gridpoints", "1", ("gridpoints", "1")),
        ("--gridpoints", "-5", ("gridpoints", "-5")),
        ("--gridpoints", "abc", ("gridpoints", "abc")),
        ("--gridpoints", "1000000000", ("gridpoints", "1000000000")),
    ]:
        cases.append(
            Case(
                f"retime.{flag[2:]}={value}",
                (*ret, "--waypoints", "w.csv", flag, value, "--out", "o.npz"),
                files={"w.csv": _SWING},
                expect=expect,
            )
        )
    cases += [
        Case(
            "retime.out_suffix_csv",
            (*ret, "--waypoints", "w.csv", "--out", "x.csv"),
            files={"w.csv": _SWING},
            expect=("--out", "x.csv", ".npz"),
            absent=("x.csv", "x.csv.npz"),
        ),
        Case(
            "retime.out_is_the_waypoints",
            (*ret, "--waypoints", "w.npz", "--out", "w.npz"),
            files={"w.npz": _SWING},
            expect=("--out", "w.npz", "input"),
            inputs=("w.npz",),
        ),
        Case(
            "retime.out_is_directory",
            (*ret, "--waypoints", "w.csv", "--out", "d.npz"),
            files={"w.csv": _SWING, "d.npz/keep": ""},
            expect=("--out", "d.npz", "directory"),
        ),
        Case(
            "retime.out_under_a_file",
            (*ret, "--waypoints", "w.csv", "--out", "f/o.npz"),
            files={"w.csv": _SWING, "f": "x\n"},
            expect=("--out", "f", "not a directory"),
            inputs=("f",),
        ),
        Case(
            "retime.waypoints_is_directory",
            (*ret, "--waypoints", "d", "--out", "o.npz"),
            files={"d/keep": ""},
            expect=("d",),
        ),
    ]
    # -- retime: object models (silent wrong mass, tracebacks)
    mass = ("<mass>0.551</mass>",)
    inertia = "<ixx>0.000928</ixx><iyy>0.00211</iyy><izz>0.00298</izz>"
    cases += [
        _object_sdf_case("mass_0", [(mass[0], "<mass>0</mass>")], ("mass", "0")),
        _object_sdf_case("mass_-1", [(mass[0], "<mass>-1</mass>")], ("mass", "-1")),
        _object_sdf_case("mass_nan", [(mass[0], "<mass>nan</mass>")], ("mass", "nan")),
        _object_sdf_case(
            "inertia_negative",
            [(inertia, "<ixx>-1</ixx><iyy>-1</iyy><izz>-1</izz>")],
            ("inertia",),
        ),
        _object_sdf_case(
            "inertia_triangle",
            [(inertia, "<ixx>0.001</ixx><iyy>0.001</iyy><izz>0.01</izz>")],
            ("inertia", "triangle"),
        ),
        _object_sdf_case(
            "inertia_nan",
            [(inertia, "<ixx>nan</ixx><iyy>0.00211</iyy><izz>0.00298</izz>")],
            ("inertia|ixx", "nan"),
        ),
        _object_sdf_case("no_inertial", [(mass[0], "")], ("mass",)),
        _object_sdf_case(
            "no_body", [('<link name="body">', '<link name="box">')], ("body",)
        ),
        Case(
            "retime.object_model_not_sdf",
            (
                "retime",
                "s.yaml",
                "--waypoints",
                "w.csv",
                "--object",
                "notebook",
                "--out",
                "o.npz",
            ),
            files={
                "s.yaml": scenario(_MODEL),
                "obj.sdf": "hello, I am not XML\n",
                "w.csv": _SWING,
            },
            expect=("obj.sdf",),
        ),
        Case(
            "retime.object_model_yaml",
            (
                "retime",
                "s.yaml",
                "--waypoints",
                "w.csv",
                "--object",
                "notebook",
                "--out",
                "o.npz",
            ),
            files={
                "s.yaml": scenario(
                    ("package://rt_drake/objects/notebook.sdf", "{d}/s.yaml")
                ),
                "w.csv": _SWING,
            },
            expect=("s.yaml", "model"),
        ),
    ]
    # -- scenarios (through plan unless noted)
    cases += [
        _scenario_case(
            "objects_empty",
            _BASE[: _BASE.index("\nobjects:")] + "\nobjects: []\n",
            ("objects",),
            "run",
        ),
        _scenario_case(
            "objects_null_entry",
            scenario((_OBJECTS_ON, "objects:\n- null\n- name: notebook")),
            ("objects[0]",),
        ),
        _scenario_case(
            "objects_null_entry_run",
            scenario((_OBJECTS_ON, "objects:\n-\n- name: notebook")),
            ("objects[0]",),
            "run",
        ),
        _scenario_case(
            "duplicate_key", scenario((_CUP, _CUP + _DUP_CUP)), ("cup", "duplicate")
        ),
        _scenario_case(
            "duplicate_nested_key",
            scenario((_HOME, _HOME + "\n  " + _HOME)),
            ("home", "duplicate"),
        ),
        _scenario_case("alias_bomb", _ALIAS_BOMB + _BASE, ("alias",)),
        _scenario_case(
            "alias_small",
            scenario(
                ("attach_s: 1.0", "attach_s: &x 1.0"), ("detach_s: 1.0", "detach_s: *x")
            ),
            ("alias",),
        ),
        _scenario_case(
            "deep_nesting",
            "deep: " + "[" * 100000 + "]" * 100000 + "\n" + _BASE,
            ("s.yaml",),
        ),
        _scenario_case("not_utf8", b"\xff\xfe\x00\x00" + _BASE.encode(), ("s.yaml",)),
        _scenario_case("empty_file", "", ("s.yaml",)),
        _scenario_case(
            "home_nan",
            scenario((_HOME, "home: [.nan, 0.35, 1.75, 0.0, 1.04, 0.0]")),
            ("robot.home", "nan"),
        ),
        _scenario_case(
            "home_text",
            scenario((_HOME, "home: [zero, 0.35, 1.75, 0.0, 1.04, 0.0]")),
            ("robot.home", "zero"),
        ),
        _scenario_case(
            "home_short",
            scenario((_HOME, "home: [0.0, 0.35]")),
            ("s.yaml", "robot.home"),
        ),
        _scenario_case("home_scalar", scenario((_HOME, "home: 5")), ("robot.home",)),
        _scenario_case(
            "goal_nan",
            scenario((_GOAL, "goal: {translation: [.nan, 0.40, 0.043]")),
            ("objects[0].goal", "nan"),
        ),
        _scenario_case(
            "start_nan",
            scenario((_START, "start: {translation: [.nan, -0.345, -0.0055]")),
            ("objects[0].start", "nan"),
        ),
        _scenario_case(
            "start_inf",
            scenario((_START, "start: {translation: [.inf, -0.345, -0.0055]")),
            ("objects[0].start", "inf"),
        ),
        _scenario_case(
            "rotation_nan",
            scenario(("deg: [0, 0, 90]", "deg: [0, .nan, 90]")),
            ("objects[0].start", "nan"),
        ),
        _scenario_case(
            "grasp_nan",
            scenario(
                (
                    "grasp: {translation: [0, 0, 0.0125]",
                    "grasp: {translation: [0, 0, .nan]",
                )
            ),
            ("objects[0].grasp", "nan"),
        ),
        _scenario_case(
            "points_text", scenario(("points: 6", "points: six")), ("cup.points", "six")
        ),
        _scenario_case(
            "points_float",
            scenario(("points: 6", "points: 6.5")),
            ("cup.points", "6.5"),
        ),
        _scenario_case(
            "radius_text",
            scenario(("radius: 0.0125", "radius: big")),
            ("cup.radius", "big"),
        ),
        _scenario_case(
            "radius_tiny",
            scenario(("radius: 0.0125", "radius: 1e-300")),
            ("cup", "radius", "1e-300"),
        ),
        _scenario_case(
            "friction_nan",
            scenario(("friction: 0.3", "friction: .nan")),
            ("cup", "friction", "nan"),
        ),
        _scenario_case(
            "friction_zero",
            scenario(("friction: 0.3", "friction: 0.0")),
            ("cup.friction", "0.0"),
        ),
        _scenario_case(
            "attach_text",
            scenario(("attach_s: 1.0", "attach_s: soon")),
            ("vacuum.attach_s", "soon"),
        ),
        _scenario_case(
            "attach_nan",
            scenario(("attach_s: 1.0", "attach_s: .nan")),
            ("vacuum.attach_s", "nan"),
        ),
        _scenario_case(
            "approach_offset_list",
            scenario(("approach_offset: 0.20", "approach_offset: [1]")),
            ("approach_offset",),
        ),
        _scenario_case(
            "approach_offset_nan",
            scenario(("approach_offset: 0.20", "approach_offset: .nan")),
            ("approach_offset", "nan"),
        ),
        _scenario_case(
            "name_number",
            scenario(("- name: notebook", "- name: 5")),
            ("objects[0].name",),
        ),
        _scenario_case(
            "velocity_limits_short",
            scenario((_HOME, _HOME + "\n  velocity_limits: [1.0, 2.0]")),
            ("s.yaml", "velocity_limits"),
            "retime",
        ),
        _scenario_case(
            "velocity_limits_nan",
            scenario((_HOME, _HOME + "\n  velocity_limits: [.nan, 1, 1, 1, 1, 1]")),
            ("s.yaml", "velocity_limits", "nan"),
            "retime",
        ),
        _scenario_case(
            "velocity_limits_negative",
            scenario((_HOME, _HOME + "\n  velocity_limits: [-1, 1, 1, 1, 1, 1]")),
            ("s.yaml", "velocity_limits", "-1"),
            "retime",
        ),
        _scenario_case(
            "acceleration_limits_short",
            scenario((_HOME, _HOME + "\n  acceleration_limits: [1.0]")),
            ("s.yaml", "acceleration_limits"),
            "retime",
        ),
        _scenario_case(
            "torque_limits_zero",
            scenario((_HOME, _HOME + "\n  torque_limits: [0, 0, 0, 0, 0, 0]")),
            ("s.yaml", "torque_limits", "0"),
        ),
        _scenario_case(
            "region_nan",
            scenario(
                ("lower: [0.38, -0.365, -0.0055]", "lower: [.nan, -0.365, -0.0055]")
            ),
            ("random_transport.start_region", "nan"),
        ),
        _scenario_case(
            "model_instance_number",
            scenario(("model_instance: vs060", "model_instance: [1]")),
            ("robot.model_instance",),
        ),
        _scenario_case("top_level_list", "- 1\n- 2\n", ("s.yaml",)),
    ]
    # -- run: flags and output paths, before any simulation
    cases += [
        Case(
            "run.out_is_a_file",
            ("run", "random_transport", "--out", "o"),
            files={"o": "keep me\n"},
            expect=("--out", "o", "not a directory|is a file"),
            inputs=("o",),
        ),
        Case(
            "run.out_under_a_file",
            ("run", "random_transport", "--out", "f/run"),
            files={"f": "x\n"},
            expect=("--out", "f", "not a directory"),
            inputs=("f",),
        ),
        Case(
            "run.out_holds_the_scenario",
            ("run", "out/report.json", "--out", "out"),
            files={"out/report.json": _BASE},
            expect=("--out", "report.json", "input"),
            inputs=("out/report.json",),
        ),
        Case(
            "run.speed=0",
            ("run", "random_transport", "--speed", "0"),
            expect=("speed", "0"),
        ),
        Case(
            "run.speed=nan",
            ("run", "random_transport", "--speed", "nan"),
            expect=("speed", "nan"),
        ),
        Case(
            "run.time-step=1",
            ("run", "random_transport", "--time-step", "1"),
            expect=("time-step", "1"),
        ),
        Case(
            "run.seed=abc",
            ("run", "random_transport", "--seed", "abc"),
            expect=("seed", "abc"),
        ),
    ]
    # -- show: output paths
    cases += [
        Case(
            "show.html_is_directory",
            ("show", "random_transport", "--html", "d"),
            files={"d/keep": ""},
            expect=("--html", "directory"),
        ),
        Case(
            "show.html_under_a_file",
            ("show", "random_transport", "--html", "f/x.html"),
            files={"f": "x\n"},
            expect=("--html", "f", "not a directory"),
            inputs=("f",),
        ),
        Case(
            "show.html_is_the_scenario",
            ("show", "s.html", "--html", "s.html"),
            files={"s.html": _BASE},
            expect=("--html", "s.html", "input"),
            inputs=("s.html",),
        ),
        Case(
            "show.html_suffix",
            ("show", "random_transport", "--html", "x.yaml"),
            expect=("--html", "x.yaml", ".html"),
            absent=("x.yaml",),
        ),
    ]
    # -- experiment: flags and output paths, before any trial
    tr = ("experiment", "transport")
    cases += [
        Case(
            "experiment.transport.n=0",
            (*tr, "--n", "0", "--out", "o"),
            expect=("--n", "0"),
        ),
        Case(
            "experiment.transport.workers=0",
            (*tr, "--workers", "0", "--out", "o"),
            expect=("--workers", "0"),
        ),
        Case(
            "experiment.transport.out_is_a_file",
            (*tr, "--n", "1", "--out", "o"),
            files={"o": "keep\n"},
            expect=("--out", "o"),
            inputs=("o",),
        ),
        Case(
            "experiment.transport.object_unknown",
            (*tr, "--object", "nope", "--out", "o"),
            expect=("nope",),
        ),
        Case(
            "experiment.transport.no_section",
            (*tr, "--scenario", "stack_four_objects", "--out", "o"),
            expect=("random_transport",),
        ),
        Case(
            "experiment.cycle.out_is_a_file",
            ("experiment", "cycle", "--out", "o"),
            files={"o": "keep\n"},
            expect=("--out", "o"),
            inputs=("o",),
        ),
        Case("usage.unknown_command", ("fly",), expect=("fly",)),
        Case(
            "usage.missing_flag",
            ("retime", "random_transport"),
            expect=("--waypoints|required",),
        ),
    ]
    # -- export: a trajectory file for a controller
    exp = ("export", "t.npz", "--joint-names", "a,b,c,d,e,f")
    good = {"t.npz": _trajectory_npz()}
    for name, flags, files, expect in [
        ("period=0", ("--period", "0", "--out", "o.mcap"), good, ("--period", "0")),
        ("period=nan", ("--period", "nan", "--out", "o.mcap"), good, ("--period", "nan")),
        ("period_longer", ("--period", "9", "--out", "o.mcap"), good, ("9", "longer")),
        ("period_0.1ns", ("--period", "1e-10", "--out", "o.csv"), good, ("nanosecond",)),
        ("format_bag", ("--period", "0.008", "--out", "o.bag"), good, ("bag", "mcap")),
        ("out_is_input", ("--period", "0.008", "--out", "t.npz", "--format", "csv"),
         good, ("--out", "t.npz")),
        ("sd_nan", ("--period", "0.008", "--out", "o.csv"),
         {"t.npz": _trajectory_npz(sd=[0.0, float("nan"), 0.0])}, ("t.npz", "sd", "nan")),
        ("not_npz", ("--period", "0.008", "--out", "o.csv"), {"t.npz": "q\n1\n"},
         ("t.npz", "npz")),
    ]:  # fmt: skip
        cases.append(
            Case(f"export.{name}", (*exp, *flags), files=files, expect=expect,
                 inputs=("t.npz",), absent=("o.mcap", "o.csv", "o.bag"))
        )  # fmt: skip
    cases.append(
        Case(
            "export.names_count",
            (
                "export",
                "t.npz",
                "--period",
                "0.008",
                "--joint-names",
                "a,b",
                "--out",
                "o.mcap",
            ),
            files=good,
            expect=("2 joint names", "6 joints"),
            absent=("o.mcap",),
        )  # fmt: skip
    )
    # -- controls: good inputs must still work
    cases += [
        Case(
            "control.export",
            (*exp, "--period", "0.008", "--out", "o.mcap"),
            files=good,
            control=True,
        ),
        Case("control.constraint", ("constraint", "--out", "o.npz"), control=True),
        Case(
            "control.retime",
            (
                "retime",
                "random_transport",
                "--waypoints",
                "w.csv",
                "--object",
                "notebook",
                "--out",
                "o.npz",
            ),
            files={"w.csv": _SWING},
            control=True,
        ),
        Case("control.plan", (*plan, "--out", "w.csv"), control=True),
    ]
    return cases


def _trajectory_npz(sd: list[float] | None = None) -> bytes:
    """A small trajectory file: 0.5 rad on every joint, s' = 0, 1, 0 on 3 points."""
    import io

    import numpy as np

    home = np.array([0.0, 0.35, 1.75, 0.0, 1.04, 0.0])
    arrays = {
        "t": np.zeros(1), "q": np.zeros((1, 6)), "qd": np.zeros((1, 6)),
        "qdd": np.zeros((1, 6)), "duration": 2.0, "X_WC": np.zeros((1, 4, 4)),
        "object_name": "box", "object_mass": 1.0, "p_CoScm_C": np.zeros(3),
        "I_Scm_C": np.eye(3), "F": np.zeros((0, 6)), "g": np.zeros(0),
        "cup_names": np.array(["radius"]), "cup_values": np.array([0.0125]),
        "waypoints": np.array([home, home + 0.5]), "knots": np.array([0.0, 1.0]),
        "gridpoints": np.array([0.0, 0.5, 1.0]),
        "sd": np.array([0.0, 1.0, 0.0] if sd is None else sd),
    }  # fmt: skip
    stream = io.BytesIO()
    np.savez(stream, format_version=1, **arrays)
    return stream.getvalue()


_API_PRELUDE = """
import numpy as np
"""


def api_cases() -> list[Case]:
    """Bad inputs through the Python API; each snippet must raise."""
    polytope = (
        "from rt_drake.contact import CupParameters, cached_wrench_polytope\n"
        "W = cached_wrench_polytope(CupParameters())\n"
    )
    held = "from rt_drake import HeldObject\n"
    plant = (
        "from rt_drake import load_scenario, make_arm_plant, JointLimits, retime\n"
        "from rt_drake.model.resources import scenarios_dir\n"
        "sc = load_scenario(scenarios_dir() / 'random_transport.yaml')\n"
        "plant = make_arm_plant(sc)\n"
        "limits = JointLimits.from_plant(plant, sc.robot)\n"
        "W0 = np.array([[0, 0.35, 1.75, 0, 1.04, 0], [-0.4, 0.45, 1.55, 0, 1.14, -0.5],"
        " [-1.2, 0.25, 1.95, 0, 0.94, -0.8]])\n"
    )
    planner = (
        "from rt_drake import CyclePlanner, load_scenario\n"
        "from rt_drake.model.resources import scenarios_dir\n"
        "sc = load_scenario(scenarios_dir() / 'random_transport.yaml')\n"
        "planner = CyclePlanner(sc, seed=0)\n"
    )
    grasp = (
        held
        + "from rt_drake import GraspConstraint\n"
        + "h = HeldObject(mass=1.0, p_CoScm_C=np.zeros(3), I_Scm_C=np.eye(3) * 1e-3)\n"
    )
    a = [
        (
            "is_realizable.nan_wrench",
            polytope
            + "from rt_drake import is_realizable\nresult = is_realizable(np.full(6, np.nan), W.F, W.g)",
            ("wrench", "nan|finite"),
        ),
        (
            "is_realizable.nan_F",
            polytope
            + "from rt_drake import is_realizable\nF = W.F.copy(); F[0, 0] = np.nan\nresult = is_realizable(np.zeros(6), F, W.g)",
            ("F", "nan|finite"),
        ),
        (
            "is_realizable.zero_row",
            polytope
            + "from rt_drake import is_realizable\nF = W.F.copy(); F[0] = 0\nresult = is_realizable(np.zeros(6), F, W.g)",
            ("row", "zero"),
        ),
        (
            "is_realizable.tol_nan",
            polytope
            + "from rt_drake import is_realizable\nresult = is_realizable(np.zeros(6), W.F, W.g, tol=np.nan)",
            ("tol", "nan"),
        ),
        (
            "load_polytope.missing",
            "from rt_drake.contact import CupParameters, load_polytope\nresult = load_polytope('{d}/nope.npz', CupParameters())",
            ("nope.npz",),
        ),
        (
            "load_polytope.other_cup",
            polytope
            + "from rt_drake.contact import load_polytope, save_polytope\nsave_polytope('{d}/w.npz', W)\nresult = load_polytope('{d}/w.npz', CupParameters(points=5))",
            ("w.npz", "points"),
        ),
        (
            "load_polytope.not_npz",
            "from rt_drake.contact import CupParameters, load_polytope\nopen('{d}/w.npz', 'w').write('x')\nresult = load_polytope('{d}/w.npz', CupParameters())",
            ("w.npz",),
        ),
        (
            "cup.radius_tiny",
            "from rt_drake.contact import CupParameters\nresult = CupParameters(radius=1e-300)",
            ("radius", "1e-300"),
        ),
        (
            "cup.radius_huge",
            "from rt_drake.contact import CupParameters\nresult = CupParameters(radius=1e300)",
            ("radius", "1e+300"),
        ),
        (
            "cup.suction_huge",
            "from rt_drake.contact import CupParameters\nresult = CupParameters(suction_force=1e300)",
            ("suction", "1e+300"),
        ),
        (
            "cup.points_12",
            "from rt_drake.contact import CupParameters, contact_wrench_polytope\nresult = contact_wrench_polytope(CupParameters(points=12))",
            ("points", "12", "GB"),
        ),
        (
            "cup.sides_64",
            "from rt_drake.contact import CupParameters, contact_wrench_polytope\nresult = contact_wrench_polytope(CupParameters(sides=64))",
            ("sides", "64", "GB"),
        ),
        (
            "cup.points_float",
            "from rt_drake.contact import CupParameters\nresult = CupParameters(points=6.0)",
            ("points", "6.0"),
        ),
        (
            "held.mass_nan",
            held
            + "result = HeldObject(mass=np.nan, p_CoScm_C=np.zeros(3), I_Scm_C=np.eye(3))",
            ("mass", "nan"),
        ),
        (
            "held.mass_zero",
            held
            + "result = HeldObject(mass=0.0, p_CoScm_C=np.zeros(3), I_Scm_C=np.eye(3))",
            ("mass", "0"),
        ),
        (
            "held.inertia_negative_definite",
            held
            + "result = HeldObject(mass=1.0, p_CoScm_C=np.zeros(3), I_Scm_C=-np.eye(3))",
            ("I_Scm_C|inertia", "positive"),
        ),
        (
            "held.inertia_triangle",
            held
            + "result = HeldObject(mass=1.0, p_CoScm_C=np.zeros(3), I_Scm_C=np.diag([1e-3, 1e-3, 1e-2]))",
            ("I_Scm_C|inertia", "triangle"),
        ),
        (
            "held.inertia_asymmetric",
            held
            + "I = np.eye(3); I[0, 1] = 0.5\nresult = HeldObject(mass=1.0, p_CoScm_C=np.zeros(3), I_Scm_C=I)",
            ("I_Scm_C|inertia", "symmetric"),
        ),
        (
            "held.p_inf",
            held
            + "result = HeldObject(mass=1.0, p_CoScm_C=[np.inf, 0, 0], I_Scm_C=np.eye(3))",
            ("p_CoScm_C", "inf"),
        ),
        (
            "grasp.zero_row",
            grasp
            + "F = np.vstack([np.eye(6), -np.eye(6), np.zeros((1, 6))])\nresult = GraspConstraint(h, F, np.ones(13))",
            ("row 12", "zero"),
        ),
        (
            "grasp.nan_F",
            grasp
            + "F = np.vstack([np.eye(6), -np.eye(6)]); F[0, 0] = np.nan\nresult = GraspConstraint(h, F, np.ones(12))",
            ("F", "finite|nan"),
        ),
        (
            "retime.sd_start_nan",
            plant + "result = retime(plant, W0, limits, sd_start=np.nan)",
            ("sd_start", "nan"),
        ),
        (
            "retime.sd_start_negative",
            plant + "result = retime(plant, W0, limits, sd_start=-1.0)",
            ("sd_start", "-1"),
        ),
        (
            "retime.sd_end_inf",
            plant + "result = retime(plant, W0, limits, sd_end=np.inf)",
            ("sd_end", "inf"),
        ),
        (
            "retime.start_time_nan",
            plant + "result = retime(plant, W0, limits, start_time=np.nan)",
            ("start_time", "nan"),
        ),
        (
            "retime.waypoint_1e6",
            plant + "W0[1, 0] = 1e6\nresult = retime(plant, W0, limits)",
            ("waypoint", "1e+06|1000000"),
        ),
        (
            "retime.gridpoints_huge",
            plant + "result = retime(plant, W0, limits, gridpoints=10**9)",
            ("gridpoints", "1000000000"),
        ),
        (
            "retime.gridpoints_float",
            plant + "result = retime(plant, W0, limits, gridpoints=2.5)",
            ("gridpoints", "2.5"),
        ),
        (
            "retime.wrong_joints",
            plant + "result = retime(plant, W0[:, :5], limits)",
            ("joints",),
        ),
        (
            "retime.jerk_start_file_name",
            plant + "result = retime(plant, W0, limits, jerk_start='profile.npz')",
            ("jerk_start", "str"),
        ),
        (
            "retime.path_jumps",
            plant
            + "from pydrake.trajectories import CompositeTrajectory, PiecewisePolynomial\n"
            "a = PiecewisePolynomial.CubicShapePreserving([0.0, 0.5], W0[:2].T, True)\n"
            "b = PiecewisePolynomial.CubicShapePreserving([0.5, 1.0], W0[1:].T + 0.3, True)\n"
            "result = retime(plant, CompositeTrajectory([a, b]), limits)",
            ("continuous|jumps", "s = 0.5"),
        ),
        (
            "limits.wrong_length",
            "from rt_drake import JointLimits\nresult = JointLimits(np.ones(6), np.ones(5))",
            ("length|differ", "5"),
        ),
        (
            "limits.nan",
            "from rt_drake import JointLimits\nresult = JointLimits(np.full(6, np.nan), np.ones(6))",
            ("velocity", "nan"),
        ),
        (
            "planner.approach_nan_q",
            planner
            + "q = planner.q_home.copy(); q[0] = np.nan\nresult = planner.plan_approach(q, 'notebook')",
            ("q", "nan"),
        ),
        (
            "planner.approach_short_q",
            planner + "result = planner.plan_approach(np.zeros(3), 'notebook')",
            ("q", "3", "6"),
        ),
        (
            "planner.reach_nan_q",
            planner
            + "q = planner.q_home.copy(); q[2] = np.nan\nresult = planner.plan_reach(q, 'notebook')",
            ("q", "nan"),
        ),
        (
            "planner.move_nan_q",
            planner
            + "q = planner.q_home.copy(); q[2] = np.nan\nresult = planner.plan_move(q, 'notebook')",
            ("q", "nan"),
        ),
        (
            "planner.between_inf_goal",
            planner
            + "q = planner.q_home.copy(); g = q.copy(); g[1] = np.inf\nresult = planner.plan_between(q, g, 'notebook')",
            ("q", "inf"),
        ),
        (
            "planner.budget_nan",
            "from rt_drake import CyclePlanner, load_scenario\nfrom rt_drake.model.resources import scenarios_dir\nsc = load_scenario(scenarios_dir() / 'random_transport.yaml')\nresult = CyclePlanner(sc, budget_s=np.nan)",
            ("budget", "nan"),
        ),
        (
            "planner.budget_zero",
            "from rt_drake import CyclePlanner, load_scenario\nfrom rt_drake.model.resources import scenarios_dir\nsc = load_scenario(scenarios_dir() / 'random_transport.yaml')\nresult = CyclePlanner(sc, budget_s=0)",
            ("budget", "0"),
        ),
        (
            "scenario.duplicate_key",
            "from rt_drake import load_scenario\nopen('{d}/s.yaml', 'w').write("
            + repr(scenario((_CUP, _CUP + _DUP_CUP)))
            + ")\nresult = load_scenario('{d}/s.yaml')",
            ("cup", "duplicate"),
        ),
        (
            "scenario.alias_bomb",
            "from rt_drake import load_scenario\nopen('{d}/s.yaml', 'w').write("
            + repr(_ALIAS_BOMB + _BASE)
            + ")\nresult = load_scenario('{d}/s.yaml')",
            ("alias",),
        ),
        (
            "held.from_scenario_mass_0",
            "from rt_drake import held_object_of, load_scenario\nopen('{d}/obj.sdf', 'w').write("
            + repr(sdf(("<mass>0.551</mass>", "<mass>0</mass>")))
            + ")\nopen('{d}/s.yaml', 'w').write("
            + repr(scenario(_MODEL))
            + ")\nresult = held_object_of(load_scenario('{d}/s.yaml').object('notebook'))",
            ("mass", "0"),
        ),
        (
            "is_realizable.list_F_wrong_shape",
            polytope
            + "from rt_drake import is_realizable\nresult = is_realizable([0.0] * 6, W.F.tolist()[0], W.g.tolist())",
            ("F", "(rows, 6)", "list"),
        ),
        (
            "contact_wrench_polytope.none",
            "from rt_drake import contact_wrench_polytope\nresult = contact_wrench_polytope(None)",
            ("cup", "None"),
        ),
        (
            "grasp.no_rows",
            grasp + "result = GraspConstraint(h, np.zeros((0, 6)), np.zeros(0))",
            ("F", "(0, 6)"),
        ),
        (
            "grasp.frictionless_cup",
            grasp
            + "from rt_drake import CupParameters\nresult = GraspConstraint.for_cup(h, CupParameters(points=4, friction=0.0))",
            ("friction", "0.0"),
        ),
        (
            "trajectory.save_onto_directory",
            "import os\nfrom rt_drake import save_trajectory\nos.mkdir('{d}/t.npz')\nresult = save_trajectory('{d}/t.npz', None)",
            ("t.npz",),
        ),
    ]
    return [Case(f"api.{name}", api=code, expect=expect) for name, code, expect in a]


# -- running ----------------------------------------------------------------

_API_WRAPPER = textwrap.dedent(
    """
    import sys, traceback
    from rt_drake.errors import RtDrakeError
    namespace = {}
    try:
        exec(compile(sys.argv[1], "<case>", "exec"), namespace)
    except RtDrakeError as error:
        names = [c.__name__ for c in type(error).__mro__]
        print(f"{'/'.join(names[:3])}: {error}", file=sys.stderr)
        sys.exit(2)
    except BaseException:
        traceback.print_exc()
        sys.exit(3)
    print("returned", repr(namespace.get("result"))[:200])
    """
)


#: A line of Drake's logging through Python's default format.
_DRAKE_LOG = re.compile(r"^(DEBUG|INFO|WARNING):drake:")


def _limit(memory_bytes: int):
    def apply() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (memory_bytes, memory_bytes))
        os.setsid()

    return apply


def _digest(path: Path) -> str | None:
    return hashlib.sha256(path.read_bytes()).hexdigest() if path.is_file() else None


def run_case(case: Case, base: Path, timeout: float, memory: int) -> dict:
    """Run one case in a fresh directory; return its record with a verdict."""
    directory = Path(
        tempfile.mkdtemp(prefix=case.name.replace("/", "_") + ".", dir=base)
    )
    for name, content in case.files.items():
        target = directory / name
        target.parent.mkdir(parents=True, exist_ok=True)
        if isinstance(content, bytes):
            target.write_bytes(content)
        else:
            target.write_text(content.replace("{d}", str(directory)))
    before = {name: _digest(directory / name) for name in case.inputs}
    existing = {p for p in directory.rglob("*")}
    env = dict(os.environ, PYTHONPATH=str(ROOT), OPENBLAS_NUM_THREADS="1")
    env["RT_DRAKE_CACHE_DIR"] = str(base / "cache")
    if case.argv:
        command = [sys.executable, "-m", "rt_drake.cli", *case.argv]
    else:
        code = _API_PRELUDE + case.api.replace("{d}", str(directory))
        command = [sys.executable, "-c", _API_WRAPPER, code]
    start = time.perf_counter()
    try:
        done = subprocess.run(
            command,
            cwd=directory,
            env=env,
            capture_output=True,
            text=True,
            errors="replace",
            timeout=timeout,
            preexec_fn=_limit(memory),
        )
        code, out, err = done.returncode, done.stdout, done.stderr
    except subprocess.TimeoutExpired as expired:
        code, out, err = None, str(expired.stdout or ""), str(expired.stderr or "")
    seconds = time.perf_counter() - start
    lines = [line for line in err.splitlines() if line.strip()]
    if not case.argv:  # the API: Drake's own log lines are the user's to configure
        lines = [line for line in lines if not _DRAKE_LOG.match(line)]
    changed = [n for n, d in before.items() if _digest(directory / n) != d]
    left = sorted(
        str(p.relative_to(directory))
        for p in set(directory.rglob("*")) - existing
        if ".tmp" in p.name or p.name.startswith("tmp")
    )
    present = [n for n in case.absent if (directory / n).exists()]
    message = lines[-1] if lines else ""
    missing = [
        token
        for token in case.expect
        if not any(t.lower() in message.lower() for t in token.split("|"))
    ]
    oom = any(
        marker in err for marker in ("MemoryError", "bad_alloc", "Cannot allocate")
    )
    if code is None or oom or (code is not None and code < 0):
        verdict = "hang or OOM"
    elif changed or left:
        verdict = "data loss"
    elif case.control:
        verdict = "good" if code == 0 else "control failed"
    elif "Traceback" in err or code not in (0, 2):
        verdict = "traceback"
    elif code == 0 or present:
        verdict = "silent wrong"
    elif (
        len(lines) != 1 or missing or (case.argv and not message.startswith("rt-drake"))
    ):
        verdict = "poor message"
    else:
        verdict = "good"
    return {
        "name": case.name,
        "verdict": verdict,
        "exit": code,
        "seconds": round(seconds, 1),
        "message": message[:400],
        "stderr_lines": len(lines),
        "missing": missing,
        "changed": changed,
        "left": left,
        "present": present,
        "stdout_tail": out.strip().splitlines()[-1:] if out.strip() else [],
    }


def main() -> int:
    """Run the campaign and print the tally."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", default="", help="run cases whose name has TEXT")
    parser.add_argument("--timeout", type=float, default=60.0, help="s per case")
    parser.add_argument("--memory-gb", type=float, default=4.0, help="per case")
    parser.add_argument("--json", type=Path, help="write every record here")
    parser.add_argument("--list", action="store_true", help="list the cases")
    args = parser.parse_args()
    cases = [c for c in cli_cases() + api_cases() if args.only in c.name]
    if len({c.name for c in cases}) != len(cases):
        raise SystemExit("duplicate case names")
    if args.list:
        print("\n".join(c.name for c in cases))
        return 0
    records = []
    with tempfile.TemporaryDirectory(prefix="rt_drake_bad_inputs.") as base:
        for case in cases:
            record = run_case(
                case, Path(base), args.timeout, int(args.memory_gb * 2**30)
            )
            records.append(record)
            print(
                f"{record['verdict']:14} {record['seconds']:6.1f} s  {case.name}: "
                f"{record['message'][:160]}",
                flush=True,
            )
    tally = collections.Counter(
        r["verdict"] for r in records if not r["name"].startswith("control.")
    )
    controls = [r for r in records if r["name"].startswith("control.")]
    print()
    print("| verdict | count |\n|---|---:|")
    for verdict in VERDICTS:
        print(f"| {verdict} | {tally.get(verdict, 0)} |")
    print(f"| **total** | {sum(tally.values())} |")
    print("controls: " + ", ".join(f"{r['name']} {r['verdict']}" for r in controls))
    if args.json:
        args.json.write_text(json.dumps(records, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
