"""The scenario's ``planning`` key (issue 13) and ``random_transport.start_on_cup``."""

from __future__ import annotations

import pytest

from rt_drake.errors import ScenarioError
from rt_drake.model.resources import scenarios_dir
from rt_drake.model.scenario import (
    PlanningConfig,
    load_scenario,
)
from rt_drake.shaping import MoveOptimizerOptions


def test_planning_defaults_when_the_key_is_absent(scenario_paths):
    planning = load_scenario(scenario_paths["stack_four_objects_paper"]).planning
    assert planning == PlanningConfig()
    assert planning.max_tilt_deg == 45.0 and planning.budget_s == 0.15
    options = MoveOptimizerOptions.from_config(planning)
    assert options.max_tilt_deg == 45.0 and options.budget_s == 0.15


def test_paper_regions_load_and_start_on_the_cup():
    scenario = load_scenario(scenarios_dir() / "random_transport_paper.yaml")
    transport = scenario.random_transport
    assert transport is not None and transport.start_on_cup
    assert transport.start_region.yaw_deg == [-81, 81]


def _with_planning(tmp_path, scenario_paths, text: str):
    path = tmp_path / "planned.yaml"
    base = scenario_paths["random_transport"].read_text()
    path.write_text(base + "\nplanning:\n" + text)
    return path


def test_planning_values_are_read(tmp_path, scenario_paths):
    path = _with_planning(
        tmp_path,
        scenario_paths,
        "  optimize_move: true\n  max_tilt_deg: 0\n  budget_s: 0.5\n",
    )
    planning = load_scenario(path).planning
    assert planning == PlanningConfig(True, 0.0, 0.5)


@pytest.mark.parametrize(
    "text,words",
    [
        ("  max_tilt_deg: 90\n", ["planning.max_tilt_deg", "[0, 90)", "90"]),
        ("  max_tilt_deg: -5\n", ["planning.max_tilt_deg", "-5"]),
        ("  budget_s: 0\n", ["planning.budget_s", "> 0"]),
        ("  optimise_move: true\n", ["planning.optimise_move", "unknown key"]),
    ],
)
def test_bad_planning_values_give_one_line_naming_the_key(
    tmp_path, scenario_paths, text, words
):
    path = _with_planning(tmp_path, scenario_paths, text)
    with pytest.raises(ScenarioError) as info:
        load_scenario(path)
    message = str(info.value)
    assert "\n" not in message
    for word in words:
        assert word in message, (word, message)
