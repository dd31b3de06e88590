"""Campaigns in the physics: local and Ray executors, kill and resume, crashes.

One small campaign, the notebook x 2 cups x 1 trial, the ``constrained``
variant only (one rollout per row, the cheapest variant): 2 rows, of which
the one on the small cup is infeasible (the notebook slips off even at
rest, found in about a second), so 1 physics rollout per run, running when
the first row (the infeasible one) is committed.

- The local run is killed (SIGKILL to the driver and its workers) once its
  first row is committed, then rerun with the same command to completion.
- The Ray run uses a Ray instance the test starts on this machine
  (``ray.init(num_cpus=2)``), so CI needs no external service.
- Killed Ray workers, on that instance (the tasks of ``campaign_helpers``,
  as in ``test_campaign_crash.py``; no physics): the killed row is started
  exactly twice, then recorded; a row that dies once is started again and
  stored with ``attempts`` 2.

Each run takes about half a minute on 2 busy cores.
"""

from __future__ import annotations

import io
import json
import os
import signal
import sqlite3
import subprocess
import sys
import time
from pathlib import Path

import pytest
from campaign_helpers import (
    CRASH_COLUMNS,
    check_resume,
    crash_campaign,
    deaths,
    init_local_ray,
    rollout_rows,
    write_campaign,
    write_tool_campaign,
)
from crash_tasks import (
    BESIDE_S,
    CRASH_DIR,
    crash_always,
    crash_once,
    killed_beside,
    no_init,
)

import rt_drake
from rt_drake.cli import main
from rt_drake.experiments.campaign import (
    RowKey,
    Status,
    Variant,
    load_campaign,
    run_campaign,
)
from rt_drake.experiments.campaign._local_executor import LocalExecutor

pytestmark = pytest.mark.slow

#: Rows of the campaign: 1 object x 2 cups x TRIALS.
TRIALS = 1
ROWS = 1 * 2 * TRIALS

#: The columns that depend only on the combination (not wall times, workers).
RESULT_COLUMNS = (
    "object, cup, seed, trial, variant, status, duration_s, speed, success, "
    "slip_translation_mm, slip_rotation_deg, critical_speed, error, detail"
)


def _rows(db: Path, columns: str = RESULT_COLUMNS) -> list[tuple]:
    with sqlite3.connect(db) as connection:
        return connection.execute(
            f"SELECT {columns} FROM rollouts ORDER BY object, cup, seed, trial, variant"
        ).fetchall()


def _count(db: Path) -> int:
    try:
        with sqlite3.connect(f"file:{db}?mode=ro", uri=True) as connection:
            return connection.execute("SELECT COUNT(*) FROM rollouts").fetchone()[0]
    except sqlite3.Error:  # not created yet
        return 0


@pytest.fixture(scope="module")
def campaign_file(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("campaign") / "campaign.yaml"
    return write_campaign(path, trials=TRIALS, objects=("notebook",))


@pytest.fixture(scope="module")
def killed_and_resumed(campaign_file, tmp_path_factory):
    """The local run: killed after its first committed row, then rerun."""
    out = tmp_path_factory.mktemp("local")
    db = out / "campaign.db"
    argv = ["experiment", "campaign", str(campaign_file), "--out", str(db)]
    with (out / "killed.log").open("w") as log:
        process = subprocess.Popen(
            [sys.executable, "-m", "rt_drake.cli", *argv, "--workers", "2"],
            stdout=log,
            stderr=subprocess.STDOUT,
            start_new_session=True,  # its own process group: driver and workers
        )
        deadline = time.monotonic() + 900
        while _count(db) == 0 and process.poll() is None:
            assert time.monotonic() < deadline, "no row committed in 15 minutes"
            time.sleep(0.2)
        os.killpg(process.pid, signal.SIGKILL)
        process.wait()
    before = _rows(db, "object, cup, seed, trial, variant, finished_at")
    assert main([*argv, "--workers", "2"]) == 0
    return db, before


@pytest.fixture(scope="module")
def ray_instance(tmp_path_factory):
    """A Ray instance started here, shut down after the module's tests.

    Its workers see tests/ and the crash tests' marker directory (yielded).
    """
    ray = pytest.importorskip("ray")
    directory = tmp_path_factory.mktemp("ray_crash")
    # A Ray task is not killed with its neighbour's worker: no need to wait.
    init_local_ray(ray, {CRASH_DIR: str(directory), BESIDE_S: "0"})
    try:
        yield directory
    finally:
        ray.shutdown()


@pytest.fixture(scope="module")
def ray_run(campaign_file, ray_instance, tmp_path_factory):
    """The Ray run, on the module's Ray instance (tests/ on the workers' path)."""
    db = tmp_path_factory.mktemp("ray") / "campaign.db"
    argv = ["experiment", "campaign", str(campaign_file), "--out", str(db)]
    start = time.perf_counter()
    assert main([*argv, "--executor", "ray"]) == 0
    print(f"ray campaign run: {time.perf_counter() - start:.0f} s")
    return db


def test_kill_and_resume_loses_no_row_and_duplicates_none(
    campaign_file, killed_and_resumed
):
    db, before = killed_and_resumed
    expected = {
        (k.object, k.cup, k.seed, k.trial, k.variant.value)
        for k in load_campaign(campaign_file).row_keys()
    }
    keys = [row[:5] for row in _rows(db, "object, cup, seed, trial, variant")]
    assert len(keys) == len(set(keys)) == len(expected) == ROWS
    assert set(keys) == expected
    # Killed midway: some rows were committed, not all; they were kept as
    # they were (not computed again).
    assert 1 <= len(before) < ROWS
    after = set(_rows(db, "object, cup, seed, trial, variant, finished_at"))
    assert set(before) <= after


def test_rows_hold_the_results_and_infeasible_combinations_are_data(
    killed_and_resumed,
):
    db, _ = killed_and_resumed
    for row in _rows(db, "object, cup, status, duration_s, success, error, attempts"):
        obj, cup, status, duration, success, error, attempts = row
        assert attempts == 1
        if (obj, cup) == ("notebook", "small"):
            assert status == Status.INFEASIBLE.value and duration is None
            assert error.startswith("GraspUnstableAtRestError: object slips even at")
        else:  # the constraint holds every object it accepts
            assert status == Status.OK.value and error is None
            assert success == 1 and 0.5 < duration < 3.0


def test_local_and_ray_executors_give_the_same_rows(killed_and_resumed, ray_run):
    local_db, _ = killed_and_resumed
    ray_db = ray_run
    local, remote = _rows(local_db), _rows(ray_db)
    assert len(local) == len(remote) == ROWS
    assert local == remote
    for db in (local_db, ray_db):
        (versions,) = zip(*_rows(db, "code_version"), strict=True)
        assert all(v.startswith(rt_drake.__version__) for v in versions)


def test_report_equals_the_rows(killed_and_resumed, tmp_path):
    db, _ = killed_and_resumed
    assert main(["experiment", "report", str(db), "--out", str(tmp_path)]) == 0
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["rows"] == summary["total_rows"] == ROWS
    groups = {(g["object"], g["cup"]): g for g in summary["groups"]}
    with sqlite3.connect(db) as sql:
        for obj, cup, ran, held, infeasible in sql.execute(
            "SELECT object, cup, SUM(status = 'ok'), SUM(success),"
            " SUM(status = 'infeasible') FROM rollouts GROUP BY object, cup"
        ):
            got = groups[(obj, cup)]["variants"]["constrained"]
            assert (got["ran"], got["held"] or None, got["infeasible"]) == (
                ran,
                held,
                infeasible,
            )
    table = (tmp_path / "summary.md").read_text()
    n = TRIALS
    assert f"| notebook | small | 0/0 | - | {n} | 0 | - | - | - |" in table
    assert f"| notebook | paper | {n}/{n} | - | 0 | 0 | - | - | - |" in table


def test_local_worker_crash_is_retried_once_then_recorded(
    campaign_file, tmp_path, monkeypatch
):
    campaign = load_campaign(campaign_file)
    keys = [RowKey("notebook", "paper", 0, t, Variant.CONSTRAINED) for t in (0, 1)]
    always = LocalExecutor(1, task=crash_always, initializer=no_init)
    outcomes = {o.key.trial: o for o in always.run(campaign, keys)}
    assert outcomes[0].result.status is Status.CRASHED
    assert outcomes[0].attempts == 2 and "died 2 times" in outcomes[0].result.error
    assert outcomes[1].result.status is Status.OK
    monkeypatch.setenv(CRASH_DIR, str(tmp_path))
    once = LocalExecutor(1, task=crash_once, initializer=no_init)
    (outcome,) = once.run(campaign, keys[:1])
    assert outcome.result.status is Status.OK and outcome.attempts == 2


def test_ray_worker_crash_is_retried_once_then_recorded(campaign_file, ray_instance):
    from rt_drake.experiments.campaign._ray_executor import RayExecutor

    campaign = load_campaign(campaign_file)
    keys = [RowKey("notebook", "paper", 0, t, Variant.CONSTRAINED) for t in (0, 1)]
    outcomes = {
        o.key.trial: o for o in RayExecutor(task=crash_always).run(campaign, keys)
    }
    assert outcomes[0].result.status is Status.CRASHED
    assert "WorkerCrashedError" in outcomes[0].result.error
    assert outcomes[1].result.status is Status.OK


def test_ray_killed_worker_is_retried_once_then_recorded(ray_instance):
    from rt_drake.experiments.campaign._ray_executor import RayExecutor

    campaign = crash_campaign(ray_instance, "ray")
    db = ray_instance / "ray.db"
    executor = RayExecutor(task=killed_beside)
    run = run_campaign(campaign, db, executor, stream=io.StringIO())
    assert (run.total, run.computed, run.failed) == (2, 2, 1)
    killed, beside = check_resume(campaign, db, executor)
    assert deaths(ray_instance, "ray") == 2  # started again exactly once
    assert killed[5] == Status.CRASHED.value and killed[6] == 2
    assert "WorkerCrashedError" in killed[7]
    assert (beside[5], beside[6], beside[7]) == (Status.OK.value, 1, None)


def test_ray_row_whose_worker_dies_once_is_stored_with_two_attempts(ray_instance):
    from rt_drake.experiments.campaign._ray_executor import RayExecutor

    campaign = crash_campaign(ray_instance, "once")
    db = ray_instance / "once.db"
    run = run_campaign(campaign, db, RayExecutor(task=crash_once), stream=io.StringIO())
    assert (run.computed, run.failed) == (2, 0)
    for row in rollout_rows(db, CRASH_COLUMNS):
        assert (row[5], row[6]) == (Status.OK.value, 2)
        assert (ray_instance / f"notebook-once-{row[3]}").exists()


def test_a_tool_of_two_weak_cups_holds_what_one_cannot(tmp_path):
    """The rows and report name the tool; its MOVE is retimed under both cups.

    The kindle box weighs 2.06 N: one cup of 1.8 N of suction cannot hold
    it at rest (an infeasible row), two such cups can (3.6 N), and the
    MOVE retimed under the tool's set keeps it on the tool in the physics.
    """
    campaign_file = write_tool_campaign(tmp_path / "tool.yaml")
    db = tmp_path / "tool.db"
    argv = ["experiment", "campaign", str(campaign_file), "--out", str(db)]
    assert main([*argv, "--workers", "1"]) == 0
    rows = _rows(db, "cup, status, success, slip_translation_mm, duration_s, error")
    (cup, *weak), (tool, *pair) = rows
    assert (cup, tool) == ("weak", "weak_pair")
    assert weak[0] == Status.INFEASIBLE.value
    assert weak[4].startswith("GraspUnstableAtRestError: object slips even at rest")
    status, success, slip, duration, error = pair
    assert (status, success, error) == (Status.OK.value, 1, None)
    assert slip < 5.0 and 0.5 < duration < 5.0
    assert main(["experiment", "report", str(db), "--out", str(tmp_path)]) == 0
    assert "| kindle_box | weak_pair | 1/1 |" in (tmp_path / "summary.md").read_text()
