"""The sequencer runs pick, attach, move, detach and measures what happened."""

from __future__ import annotations

import numpy as np
import pytest
from motion_helpers import IkMotions

from rt_drake.model.scenario import load_scenario
from rt_drake.simulation import run_cycle
from rt_drake.types.phase import Phase

#: Whole-cycle simulations: tens of seconds (still run by CI).
pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def one_object_cycle(scenario_paths):
    scenario = load_scenario(scenario_paths["random_transport"])
    return scenario, run_cycle(scenario, IkMotions(scenario), max_sim_time=20.0)


def test_every_phase_lasts_as_planned(one_object_cycle):
    scenario, result = one_object_cycle
    (record,) = result.records
    exec_s = record.exec_s
    assert list(exec_s) == [p for p in Phase if p is not Phase.DONE]
    assert exec_s[Phase.APPROACH] == pytest.approx(1.0, abs=0.01)
    assert exec_s[Phase.REACH] == pytest.approx(0.6, abs=0.01)
    assert exec_s[Phase.ATTACH] == pytest.approx(scenario.vacuum.attach_s, abs=0.01)
    assert exec_s[Phase.MOVE] == pytest.approx(2.2, abs=0.01)
    assert exec_s[Phase.DETACH] == pytest.approx(scenario.vacuum.detach_s, abs=0.01)
    assert result.sim_time == pytest.approx(sum(exec_s.values()), abs=0.02)


def test_object_is_carried_to_its_goal_without_slipping(one_object_cycle):
    _, result = one_object_cycle
    (record,) = result.records
    assert record.max_slip_translation < 2e-3
    assert np.degrees(record.max_slip_rotation) < 2.0
    assert record.placement_translation < 0.01
    assert np.degrees(record.placement_rotation) < 5.0


def test_under_the_rim_cup_the_slip_is_the_motion_on_the_tool(one_object_cycle):
    """The rim cup's lip is the tool: the two measures are one."""
    _, result = one_object_cycle
    (record,) = result.records
    assert record.max_slip_translation > 0.0
    assert record.max_on_tool_translation == record.max_slip_translation
    assert record.max_on_tool_rotation == record.max_slip_rotation
