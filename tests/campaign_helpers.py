"""Campaign test helpers importable by worker processes (``tests`` is on the path).

Tasks that crash their worker, to test the executors' retry, and
campaign file writers.
"""

from __future__ import annotations

import io
import os
import signal
import sqlite3
import time
import warnings
from pathlib import Path
from typing import Any

from rt_drake.experiments.campaign import Campaign, load_campaign, run_campaign
from rt_drake.experiments.campaign._row_types import (
    Outcome,
    RowResult,
    Status,
)
from rt_drake.experiments.campaign._worker import Task

#: Environment variable: directory of the marker files of crash_once.
CRASH_DIR = "RT_DRAKE_TEST_CRASH_DIR"

#: Environment variable: seconds killed_beside's trial 1 outlives trial 0.
BESIDE_S = "RT_DRAKE_TEST_BESIDE_S"


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
    key = task.key
    marker = Path(os.environ[CRASH_DIR]) / f"{key.object}-{key.cup}-{key.trial}"
    if not marker.exists():
        marker.touch()
        os._exit(3)
    return _ok(task)


def _markers(task: Task, kind: str) -> list[Path]:
    directory = Path(os.environ[CRASH_DIR])
    return list(directory.glob(f"{task.key.object}-{task.key.cup}-{kind}-*"))


def _mark(task: Task, kind: str) -> int:
    """Leave one more ``kind`` marker of the task's (object, cup); their count."""
    count = len(_markers(task, kind)) + 1
    name = f"{task.key.object}-{task.key.cup}-{kind}-{count}-{os.getpid()}"
    (Path(os.environ[CRASH_DIR]) / name).touch()
    return count


def killed_beside(task: Task) -> Outcome:
    """Trial 0 SIGKILLs its own worker at every start; trial 1 runs beside it.

    Trial 0 first waits (at most 60 s) for trial 1 to have started once.
    Trial 1, at its n-th start, waits (at most 60 s) for trial 0's n-th
    death and, if trial 0 has died exactly n times, ``$RT_DRAKE_TEST_BESIDE_S``
    seconds more (default 3): it is still running when a pool of both
    breaks. Started after trial 0's last death (run alone), it finishes at
    once, as other trials do. Markers (per object and cup) in
    ``$RT_DRAKE_TEST_CRASH_DIR``.
    """
    if task.key.trial == 0:
        _wait_for(task, "beside", 1)
        _mark(task, "died")
        os.kill(os.getpid(), signal.SIGKILL)
    if task.key.trial == 1:
        start = _mark(task, "beside")
        _wait_for(task, "died", start)
        if len(_markers(task, "died")) == start:
            time.sleep(float(os.environ.get(BESIDE_S, "3")))
    return _ok(task)


def _wait_for(task: Task, kind: str, count: int) -> None:
    deadline = time.monotonic() + 60.0
    while len(_markers(task, kind)) < count:
        assert time.monotonic() < deadline, f"no {count} {kind} markers in 60 s"
        time.sleep(0.02)


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
