"""``ring_tool``: the cups ``planning.grasp_margin: ring`` rings, or a refusal."""

from __future__ import annotations

import numpy as np
import pytest

from rt_drake.errors import ScenarioError
from rt_drake.model.resources import scenarios_dir
from rt_drake.model.scenario import load_scenario
from rt_drake.simulation.move_grasp import ring_tool


def _with_ring(tmp_path, name: str, margin: str):
    text = (scenarios_dir() / f"{name}.yaml").read_text()
    assert f"grasp_margin: {margin}" in text
    path = tmp_path / f"{name}.yaml"
    path.write_text(text.replace(f"grasp_margin: {margin}", "grasp_margin: ring"))
    return load_scenario(path)


def test_the_two_cup_tool_is_stiffer_in_torsion_by_the_lateral_springs(tmp_path):
    scenario = _with_ring(tmp_path, "carton_two_cups_bellows_20n", "0.417")
    tool = ring_tool(scenario)
    assert tool is not None and len(tool.X_TCs) == 2
    cup = tool.cup  # closed form: 2 k_tor + 2 k_lat d^2 about z, d = 0.06 m
    expected = 2 * cup.torsion_stiffness + 2 * cup.lateral_stiffness * 0.06**2
    assert tool.stiffness[2, 2] == pytest.approx(expected, rel=1e-12)
    np.testing.assert_allclose(tool.stiffness, tool.stiffness.T)


def test_a_number_needs_no_tool(tmp_path):
    text = (scenarios_dir() / "random_transport_bellows.yaml").read_text()
    path = tmp_path / "fixed.yaml"
    path.write_text(text)
    assert ring_tool(load_scenario(path)) is None


def test_an_uncertainty_set_is_refused_in_one_line(tmp_path):
    scenario = _with_ring(tmp_path, "random_transport_uncertain_bellows", "0.18")
    assert ring_tool(scenario, robust=False) is not None  # the nominal object
    with pytest.raises(ScenarioError) as info:
        ring_tool(scenario, robust=True)
    message = str(info.value)
    assert "key 'planning.grasp_margin'" in message and "uncertainty set" in message
    assert "\n" not in message
