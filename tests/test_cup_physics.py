"""The scenario's ``cup_physics`` key and the bellows cup catalogue."""

from __future__ import annotations

import math

import pytest

from rt_drake.errors import ScenarioError
from rt_drake.model.cup_physics import CupPhysics, cup_catalogue_path, load_bellows_cup
from rt_drake.model.scenario import load_scenario

SHIPPED_CUP = cup_catalogue_path("vs060_bellows")


def _scenario(tmp_path, scenario_paths, extra: str):
    text = scenario_paths["stack_four_objects"].read_text() + extra
    path = tmp_path / "s.yaml"
    path.write_text(text)
    return path


def test_default_is_the_rim_cup_and_bellows_loads(tmp_path, scenario_paths):
    assert load_scenario(scenario_paths["stack_four_objects"]).cup_physics.physics is (
        CupPhysics.RIM
    )
    path = _scenario(tmp_path, scenario_paths, "\ncup_physics: {kind: bellows}\n")
    assert load_scenario(path).cup_physics.physics is CupPhysics.BELLOWS


def test_shipped_cup_is_the_papers_cup_with_every_value_sourced():
    cup = load_bellows_cup("vs060_bellows")
    assert cup.radius == 0.0125
    # cell-facts: about 30 kPa over the cup, P A about 14.7 N.
    assert cup.suction_force == pytest.approx(14.7, abs=0.05)
    assert cup.effective_area == pytest.approx(math.pi * cup.radius**2, rel=1e-3)
    assert cup.lip_points >= 24
    assert all(source.strip() for source in cup.sources.values())


@pytest.mark.parametrize(
    ("extra", "words"),
    [
        ("cup_physics: {kind: sponge}", ["cup_physics.kind", "sponge", "bellows"]),
        ("cup_physics: {kind: bellows, cup: nope}", ["cup_physics.cup", "nope"]),
        ("cup_physics: {kind: rim, colour: red}", ["cup_physics.colour"]),
    ],
)
def test_bad_cup_physics_is_one_line_naming_key_and_value(
    tmp_path, scenario_paths, extra, words
):
    path = _scenario(tmp_path, scenario_paths, "\n" + extra + "\n")
    with pytest.raises(ScenarioError) as error:
        load_scenario(path)
    message = str(error.value)
    assert "\n" not in message and str(path) in message
    for word in words:
        assert word in message


@pytest.mark.parametrize(
    ("old", "new", "words"),
    [
        ("value: 0.6,", "value: -0.6,", ["friction.value", "-0.6"]),
        ("value: 24,", "value: 12,", ["lip_points.value", "12"]),
        (
            'source: "cell-facts.md: the paper\'s cup, radius 12.5 mm"',
            'source: " "',
            ["radius.source"],
        ),
        ("leak_gap: {value: 0.5e-3", "leak_gap: {value: 0.5", ["leak_gap.value"]),
    ],
)
def test_bad_catalogue_values_are_refused(tmp_path, old, new, words):
    text = SHIPPED_CUP.read_text()
    assert old in text
    path = tmp_path / "cup.yaml"
    path.write_text(text.replace(old, new, 1))
    with pytest.raises(ScenarioError) as error:
        load_bellows_cup(str(path))
    message = str(error.value)
    assert "\n" not in message and str(path) in message
    for word in words:
        assert word in message


def test_command_period_is_checked(tmp_path, scenario_paths):
    text = scenario_paths["stack_four_objects"].read_text()
    text = text.replace("robot:\n", "robot:\n  command_period_s: -0.008\n", 1)
    path = tmp_path / "s.yaml"
    path.write_text(text)
    with pytest.raises(ScenarioError, match=r"robot.command_period_s.*-0.008"):
        load_scenario(path)
