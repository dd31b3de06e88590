"""A lost node: its row runs again on another node; none is lost or doubled.

A Ray cluster of several nodes on this machine (``ray.cluster_utils``): a
head with no CPUs, which runs no row, and worker nodes of one CPU each,
each at its own loopback address (127.0.0.2, ...). The campaigns run
through the command line, ``--executor ray --ray-address`` the head's
address. As soon as a row runs on a worker node (a Ray worker process, a
child of that node's raylet, titled ``ray::run_task``), the node is removed
(its raylet and workers killed).

- A worker node is lost (its own temporary directory, as on another
  machine; the driver is on the head): a new node is added, the lost row
  runs again on it (``attempts`` 2, another worker process than the one
  seen running), the row that waited is run once; each row of the campaign
  is in the database once; the same command run again computes nothing.
- The driver's own node is lost (a node sharing the head's session
  directory, whose address the driver then takes as its own, so that it
  connects to that node's raylet): nothing can run any more; the command
  stops with a one-line error and exit code 2, and no row is blamed (none
  is recorded as ``crashed``).

Evidence independent of the executor: the pid of the worker process seen
running when its node was removed, and the rows in the database.

The rows put the notebook on a cup too weak to hold it (infeasible rows, no
physics): a row still runs for seconds on a fresh worker (its imports and
the campaign's context), long enough to be seen running, and what is tested
is where rows run and how often, not what they compute.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from campaign_helpers import WEAK_CUP, rollout_rows, write_notebook_campaign

from rt_drake.experiments.campaign import Status

pytestmark = pytest.mark.slow

#: Longest wait for a row to start, and for a command to finish, s.
TIMEOUT_S = 600.0


def _command(campaign: Path, db: Path, address: str) -> list[str]:
    return [
        *(sys.executable, "-m", "rt_drake.cli", "experiment", "campaign"),
        *(str(campaign), "--out", str(db)),
        *("--executor", "ray", "--ray-address", address),
    ]


def _rows(db: Path) -> list[tuple]:
    return rollout_rows(
        db,
        "object, cup, seed, trial, variant, status, attempts, worker, error, "
        "finished_at",
    )


class _Cluster:
    """A head without CPUs; worker nodes of one CPU at 127.0.0.2, 127.0.0.3, ..."""

    def __init__(self, cluster_utils: Any) -> None:
        self.cluster = cluster_utils.Cluster(
            initialize_head=True,
            head_node_args={"num_cpus": 0, "include_dashboard": False},
        )
        self.address: str = self.cluster.address
        self.directories: list[str] = []
        self.added = 0

    def add_node(self, own_directory: bool) -> Any:
        """A node; ``own_directory``: its own temporary directory (short: sockets)."""
        options: dict[str, Any] = {"num_cpus": 1, "include_dashboard": False}
        self.added += 1
        options["node_ip_address"] = f"127.0.0.{1 + self.added}"
        if own_directory:
            self.directories.append(tempfile.mkdtemp(prefix="rtd-ray-"))
            options["temp_dir"] = self.directories[-1]
        return self.cluster.add_node(**options)

    def shutdown(self) -> None:
        self.cluster.shutdown()
        for directory in self.directories:
            shutil.rmtree(directory, ignore_errors=True)


@pytest.fixture
def cluster() -> Iterator[_Cluster]:
    """The cluster, shut down (every node's processes) whatever happens."""
    cluster = _Cluster(pytest.importorskip("ray.cluster_utils"))
    try:
        yield cluster
    finally:
        cluster.shutdown()


def _running_task(node: Any) -> int | None:
    """The pid of a Ray worker of ``node`` running a row, if any."""
    import psutil  # Ray ships it (on the path once ray is imported)
    from ray._private import ray_constants

    (raylet,) = node.all_processes[ray_constants.PROCESS_TYPE_RAYLET]
    try:
        children = psutil.Process(raylet.process.pid).children(recursive=True)
    except psutil.NoSuchProcess:
        return None
    for child in children:
        try:
            if child.cmdline()[:1] == ["ray::run_task"]:
                return child.pid
        except psutil.Error:  # exited meanwhile
            continue
    return None


def _run_and_lose(
    cluster: _Cluster, node: Any, command: list[str], log: Path, new_node: bool
) -> tuple[int, int]:
    """Run ``command``; remove ``node`` once it runs a row (then add one if asked).

    Returns the command's exit code and the pid of the worker seen running.
    """
    with log.open("w") as out:
        driver = subprocess.Popen(command, stdout=out, stderr=subprocess.STDOUT)
        try:
            deadline = time.monotonic() + TIMEOUT_S
            running = _running_task(node)
            while running is None:
                assert driver.poll() is None, log.read_text()
                assert time.monotonic() < deadline, "no row started in 10 minutes"
                time.sleep(0.05)
                running = _running_task(node)
            cluster.cluster.remove_node(node)  # kills its raylet and workers
            if new_node:
                cluster.add_node(own_directory=True)
            return driver.wait(timeout=TIMEOUT_S), running
        finally:
            if driver.poll() is None:
                driver.kill()
                driver.wait()


def test_a_row_lost_with_its_node_runs_again_elsewhere_and_none_is_lost(
    cluster, tmp_path
):
    node = cluster.add_node(own_directory=True)
    db = tmp_path / "campaign.db"
    campaign = write_notebook_campaign(
        tmp_path / "two.yaml", "weak", trials=2, cup_options=WEAK_CUP
    )
    command = _command(campaign, db, cluster.address)
    log = tmp_path / "campaign.log"
    code, killed = _run_and_lose(cluster, node, command, log, new_node=True)
    assert code == 0, log.read_text()
    rows = _rows(db)
    keys = [row[:5] for row in rows]
    assert keys == [("notebook", "weak", 0, t, "constrained") for t in (0, 1)]
    assert all(row[5] == Status.INFEASIBLE.value for row in rows), rows
    # The row lost with its node ran again, the other once, both elsewhere.
    assert sorted(row[6] for row in rows) == [1, 2], rows
    assert all(not row[7].endswith(f":{killed}") for row in rows), (killed, rows)
    # The same command computes nothing more and changes no row.
    rerun = subprocess.run(
        command, capture_output=True, text=True, timeout=TIMEOUT_S, check=False
    )
    assert rerun.returncode == 0, rerun.stderr
    assert "2 already in" in rerun.stderr and "0 to compute" in rerun.stderr
    assert _rows(db) == rows


def test_losing_the_drivers_own_node_stops_the_run_and_blames_no_row(cluster, tmp_path):
    node = cluster.add_node(own_directory=False)  # the driver connects to it
    db = tmp_path / "campaign.db"
    campaign = write_notebook_campaign(
        tmp_path / "one.yaml", "weak", trials=1, cup_options=WEAK_CUP
    )
    command = _command(campaign, db, cluster.address)
    log = tmp_path / "campaign.log"
    code, _ = _run_and_lose(cluster, node, command, log, new_node=False)
    output = log.read_text()
    assert code == 2, output
    assert "error: lost the Ray node this command runs on" in output
    assert "run the same command to resume" in output
    assert _rows(db) == []  # not recorded as crashed
