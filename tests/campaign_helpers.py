"""Campaign test helpers importable by worker processes (``tests`` is on the path).

Tasks that crash their worker, to test the executors' retry, and a
campaign file writer.
"""

from __future__ import annotations

import os
from pathlib import Path

from rt_drake.experiments.campaign.rows import Outcome, RowResult, Status
from rt_drake.experiments.campaign.worker import Task

#: Environment variable: directory of the marker files of crash_once.
CRASH_DIR = "RT_DRAKE_TEST_CRASH_DIR"


def no_init(campaign_path: str, content_hash: str) -> None:
    """A pool initializer that builds nothing."""


def _ok(task: Task) -> Outcome:
    return Outcome(task.key, RowResult(Status.OK, duration_s=1.0), 0.0, 0.0, "t", "t")


def crash_always(task: Task) -> Outcome:
    """Kill the worker process at every start of trial 0; trial 1 succeeds."""
    if task.key.trial == 0:
        os._exit(3)
    return _ok(task)


def crash_once(task: Task) -> Outcome:
    """Kill the worker at the first start of each row (a marker file remembers)."""
    marker = Path(os.environ[CRASH_DIR]) / f"{task.key.object}-{task.key.trial}"
    if not marker.exists():
        marker.touch()
        os._exit(3)
    return _ok(task)


def write_campaign(
    path: Path, trials: int = 2, variants: str | None = "[constrained]"
) -> Path:
    """Two boxes x two cups (the small cup cannot hold the notebook at rest).

    ``variants`` None leaves the key out (the default variants).
    """
    line = "" if variants is None else f"variants: {variants}\n"
    path.write_text(
        f"""\
scenario: random_transport
objects:
- model: package://rt_drake/objects/notebook.sdf
- model: package://rt_drake/objects/kindle_box.sdf
cups:
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
