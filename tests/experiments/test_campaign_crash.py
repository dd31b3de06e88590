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
- Ray executor: in ``test_campaign_run.py``, on the Ray instance its Ray
  campaign starts (one Ray start for both).
"""

from __future__ import annotations

import io

import pytest
from campaign_helpers import (
    check_resume,
    crash_campaign,
    deaths,
)
from crash_tasks import (
    CRASH_DIR,
    killed_beside,
    no_init,
)

from rt_drake.experiments.campaign import Status, run_campaign
from rt_drake.experiments.campaign._local_executor import LocalExecutor

pytestmark = pytest.mark.slow


def test_local_killed_worker_is_retried_alone_once_then_recorded(tmp_path, monkeypatch):
    monkeypatch.setenv(CRASH_DIR, str(tmp_path))
    campaign = crash_campaign(tmp_path, "local")
    db = tmp_path / "local.db"
    executor = LocalExecutor(2, task=killed_beside, initializer=no_init)
    run = run_campaign(campaign, db, executor, stream=io.StringIO())
    assert (run.total, run.computed, run.failed) == (2, 2, 1)
    killed, beside = check_resume(campaign, db, executor)
    # Usually the pool breaks with both rows: trial 0 is not blamed for that
    # death (whose worker it was is unknown) and dies twice more alone:
    # three deaths, three starts; trial 1 is started again, alone. But the
    # pool may notice the death only after trial 1 has finished (CPython
    # watches a worker spawned by a later submit from its next event on):
    # then trial 0 broke the pool alone, and dies twice, started twice.
    died = deaths(tmp_path, "local")
    assert died in (2, 3)
    assert killed[5] == Status.CRASHED.value and killed[6] == died
    message = f"WorkerCrashed: worker died 2 times, started {died} times"
    assert killed[7].startswith(message)
    # The row beside it finished (never blamed).
    assert (beside[5], beside[6], beside[7]) == (Status.OK.value, died - 1, None)
