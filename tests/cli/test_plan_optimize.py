"""``rt-drake plan --optimize``: the optimised MOVE, same ends as the spline MOVE."""

from __future__ import annotations

import argparse

import numpy as np
import pytest

from rt_drake.cli import _plan as plan


def run(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="rt-drake")
    plan.register(parser.add_subparsers(dest="command", required=True))
    args = parser.parse_args(["plan", *argv])
    return args.run(args)


@pytest.mark.slow
def test_optimised_move_keeps_the_ends_and_is_reported(tmp_path, capsys):
    spline, optimised = tmp_path / "spline.csv", tmp_path / "optimised.csv"
    argv = ["random_transport", "--object", "notebook", "--out"]
    assert run([*argv, str(spline)]) == 0
    assert "MOVE optimised" not in capsys.readouterr().out
    assert run([*argv, str(optimised), "--optimize"]) == 0
    printed = capsys.readouterr().out
    assert "MOVE optimised:" in printed or "MOVE kept" in printed
    a, b = (np.loadtxt(f, delimiter=",") for f in (spline, optimised))
    np.testing.assert_array_equal(a[[0, -1]], b[[0, -1]])


@pytest.mark.slow
def test_a_two_cup_tool_is_optimised_under_its_spring_split(tmp_path, capsys):
    """The MOVE of carton_two_cups is shaped under the tool's set, not refused."""
    out = tmp_path / "move.csv"
    argv = ["carton_two_cups", "--object", "heavy_carton", "--optimize"]
    assert run([*argv, "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "MOVE optimised:" in printed or "MOVE kept" in printed
    assert np.loadtxt(out, delimiter=",").shape[1] == 6
