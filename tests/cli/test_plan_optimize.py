"""``rt-drake plan --optimize``: the optimised MOVE, same ends as the spline MOVE."""

from __future__ import annotations

import argparse

import numpy as np
import pytest

from rt_drake.cli import plan


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
