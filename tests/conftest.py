"""Shared fixtures: the shipped scenarios and plants built from them.

Property tests draw the same examples on every run (hypothesis profile
``deterministic``, the default), so CI never turns red at random; run
``python -m pytest --hypothesis-profile=explore`` to search new examples.

The suite runs on pytest-xdist workers (``-n auto --dist loadfile`` in
pyproject.toml): a worker runs a whole test module, so it builds the
module's fixtures once; :func:`pytest_collection_modifyitems` puts the
modules with a slow test first, so that the short ones fill the end.
``python -m pytest -n 0`` runs the same tests in one process.
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
    "stack_four_objects_paper",
    "stack_four_objects_vacuum_sensor",
    "random_transport",
)


@pytest.fixture(scope="session")
def scenario_paths() -> dict[str, Path]:
    """Paths of the shipped scenario files, by name."""
    return {name: scenarios_dir() / f"{name}.yaml" for name in SCENARIO_NAMES}


@pytest.fixture(scope="session")
def scenario() -> Scenario:
    """Table II's four-object stack, the paper's fixed approach heights.

    Tests do not change it.
    """
    return load_scenario(scenarios_dir() / "stack_four_objects_paper.yaml")


@pytest.fixture(scope="session")
def plant(scenario: Scenario) -> MultibodyPlant:
    """The arm-and-tool plant of ``scenario`` (the retimer's plant), finalized."""
    return make_arm_plant(scenario)


def pytest_configure(config: pytest.Config) -> None:
    """Compile the numba kernels once, before pytest-xdist starts its workers.

    numba caches machine code beside each module at its first compile. In a
    fresh clone (as in CI) every process started before that cache exists
    compiles every kernel again (about 10 s of CPU each): both workers, and
    the campaign drivers, pool and Ray workers the slow modules start
    first. Compiled here, in the controller (or the only process, with
    ``-n 0``), each of them loads the cache instead. An xdist worker skips
    this (``workerinput``).
    """
    if hasattr(config, "workerinput"):
        return
    from rt_drake.shaping import warm_up  # the retimer's kernels too

    warm_up()


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """The modules with a slow test first, in collection order; then the rest.

    The order within a module is kept, and a module's tests stay together
    (its module fixtures are built once, also without xdist). With
    ``--dist loadfile --no-loadscope-reorder`` xdist hands the modules out
    in this order: the longest start first, as in longest-job-first.
    """
    modules: dict[str, list[pytest.Item]] = {}
    for item in items:
        modules.setdefault(item.nodeid.split("::", 1)[0], []).append(item)

    def slow_first(module: str) -> bool:
        return not any(item.get_closest_marker("slow") for item in modules[module])

    items[:] = [
        item for module in sorted(modules, key=slow_first) for item in modules[module]
    ]
