"""Where the shipped models and scenarios are, installed or in a checkout.

In a wheel, ``models/`` and ``scenarios/`` are installed as the package data
``rt_drake/models`` and ``rt_drake/scenarios``; in a source checkout they sit
beside the ``rt_drake`` directory.
"""

from __future__ import annotations

from pathlib import Path

from rt_drake.errors import ScenarioError

#: The ``rt_drake`` package directory (this module is in ``rt_drake/model``).
_PACKAGE_DIR = Path(__file__).resolve().parents[1]


def _data_dir(name: str) -> Path:
    for candidate in (_PACKAGE_DIR / name, _PACKAGE_DIR.parent / name):
        if candidate.is_dir():
            return candidate
    raise FileNotFoundError(f"rt_drake data directory '{name}' is not installed")


def models_dir() -> Path:
    """Return the directory holding ``package.xml`` of ``package://rt_drake``."""
    return _data_dir("models")


def scenarios_dir() -> Path:
    """Return the directory of the shipped scenario files."""
    return _data_dir("scenarios")


def resolve_scenario_path(name: str | Path) -> Path:
    """Return ``name`` as a path, or as a shipped scenario if no such file.

    ``stack_four_objects.yaml`` (or ``stack_four_objects``) finds the shipped
    file when the working directory has none of that name.
    """
    path = Path(name)
    if path.is_file():
        return path
    for candidate in (
        scenarios_dir() / path.name,
        scenarios_dir() / f"{path.name}.yaml",
    ):
        if candidate.is_file():
            return candidate
    raise ScenarioError(f"scenario file '{name}' does not exist")
