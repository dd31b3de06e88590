"""The scenario's ``planning`` key (issues 13, 27); ``start_on_cup``."""

from __future__ import annotations

import pytest

from rt_drake.errors import ScenarioError
from rt_drake.model.resources import scenarios_dir
from rt_drake.model.scenario import (
    MOVE_EVALUATIONS,
    PlanningConfig,
    load_scenario,
)
from rt_drake.shaping import MoveOptimizerOptions


def test_planning_defaults_when_the_key_is_absent(scenario_paths):
    """A scenario without ``planning`` shapes its MOVEs, on the evaluation budget."""
    planning = load_scenario(scenario_paths["random_transport"]).planning
    assert planning == PlanningConfig()
    assert planning.optimize_move
    assert planning.max_tilt_deg == 45.0
    assert planning.max_evaluations == MOVE_EVALUATIONS
    options = MoveOptimizerOptions.from_config(planning)
    assert options.max_tilt_deg == 45.0
    assert options.max_evaluations == MOVE_EVALUATIONS


@pytest.mark.parametrize(
    "name", ["stack_four_objects", "stack_four_objects_vacuum_sensor"]
)
def test_shipped_cycles_shape_their_moves(name):
    scenario = load_scenario(scenarios_dir() / f"{name}.yaml")
    assert scenario.planning.optimize_move


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
        "  optimize_move: false\n  max_tilt_deg: 0\n  max_evaluations: 40\n",
    )
    planning = load_scenario(path).planning
    assert planning == PlanningConfig(False, 0.0, 40)


@pytest.mark.parametrize(
    "text,words",
    [
        ("  max_tilt_deg: 90\n", ["planning.max_tilt_deg", "[0, 90)", "90"]),
        ("  max_tilt_deg: -5\n", ["planning.max_tilt_deg", "-5"]),
        ("  max_evaluations: 0\n", ["planning.max_evaluations", ">= 1"]),
        ("  budget_s: 0.15\n", ["planning.budget_s", "planning.max_evaluations"]),
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
