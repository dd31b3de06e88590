"""Run an experiment's independent trials, in this process or in worker processes.

The trials of ``experiment transport`` (with or without ``--optimize``) and
of ``experiment transport --robust`` are independent jobs; this runs them and
reports progress as each finishes.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from multiprocessing import get_context
from typing import Any

Trial = dict[str, Any]


def run_trials(
    run: Callable[[Any], Trial],
    jobs: Sequence[Any],
    workers: int,
    progress: Callable[[int, int], None] | None = None,
) -> list[Trial]:
    """``[run(job) for job in jobs]``, in order of each trial's ``"index"``.

    Args:
        run: a module-level function (picklable: workers are spawned) of one job,
            returning the trial's record with its ``"index"``.
        jobs: the trials' arguments.
        workers: 1 runs in this process; more spawns that many processes.
        progress: called with (done, total) before the first trial and after each.
    """
    report = progress or (lambda done, total: None)
    total = len(jobs)
    report(0, total)
    trials: list[Trial] = []
    if workers == 1:
        for job in jobs:
            trials.append(run(job))
            report(len(trials), total)
        return trials
    with ProcessPoolExecutor(workers, mp_context=get_context("spawn")) as pool:
        for future in as_completed([pool.submit(run, job) for job in jobs]):
            trials.append(future.result())
            report(len(trials), total)
    trials.sort(key=lambda trial: trial["index"])
    return trials


__all__ = ["run_trials"]
