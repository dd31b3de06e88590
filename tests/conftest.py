"""Shared fixtures: the shipped scenarios and plants built from them.

Property tests draw the same examples on every run (hypothesis profile
``deterministic``, the default), so CI never turns red at random; run
``python -m pytest --hypothesis-profile=explore`` to search new examples.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import settings
from pydrake.multibody.plant import MultibodyPlant

from rt_drake.model.plant import make_arm_plant
from rt_drake.model.resources import scenarios_dir
from rt_drake.model.scenario import (
    Scenario,
    load_scenario,
)

settings.register_profile("deterministic", derandomize=True)
settings.register_profile("explore", derandomize=False)
settings.load_profile("deterministic")

SCENARIO_NAMES = (
    "stack_four_objects",
    "stack_four_objects_vacuum_sensor",
    "random_transport",
)


@pytest.fixture(scope="session")
def scenario_paths() -> dict[str, Path]:
    """Paths of the shipped scenario files, by name."""
    return {name: scenarios_dir() / f"{name}.yaml" for name in SCENARIO_NAMES}


@pytest.fixture(scope="module")
def scenario() -> Scenario:
    """The four-object stacking scenario (Table II)."""
    return load_scenario(scenarios_dir() / "stack_four_objects.yaml")


@pytest.fixture(scope="module")
def plant(scenario: Scenario) -> MultibodyPlant:
    """The arm-and-tool plant of ``scenario`` (the retimer's plant)."""
    return make_arm_plant(scenario)
