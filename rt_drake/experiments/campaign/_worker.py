"""What runs in a campaign worker: its shared inputs, built once, and a task.

A worker (a process of the local pool, or a Ray worker process) serves one
campaign. Its heavy shared inputs, a :class:`WorkerContext`, are built once
per worker and kept for all its tasks:

- the loaded campaign and its base scenario (re-hashed: a worker refuses to
  run if the files changed since the driver hashed them);
- the retimer's compiled numba kernels (:func:`rt_drake.retiming.warm_up`),
  and the MOVE optimiser's if the campaign runs the ``optimized`` variant
  (:func:`rt_drake.shaping.warm_up`), so that no row's optimisation
  time counts a compilation;
- the exact wrench polytope of every cup or tool, the one its MOVEs are
  retimed under (computed once, then in the on-disk cache that each task's
  retimer reads in milliseconds; a set that cannot be made is left for its
  rows to record as infeasible);
- the code version (rt_drake's version and git commit) and ``host:pid``.

The cache :data:`_CONTEXTS` is the campaign package's one module-level
mutable state, by design: it is per worker process, keyed on the campaign's
content hash, and holds at most one context (a new campaign replaces it).
The local executor fills it in the pool's initializer; a Ray worker fills
it at its first task.
"""

from __future__ import annotations

import dataclasses
import logging
import os
import socket
import subprocess
import time
from pathlib import Path

from rt_drake._version import __version__
from rt_drake.errors import RtDrakeError
from rt_drake.experiments.campaign._campaign_errors import CampaignMismatchError
from rt_drake.experiments.campaign._definition import (
    Campaign,
    load_campaign,
)
from rt_drake.experiments.campaign._row_types import (
    Outcome,
    Task,
    Variant,
)
from rt_drake.experiments.campaign._variants import run_variant
from rt_drake.retiming import warm_up
from rt_drake.shaping import warm_up as warm_up_optimizer
from rt_drake.simulation.move_grasp import move_polytope


@dataclasses.dataclass(frozen=True, eq=False)
class WorkerContext:
    """A worker's shared inputs for one campaign (see the module docstring)."""

    campaign: Campaign
    code_version: str
    worker: str


#: Per-worker cache of the shared inputs, keyed on the campaign content hash.
_CONTEXTS: dict[str, WorkerContext] = {}


def code_version() -> str:
    """``<version>+g<commit>`` (``.dirty`` if modified), or the version alone.

    The commit is that of the git checkout rt_drake is imported from, if any.
    """
    source = Path(__file__).resolve().parent
    try:
        commit = _git(source, "rev-parse", "--short=12", "HEAD")
        dirty = _git(source, "status", "--porcelain", "--untracked-files=no")
    except (OSError, subprocess.SubprocessError):
        return __version__
    return f"{__version__}+g{commit}{'.dirty' if dirty else ''}"


def _git(directory: Path, *args: str) -> str:
    return subprocess.run(
        ["git", "-C", str(directory), *args],
        capture_output=True,
        text=True,
        check=True,
        timeout=10,
    ).stdout.strip()


def build_context(campaign_path: str, content_hash: str) -> WorkerContext:
    """Load the campaign, check its hash, compile the kernels, make the polytopes.

    Raises:
        CampaignMismatchError: the campaign's files changed since it was hashed.
    """
    campaign = load_campaign(campaign_path)
    if campaign.content_hash != content_hash:
        raise CampaignMismatchError(
            f"{campaign_path}: the campaign or one of its files changed since the "
            f"run started (content hash {campaign.content_hash[:12]}, expected "
            f"{content_hash[:12]})"
        )
    # Not Drake's INFO line at every simulation (pydrake syncs its C++ level).
    logging.getLogger("drake").setLevel(logging.WARNING)
    warm_up()
    if Variant.OPTIMIZED in campaign.variants:
        warm_up_optimizer()
    for cup in campaign.cups:
        try:
            move_polytope(campaign.cup_scenario(cup))
        except RtDrakeError:  # e.g. a tool's set too large: its rows say so
            pass
    return WorkerContext(
        campaign, code_version(), f"{socket.gethostname()}:{os.getpid()}"
    )


def worker_context(campaign_path: str, content_hash: str) -> WorkerContext:
    """This worker's context for the campaign, built at the first call."""
    context = _CONTEXTS.get(content_hash)
    if context is None:
        context = build_context(campaign_path, content_hash)
        _CONTEXTS.clear()
        _CONTEXTS[content_hash] = context
    return context


def init_worker(campaign_path: str, content_hash: str) -> None:
    """Pool initializer: build the context now, before the first task.

    An error here is left for the first task to raise (a failing initializer
    would only break the pool, without its message).
    """
    try:
        worker_context(campaign_path, content_hash)
    except Exception:  # raised again by the first task
        pass


def run_task(task: Task) -> Outcome:
    """Compute one row in this worker; failures of the row are data.

    Raises:
        RtDrakeError: only if the shared inputs cannot be built (the whole
            campaign would fail); a row's own failure is in its result.
    """
    context = worker_context(task.campaign_path, task.content_hash)
    start, cpu = time.perf_counter(), time.process_time()
    result = run_variant(context.campaign.combination(task.key))
    return Outcome(
        key=task.key,
        result=result,
        wall_s=time.perf_counter() - start,
        cpu_s=time.process_time() - cpu,
        worker=context.worker,
        code_version=context.code_version,
    )


__all__ = [
    "WorkerContext",
    "build_context",
    "code_version",
    "init_worker",
    "run_task",
    "worker_context",
]
