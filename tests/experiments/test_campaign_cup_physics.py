"""A campaign's ``cup_physics`` key: its rows are simulated with that cup."""

from __future__ import annotations

import pytest

from rt_drake.experiments.campaign import CampaignError, load_campaign
from rt_drake.model.cup_physics import CupPhysics

BASE = """scenario: random_transport
objects:
- model: package://rt_drake/objects/notebook.sdf
cups:
- name: paper
trials: 1
"""


def _campaign(tmp_path, extra: str):
    path = tmp_path / "c.yaml"
    path.write_text(BASE + extra)
    return path


def test_cup_physics_reaches_every_row_and_the_hash(tmp_path):
    rim = load_campaign(_campaign(tmp_path, ""))
    bellows = load_campaign(_campaign(tmp_path, "cup_physics: bellows\n"))
    assert rim.scenario.cup_physics.physics is CupPhysics.RIM
    assert bellows.scenario.cup_physics.physics is CupPhysics.BELLOWS
    for cup in bellows.cups:
        assert bellows.cup_scenario(cup).cup_physics.physics is CupPhysics.BELLOWS
    assert rim.content_hash != bellows.content_hash


def test_unknown_cup_physics_is_one_line_naming_the_key(tmp_path):
    path = _campaign(tmp_path, "cup_physics: sponge\n")
    with pytest.raises(CampaignError) as error:
        load_campaign(path)
    message = str(error.value)
    assert "\n" not in message
    assert str(path) in message and "cup_physics" in message and "sponge" in message
