"""The Ray executor: each row one Ray task, on this machine or a cluster.

``ray.init()`` starts a local Ray instance (``workers`` CPUs, default all),
or, given an address (``auto``, ``ray://host:10001``, ``host:6379``), joins
a running cluster; a Ray instance the caller already started is used as it
is. Tasks are submitted in a window of twice the cluster's CPUs, so that the
driver holds few references whatever the campaign's size. A Ray worker
process builds the campaign's shared inputs at its first task and keeps
them (:mod:`._worker`); Ray reuses its worker processes across tasks.

A task whose worker or node dies is started again once by the executor
(not by Ray's ``max_retries``, so that the row records its starts in
``attempts``); if it dies again the row is recorded as ``crashed``. A Ray
task runs in one worker process, so the row whose worker died is known.
If the node of the driver itself is lost (its raylet dies), no task can run
any more: the run stops with an ExecutorUnavailableError, no row blamed,
and the same command resumes it.
Every node needs rt-drake installed and the campaign's files at the same
paths (a shared file system, or the same checkout on each node).

Ray is an optional extra (``pip install "rt-drake[ray]"``).
"""

from __future__ import annotations

import collections
import dataclasses
import warnings
from collections.abc import Callable, Iterator, Sequence
from types import ModuleType
from typing import Any

from rt_drake.errors import InputError, RtDrakeError
from rt_drake.experiments.campaign._campaign_errors import ExecutorUnavailableError
from rt_drake.experiments.campaign._definition import Campaign
from rt_drake.experiments.campaign._local_executor import (
    MAX_ATTEMPTS,
    crashed,
)
from rt_drake.experiments.campaign._row_types import (
    Outcome,
    RowKey,
    Task,
)
from rt_drake.experiments.campaign._worker import run_task

#: The Ray version rt-drake is tested with (the ``ray`` extra pins it).
RAY_VERSION = "2.52.0"


def import_ray() -> ModuleType:
    """The ``ray`` module; ExecutorUnavailableError saying how to install it."""
    try:
        import ray
    except ImportError:
        raise ExecutorUnavailableError(
            "the ray executor needs Ray, an optional extra: "
            f'pip install "rt-drake[ray]" (or pip install "ray=={RAY_VERSION}")'
        ) from None
    return ray


class RayExecutor:
    """Run rows as Ray tasks (see the module docstring).

    Args:
        address: A running cluster to join (None: start Ray on this machine).
        workers: CPUs of a Ray started here (None: all); ignored when joining.
        task: What a Ray task runs per row (tests inject one that crashes).
    """

    def __init__(
        self,
        address: str | None = None,
        workers: int | None = None,
        task: Callable[[Task], Outcome] = run_task,
    ) -> None:
        self._task = task
        if workers is not None and workers < 1:
            raise InputError(f"number of Ray CPUs must be >= 1, got {workers}")
        self.address = address
        self.workers = workers
        self._ray = import_ray()

    def describe(self) -> str:
        """One line for the progress header."""
        where = f"cluster at {self.address}" if self.address else "this machine"
        return f"ray executor, {where}"

    def run(self, campaign: Campaign, keys: Sequence[RowKey]) -> Iterator[Outcome]:
        """Yield each row's outcome as it finishes (in no particular order)."""
        ray = self._ray
        started = not ray.is_initialized()
        if started:
            self._init()
        remote = ray.remote(num_cpus=1, max_retries=0)(self._task)
        running: dict[Any, RowKey] = {}
        starts: collections.Counter[RowKey] = collections.Counter()
        try:
            window = 2 * max(1, int(ray.cluster_resources().get("CPU", 1)))
            pending = collections.deque(keys)
            while pending or running:
                while pending and len(running) < window:
                    key = pending.popleft()
                    starts[key] += 1
                    task = Task(str(campaign.path), campaign.content_hash, key)
                    running[remote.remote(task)] = key
                done, _ = ray.wait(list(running), num_returns=1)
                for ref in done:
                    key = running.pop(ref)
                    outcome = self._outcome(ref, key, starts[key])
                    if outcome is None:  # its worker died: start it again
                        pending.appendleft(key)
                    else:
                        yield outcome
        finally:
            for ref in running:
                ray.cancel(ref, force=True)
            if started:
                ray.shutdown()

    def _init(self) -> None:
        options: dict[str, Any] = {
            "include_dashboard": False,
            "log_to_driver": False,
            "logging_level": "WARNING",
        }
        if self.address is None:
            options["num_cpus"] = self.workers
        try:
            with warnings.catch_warnings():  # Ray's notices of future changes
                warnings.simplefilter("ignore", FutureWarning)
                self._ray.init(address=self.address, **options)
        except (ConnectionError, RuntimeError, ValueError) as error:
            message = " ".join(str(error).split())
            raise ExecutorUnavailableError(
                f"cannot start or join Ray: {message}"
            ) from None

    def _outcome(self, ref: Any, key: RowKey, starts: int) -> Outcome | None:
        """The task's outcome, started ``starts`` times.

        None if its worker (or node) died and it may start again; after
        :data:`MAX_ATTEMPTS` deaths, a ``crashed`` row.

        Raises:
            ExecutorUnavailableError: the driver's own node died.
        """
        exceptions = self._ray.exceptions
        try:
            outcome: Outcome = self._ray.get(ref)
        except exceptions.RayTaskError as error:
            cause = getattr(error, "cause", None)
            if isinstance(cause, RtDrakeError):
                raise cause from None
            raise
        except exceptions.LocalRayletDiedError:  # every task would fail so
            raise ExecutorUnavailableError(
                "lost the Ray node this command runs on (its raylet died); the "
                "finished rows are stored: run the same command to resume"
            ) from None
        except exceptions.RayError as error:  # worker or node died
            if starts < MAX_ATTEMPTS:
                return None
            first = str(error).strip().splitlines()[0] if str(error) else ""
            return crashed(key, starts, f"{type(error).__name__}: {first}")
        return dataclasses.replace(outcome, attempts=starts)


__all__ = ["RAY_VERSION", "RayExecutor", "import_ray"]
