"""``rt-drake plan``: timings printed, waypoints written for the retimer."""

from __future__ import annotations

import argparse

import numpy as np
import pytest
from toppra.interpolator import SplineInterpolator

from rt_drake.cli import _plan as plan
from rt_drake.errors import ScenarioError
from rt_drake.model.scenario import load_scenario
from rt_drake.planning import CyclePlanner
from rt_drake.types.path import chord_knots


def run(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="rt-drake")
    plan.register(parser.add_subparsers(dest="command", required=True))
    args = parser.parse_args(["plan", *argv])
    return args.run(args)


def test_plan_writes_move_waypoints_that_rebuild_the_planned_spline(
    tmp_path, capsys, scenario_paths
):
    out = tmp_path / "move.csv"
    scenario = str(scenario_paths["stack_four_objects"])
    argv = [scenario, "--object", "notebook", "--no-optimize", "--out", str(out)]
    assert run(argv) == 0
    printed = capsys.readouterr().out
    for phase in ("APPROACH", "REACH", "MOVE"):
        assert f"{phase} notebook:" in printed
    assert "ik " in printed and "check " in printed and "total " in printed
    waypoints = np.loadtxt(out, delimiter=",")
    # The same plan through the API (objects before the notebook placed).
    loaded = load_scenario(scenario)
    planner = CyclePlanner(loaded, seed=0)
    for obj in loaded.objects[: [o.name for o in loaded.objects].index("notebook")]:
        planner.set_object_pose(obj.name, obj.goal.GetDeterministicValue())
    a = planner.plan_approach(planner.q_home, "notebook")
    r = planner.plan_reach(a.q_goal, "notebook")
    move = planner.plan_move(r.q_goal, "notebook", reach=r)
    np.testing.assert_array_equal(waypoints, move.path.waypoints)  # %.17g round-trips
    # What the retimer builds from the file is the planned spline.
    toppra_path = SplineInterpolator(
        chord_knots(waypoints), waypoints, bc_type="clamped"
    )
    s = np.linspace(0, 1, 101)
    np.testing.assert_allclose(toppra_path(s), move.path.value(s), atol=1e-12)


def test_plan_one_phase(tmp_path, capsys, scenario_paths):
    out = tmp_path / "approach.csv"
    scenario = str(scenario_paths["random_transport"])
    assert (
        run(
            [scenario, "--object", "notebook", "--phase", "approach", "--out", str(out)]
        )
        == 0
    )
    printed = capsys.readouterr().out
    assert "APPROACH notebook:" in printed and "REACH" not in printed
    assert np.loadtxt(out, delimiter=",").shape[1] == 6


def test_unknown_object_is_a_scenario_error(scenario_paths):
    with pytest.raises(ScenarioError, match="unknown object 'laptop'"):
        run([str(scenario_paths["random_transport"]), "--object", "laptop"])
