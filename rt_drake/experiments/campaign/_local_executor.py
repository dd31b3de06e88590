"""The local executor: a pool of spawned processes on this machine.

Each row is one task of a ``ProcessPoolExecutor`` (spawn context, so no
Drake state is forked); each worker process builds its shared inputs once,
in the pool's initializer (:func:`._worker.init_worker`). At most one task
per worker is in flight, so when a worker dies (killed, out of memory, a
crash in compiled code) the pool breaks with exactly the rows that were
running. The pool does not say whose worker died, so a row is blamed for a
death only when it ran alone: the rows that were running together are
started again one at a time (in a pool of one worker), and a row whose
worker died while it ran alone is started again once; if it dies again, it
is recorded as ``crashed``. A row that merely ran beside a crashing one is
never recorded as crashed.
"""

from __future__ import annotations

import collections
import dataclasses
import os
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from multiprocessing import get_context

from rt_drake.errors import InputError
from rt_drake.experiments.campaign._definition import Campaign
from rt_drake.experiments.campaign._row_types import (
    Outcome,
    RowKey,
    RowResult,
    Status,
    Task,
)
from rt_drake.experiments.campaign._worker import (
    code_version,
    init_worker,
    run_task,
)

#: How many times a row is started before its crashes are recorded.
MAX_ATTEMPTS = 2


def crashed(key: RowKey, attempts: int, cause: str) -> Outcome:
    """The row of a task started ``attempts`` times whose worker died each time.

    (Locally, a first start beside another row's crash adds a start.)
    """
    return Outcome(
        key=key,
        result=RowResult.failed(
            Status.CRASHED,
            f"WorkerCrashed: worker died {MAX_ATTEMPTS} times, started "
            f"{attempts} times ({cause})",
        ),
        wall_s=None,
        cpu_s=None,
        worker="",
        code_version=code_version(),
        attempts=attempts,
    )


class LocalExecutor:
    """Run rows in ``workers`` processes of this machine (default: one per CPU).

    Args:
        workers: Worker processes.
        task: What a worker runs per row (tests inject one that crashes).
        initializer: What a worker runs first, with the campaign's path and
            content hash.
    """

    def __init__(
        self,
        workers: int | None = None,
        task: Callable[[Task], Outcome] = run_task,
        initializer: Callable[[str, str], None] = init_worker,
    ) -> None:
        self._task, self._initializer = task, initializer
        if workers is None:
            workers = os.cpu_count() or 1
        if workers < 1:
            raise InputError(f"number of worker processes must be >= 1, got {workers}")
        self.workers = workers

    def describe(self) -> str:
        """One line for the progress header."""
        return f"local executor, {self.workers} worker process(es)"

    def run(self, campaign: Campaign, keys: Sequence[RowKey]) -> Iterator[Outcome]:
        """Yield each row's outcome as it finishes (in no particular order)."""
        pending = collections.deque(keys)
        alone: collections.deque[RowKey] = collections.deque()  # run one at a time
        starts: collections.Counter[RowKey] = collections.Counter()
        deaths: collections.Counter[RowKey] = collections.Counter()  # while alone
        while pending or alone:
            queue = alone or pending
            size = 1 if alone else min(self.workers, len(pending))
            pool = ProcessPoolExecutor(
                size,
                mp_context=get_context("spawn"),
                initializer=self._initializer,
                initargs=(str(campaign.path), campaign.content_hash),
            )
            broken: list[tuple[RowKey, str]] = []
            finished = False
            try:
                yield from _drain(
                    pool, size, self._task, campaign, queue, starts, broken
                )
                finished = True
            finally:
                _stop(pool, wait=finished)
            if len(broken) > 1:  # whose worker died is unknown: run each alone
                alone.extend(key for key, _ in broken)
                continue
            for key, cause in broken:  # it ran alone: its worker died
                deaths[key] += 1
                if deaths[key] < MAX_ATTEMPTS:
                    alone.appendleft(key)
                else:
                    yield crashed(key, starts[key], cause)


def _drain(
    pool: ProcessPoolExecutor,
    size: int,
    function: Callable[[Task], Outcome],
    campaign: Campaign,
    queue: collections.deque[RowKey],
    starts: collections.Counter[RowKey],
    broken: list[tuple[RowKey, str]],
) -> Iterator[Outcome]:
    """Run ``queue`` in ``pool`` (``size`` workers) until done or it breaks.

    The rows that were running when the pool broke go to ``broken`` with the
    error, in the order they were started.
    """
    running: dict[Future[Outcome], RowKey] = {}
    while running or (queue and not broken):
        while queue and not broken and len(running) < size:
            key = queue.popleft()
            starts[key] += 1
            task = Task(str(campaign.path), campaign.content_hash, key)
            running[pool.submit(function, task)] = key
        done, _ = wait(running, return_when=FIRST_COMPLETED)
        for future in sorted(done, key=list(running).index):
            key = running.pop(future)
            try:
                outcome = future.result()
            except BrokenProcessPool as error:
                broken.append((key, str(error)))
                continue
            yield dataclasses.replace(outcome, attempts=starts[key])


def _stop(pool: ProcessPoolExecutor, wait: bool) -> None:
    """Shut ``pool`` down; unless waiting, terminate its running workers.

    An interrupted campaign must not leave workers computing rows nobody will
    store. ``ProcessPoolExecutor`` has no public way to stop a running task
    before Python 3.14, hence its private ``_processes``.
    """
    if not wait:
        for process in list(getattr(pool, "_processes", {}).values()):
            process.terminate()
    pool.shutdown(wait=wait, cancel_futures=True)


__all__ = ["MAX_ATTEMPTS", "LocalExecutor", "crashed"]
