"""Shared fixtures: the shipped scenarios and plants built from them."""

from __future__ import annotations

from pathlib import Path

import pytest

from rt_drake.resources import scenarios_dir

SCENARIO_NAMES = ("stack_four_objects", "random_transport")


@pytest.fixture(scope="session")
def scenario_paths() -> dict[str, Path]:
    """Paths of the shipped scenario files, by name."""
    return {name: scenarios_dir() / f"{name}.yaml" for name in SCENARIO_NAMES}
