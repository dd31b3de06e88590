"""The campaign driver: the rows still missing, run by an executor, stored.

:func:`run_campaign` opens (or creates) the results database, checks that
it holds this campaign, hands the rows it lacks to an executor, and commits
each outcome as it arrives. Interrupted anywhere (Ctrl-C, a killed driver
or worker, a lost node), it loses at most the rows that were running; the
same call computes the rest.
"""

from __future__ import annotations

import dataclasses
import enum
import sys
import time
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import IO, Protocol

from rt_drake.experiments.campaign._campaign_progress import Progress
from rt_drake.experiments.campaign._definition import Campaign
from rt_drake.experiments.campaign._row_types import (
    Outcome,
    RowKey,
    Status,
)
from rt_drake.experiments.campaign._store import ResultStore

#: The statuses of failed rows.
FAILED = (Status.INFEASIBLE, Status.ERROR, Status.CRASHED)


class ExecutorKind(enum.Enum):
    """Where the rows run."""

    LOCAL = "local"
    RAY = "ray"


class Executor(Protocol):
    """Runs rows and yields their outcomes as they finish."""

    def describe(self) -> str:
        """One line naming the executor and its size."""
        ...

    def run(self, campaign: Campaign, keys: Sequence[RowKey]) -> Iterator[Outcome]:
        """Yield one outcome per key, in any order."""
        ...


def make_executor(
    kind: ExecutorKind, workers: int | None = None, address: str | None = None
) -> Executor:
    """A local or Ray executor.

    Raises:
        ExecutorUnavailableError: Ray is asked for but not installed.
        InputError: fewer than one worker.
    """
    if kind is ExecutorKind.RAY:
        from rt_drake.experiments.campaign._ray_executor import RayExecutor

        return RayExecutor(address=address, workers=workers)
    from rt_drake.experiments.campaign._local_executor import LocalExecutor

    return LocalExecutor(workers)


@dataclasses.dataclass(frozen=True)
class CampaignRun:
    """What one call of :func:`run_campaign` did.

    Attributes:
        total: Rows of the campaign.
        resumed: Rows already in the database at the start.
        computed: Rows computed and stored by this call.
        failed: Failed rows in the database at the end.
        wall_s: Wall time of this call, s.
    """

    total: int
    resumed: int
    computed: int
    failed: int
    wall_s: float


def run_campaign(
    campaign: Campaign,
    database: str | Path,
    executor: Executor,
    retry_failed: bool = False,
    stream: IO[str] | None = None,
) -> CampaignRun:
    """Compute every row of ``campaign`` not yet in ``database``.

    Args:
        campaign: The loaded campaign.
        database: The SQLite file (created if missing).
        executor: Where the rows run.
        retry_failed: First forget the ``error`` and ``crashed`` rows, so
            they are computed again (``infeasible`` rows are kept: they are
            results).
        stream: Progress output (default stderr).

    Raises:
        CampaignMismatchError: the database holds another campaign.
    """
    stream = sys.stderr if stream is None else stream
    start = time.perf_counter()
    with ResultStore(database, campaign) as store:
        if retry_failed:
            store.forget(Status.ERROR, Status.CRASHED)
        finished = store.finished()
        keys = [key for key in campaign.row_keys() if key not in finished]
        total = len(campaign.row_keys())
        progress = Progress(total, len(finished), store.count(*FAILED), stream)
        print(
            f"campaign {campaign.content_hash[:12]}: {total} rows, "
            f"{len(finished)} already in {store.path}, {len(keys)} to compute "
            f"({executor.describe()})",
            file=stream,
            flush=True,
        )
        computed = 0
        try:
            if keys:
                for outcome in executor.run(campaign, keys):
                    store.add(outcome)
                    computed += 1
                    progress.advance(outcome.result.status is not Status.OK)
        finally:
            progress.close()
        return CampaignRun(
            total=total,
            resumed=len(finished),
            computed=computed,
            failed=store.count(*FAILED),
            wall_s=time.perf_counter() - start,
        )


__all__ = [
    "FAILED",
    "CampaignRun",
    "Executor",
    "ExecutorKind",
    "make_executor",
    "run_campaign",
]
