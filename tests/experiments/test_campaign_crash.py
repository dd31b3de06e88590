"""Killed workers: a row whose worker dies is started once more, then recorded.

No physics: the tasks are the test helpers of ``campaign_helpers`` (trial 0
SIGKILLs its own worker process at every start, trial 1 runs beside it and
succeeds), so each test costs the start of a few worker processes. The
evidence that a worker died is independent of the executor: the marker
file each doomed task leaves just before it kills its process.

- Local executor, 2 workers: the pool breaks with both rows running; the
  killed row is recorded as ``crashed`` after dying twice alone, the row
  beside it is not blamed and finishes (before, it was started twice beside
  the killed row and recorded as ``crashed`` too); a rerun with the same
  command computes nothing and the database keeps one row per combination.
- Ray executor (a Ray instance started here): the killed row is started
  exactly twice, then recorded; a row that dies once is started again and
  stored with ``attempts`` 2.
"""

from __future__ import annotations

import io
from pathlib import Path

import pytest
from campaign_helpers import (
    BESIDE_S,
    CRASH_DIR,
    crash_once,
    init_local_ray,
    killed_beside,
    no_init,
    rollout_rows,
    write_notebook_campaign,
)

from rt_drake.experiments.campaign import Status, load_campaign, run_campaign
from rt_drake.experiments.campaign._local_executor import LocalExecutor

pytestmark = pytest.mark.slow


def _campaign(directory: Path, cup: str):
    """One object, one cup called ``cup``, two trials, one variant: 2 rows."""
    return load_campaign(write_notebook_campaign(directory / f"{cup}.yaml", cup))


def _rows(db: Path) -> list[tuple]:
    return rollout_rows(
        db,
        "object, cup, seed, trial, variant, status, attempts, error, finished_at",
    )


def _deaths(directory: Path, cup: str) -> int:
    return len(list(directory.glob(f"notebook-{cup}-died-*")))


def _check_resume(campaign, db: Path, executor) -> list[tuple]:
    """A rerun computes nothing; one row per combination, none missing."""
    before = _rows(db)
    again = run_campaign(campaign, db, executor, stream=io.StringIO())
    assert (again.resumed, again.computed) == (2, 0)
    after = _rows(db)
    assert after == before
    keys = [row[:5] for row in after]
    expected = [
        (k.object, k.cup, k.seed, k.trial, k.variant.value) for k in campaign.row_keys()
    ]
    assert sorted(keys) == sorted(set(keys)) == sorted(expected)
    return after


def test_local_killed_worker_is_retried_alone_once_then_recorded(tmp_path, monkeypatch):
    monkeypatch.setenv(CRASH_DIR, str(tmp_path))
    campaign = _campaign(tmp_path, "local")
    db = tmp_path / "local.db"
    executor = LocalExecutor(2, task=killed_beside, initializer=no_init)
    run = run_campaign(campaign, db, executor, stream=io.StringIO())
    assert (run.total, run.computed, run.failed) == (2, 2, 1)
    killed, beside = _check_resume(campaign, db, executor)
    # Usually the pool breaks with both rows: trial 0 is not blamed for that
    # death (whose worker it was is unknown) and dies twice more alone:
    # three deaths, three starts; trial 1 is started again, alone. But the
    # pool may notice the death only after trial 1 has finished (CPython
    # watches a worker spawned by a later submit from its next event on):
    # then trial 0 broke the pool alone, and dies twice, started twice.
    deaths = _deaths(tmp_path, "local")
    assert deaths in (2, 3)
    assert killed[5] == Status.CRASHED.value and killed[6] == deaths
    message = f"WorkerCrashed: worker died 2 times, started {deaths} times"
    assert killed[7].startswith(message)
    # The row beside it finished (never blamed).
    assert (beside[5], beside[6], beside[7]) == (Status.OK.value, deaths - 1, None)


@pytest.fixture(scope="module")
def ray_crash_dir(tmp_path_factory):
    """A Ray instance started here; its workers see tests/ and the marker dir."""
    ray = pytest.importorskip("ray")
    directory = tmp_path_factory.mktemp("ray_crash")
    # A Ray task is not killed with its neighbour's worker: no need to wait.
    init_local_ray(ray, {CRASH_DIR: str(directory), BESIDE_S: "0"})
    try:
        yield directory
    finally:
        ray.shutdown()


def test_ray_killed_worker_is_retried_once_then_recorded(ray_crash_dir):
    from rt_drake.experiments.campaign._ray_executor import RayExecutor

    campaign = _campaign(ray_crash_dir, "ray")
    db = ray_crash_dir / "ray.db"
    executor = RayExecutor(task=killed_beside)
    run = run_campaign(campaign, db, executor, stream=io.StringIO())
    assert (run.total, run.computed, run.failed) == (2, 2, 1)
    killed, beside = _check_resume(campaign, db, executor)
    assert _deaths(ray_crash_dir, "ray") == 2  # started again exactly once
    assert killed[5] == Status.CRASHED.value and killed[6] == 2
    assert "WorkerCrashedError" in killed[7]
    assert (beside[5], beside[6], beside[7]) == (Status.OK.value, 1, None)


def test_ray_row_whose_worker_dies_once_is_stored_with_two_attempts(ray_crash_dir):
    from rt_drake.experiments.campaign._ray_executor import RayExecutor

    campaign = _campaign(ray_crash_dir, "once")
    db = ray_crash_dir / "once.db"
    run = run_campaign(campaign, db, RayExecutor(task=crash_once), stream=io.StringIO())
    assert (run.computed, run.failed) == (2, 0)
    for row in _rows(db):
        assert (row[5], row[6]) == (Status.OK.value, 2)
        assert (ray_crash_dir / f"notebook-once-{row[3]}").exists()
