"""Row tasks that kill their worker, to test the executors' retry.

Light on purpose: a worker process (a pool's or Ray's) imports this module
to unpickle the task, and it imports only the campaign's row types, not the
simulation (about 3 s of CPU per worker start otherwise).
"""

from __future__ import annotations

import os
import signal
import time
from pathlib import Path

from rt_drake.experiments.campaign._row_types import (
    Outcome,
    RowResult,
    Status,
    Task,
)

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
