"""``rt-drake plan``: the MOVE shaped by default, the spline with --no-optimize."""

from __future__ import annotations

import argparse
import re

import numpy as np
import pytest

from rt_drake.cli import _plan as plan
from rt_drake.model.resources import resolve_scenario_path
from rt_drake.model.scenario import load_scenario
from rt_drake.planning import CyclePlanner


def run(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="rt-drake")
    plan.register(parser.add_subparsers(dest="command", required=True))
    args = parser.parse_args(["plan", *argv])
    return args.run(args)


def planner_move(scenario_name: str, name: str, seed: int) -> np.ndarray:
    """The spline MOVE's waypoints from the planner itself (the objects before
    ``name`` placed, as ``plan`` does)."""
    scenario = load_scenario(resolve_scenario_path(scenario_name))
    planner = CyclePlanner(scenario, seed=seed, budget_s=1.0)
    for obj in scenario.objects:
        if obj.name == name:
            break
        planner.set_object_pose(obj.name, obj.goal.GetDeterministicValue())
    approach = planner.plan_approach(planner.q_home, name)
    reach = planner.plan_reach(approach.q_goal, name)
    return planner.plan_move(reach.q_goal, name, reach=reach).path.waypoints


@pytest.mark.slow
def test_the_move_is_shaped_by_default_and_no_optimize_keeps_the_spline(
    tmp_path, capsys
):
    """Default: shaped, at most 0.85 of the spline; --no-optimize: the planner's path.

    The notebook of the shipped cycle with the paper's fixed approach
    heights, seed 11 (``rt-drake plan stack_four_objects_paper --object
    notebook --phase move --seed 11`` gives 0.702 of the spline MOVE,
    BENCHMARKS.md "Fast by default").
    """
    spline, shaped = tmp_path / "spline.csv", tmp_path / "shaped.csv"
    argv = ["stack_four_objects_paper", "--object", "notebook", "--phase", "move"]
    argv += ["--seed", "11", "--out"]
    assert run([*argv, str(spline), "--no-optimize"]) == 0
    assert "MOVE optimised" not in capsys.readouterr().out
    assert run([*argv, str(shaped)]) == 0
    printed = capsys.readouterr().out
    ratio = float(re.search(r"MOVE optimised: .*\(([0-9.]+)x;", printed).group(1))
    assert ratio <= 0.85, printed
    a, b = (np.loadtxt(f, delimiter=",") for f in (spline, shaped))
    np.testing.assert_array_equal(a[[0, -1]], b[[0, -1]])
    # bit for bit: the CSV holds 17 significant digits, a float64's round trip
    np.testing.assert_array_equal(
        a, planner_move("stack_four_objects_paper", "notebook", 11)
    )


@pytest.mark.slow
def test_a_two_cup_tool_is_optimised_under_its_spring_split(tmp_path, capsys):
    """The MOVE of carton_two_cups is shaped under the tool's set, not refused."""
    out = tmp_path / "move.csv"
    argv = ["carton_two_cups", "--object", "heavy_carton", "--optimize"]
    assert run([*argv, "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "MOVE optimised:" in printed or "MOVE kept" in printed
    assert np.loadtxt(out, delimiter=",").shape[1] == 6
