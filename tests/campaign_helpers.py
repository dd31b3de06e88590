"""Campaign test helpers: campaign file writers, a local Ray, the crash checks.

The tasks that crash their worker are in :mod:`crash_tasks` (light, for the
worker processes that import them); tests import them from there.
"""

from __future__ import annotations

import io
import os
import sqlite3
import warnings
from pathlib import Path
from typing import Any

from rt_drake.experiments.campaign import Campaign, load_campaign, run_campaign


def write_campaign(
    path: Path,
    trials: int = 2,
    variants: str | None = "[constrained]",
    objects: tuple[str, ...] = ("notebook", "kindle_box"),
) -> Path:
    """Boxes (default two) x two cups (the small cup cannot hold the notebook).

    ``variants`` None leaves the key out (the default variants).
    """
    line = "" if variants is None else f"variants: {variants}\n"
    models = "".join(
        f"- model: package://rt_drake/objects/{name}.sdf\n" for name in objects
    )
    path.write_text(
        f"""\
scenario: random_transport
objects:
{models}cups:
- name: paper
- name: small
  radius: 0.010
  suction_force: 4.0
  max_normal_force: 15.0
trials: {trials}
seed: 0
{line}"""
    )
    return path


def init_local_ray(ray: Any, env: dict[str, str] | None = None) -> None:
    """Start a 2-CPU Ray here; its workers see tests/ (and ``env``).

    Always a new local instance (``address="local"``): never one found
    running on this machine (another test worker's, or a test cluster's
    head, which writes ``/tmp/ray/ray_current_cluster``).
    """
    tests = str(Path(__file__).resolve().parent)
    path = os.pathsep.join(p for p in (tests, os.environ.get("PYTHONPATH")) if p)
    with warnings.catch_warnings():  # Ray's notices of future changes
        warnings.simplefilter("ignore", FutureWarning)
        ray.init(
            address="local",
            num_cpus=2,
            include_dashboard=False,
            log_to_driver=False,
            runtime_env={"env_vars": {"PYTHONPATH": path, **(env or {})}},
        )


def rollout_rows(db: Path, columns: str) -> list[tuple]:
    """The ``columns`` (comma-separated) of every row of ``db``, by trial."""
    with sqlite3.connect(db) as connection:
        return connection.execute(
            f"SELECT {columns} FROM rollouts ORDER BY trial"
        ).fetchall()


#: A cup too weak for the notebook even at rest: its rows are infeasible,
#: found in about a second after the worker's start (no physics).
WEAK_CUP = "radius: 0.010, suction_force: 4.0, max_normal_force: 15.0"


def write_notebook_campaign(
    path: Path, cup: str = "paper", trials: int = 2, cup_options: str = ""
) -> Path:
    """The notebook on one cup called ``cup``, one variant.

    The paper's cup parameters, or ``cup_options`` (e.g. :data:`WEAK_CUP`).
    ``trials`` transports: one row each.
    """
    options = f", {cup_options}" if cup_options else ""
    path.write_text(
        f"""\
scenario: random_transport
objects:
- model: package://rt_drake/objects/notebook.sdf
cups:
- {{name: {cup}{options}}}
trials: {trials}
seed: 0
variants: [constrained]
"""
    )
    return path


def write_tool_campaign(path: Path) -> Path:
    """The kindle box (2.06 N) on a weak cup (1.8 N of suction) and on a tool of two.

    One cup cannot hold the box even at rest (its suction is below the
    box's weight); the tool of two such cups, 8 cm apart on the tool
    frame's x axis (along the box's 17.4 cm length), can. Small cups
    (4 points, 4 sides): the tool's exact set takes seconds to make.
    """
    cup = "points: 4, sides: 4, suction_force: 1.8"
    path.write_text(
        f"""\
scenario: random_transport
objects:
- model: package://rt_drake/objects/kindle_box.sdf
cups:
- {{name: weak, {cup}}}
- name: weak_pair
  tool:
    cups:
    - {{pose: {{translation: [0.04, 0.0, 0.0]}}, {cup}}}
    - {{pose: {{translation: [-0.04, 0.0, 0.0]}}, {cup}}}
trials: 1
seed: 0
variants: [constrained]
"""
    )
    return path


#: The columns of a crash test's rows.
CRASH_COLUMNS = (
    "object, cup, seed, trial, variant, status, attempts, error, finished_at"
)


def crash_campaign(directory: Path, cup: str) -> Campaign:
    """One object, one cup called ``cup``, two trials, one variant: 2 rows."""
    return load_campaign(write_notebook_campaign(directory / f"{cup}.yaml", cup))


def deaths(directory: Path, cup: str) -> int:
    """How many times a row of ``cup`` killed its worker (its marker files)."""
    return len(list(directory.glob(f"notebook-{cup}-died-*")))


def check_resume(campaign: Campaign, db: Path, executor: Any) -> list[tuple]:
    """A rerun computes nothing; one row per combination, none missing.

    Returns the rows (:data:`CRASH_COLUMNS`), by trial.
    """
    before = rollout_rows(db, CRASH_COLUMNS)
    again = run_campaign(campaign, db, executor, stream=io.StringIO())
    assert (again.resumed, again.computed) == (2, 0)
    after = rollout_rows(db, CRASH_COLUMNS)
    assert after == before
    keys = [row[:5] for row in after]
    expected = [
        (k.object, k.cup, k.seed, k.trial, k.variant.value) for k in campaign.row_keys()
    ]
    assert sorted(keys) == sorted(set(keys)) == sorted(expected)
    return after
