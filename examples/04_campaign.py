"""Run a tiny validation campaign in the physics and read its results.

What it shows: a campaign is a YAML file naming a base scenario, objects,
cups and how many random transports to simulate; ``rt-drake experiment
campaign`` runs every (object, cup, trial, variant) row in local worker
processes and commits each to a SQLite file, and ``rt-drake experiment
report`` summarises the file. This one is as small as a campaign gets: the
kindle box (0.21 kg, 2.06 N of weight) on two cups, one random transport,
the ``constrained`` variant (the MOVE retimed under the cup's grasp
constraint, then played in the simulated cell). The paper's cup holds the
box through the transport; a weak cup of 1 N of suction cannot hold it even
at rest, and its row is recorded as ``infeasible`` without a simulation:
failures are data.

What it prints (one ``key: value`` per line, after the commands' own
output):

- ``row``: one line per row of the database: object, cup, variant, status,
  then for a simulated row the MOVE's ``duration`` (s), whether the box was
  ``held`` and how far it slipped on the cup (``slip``, mm), and for an
  infeasible one the ``error``;
- ``held``: per cup, transports held of those simulated, from the report's
  ``summary.json``;
- ``report``: the directory of ``summary.md``, ``.csv``, ``.json`` and the
  plots.

How to run it::

    python examples/04_campaign.py                 # writes ./campaign_example/
    python examples/04_campaign.py out_dir         # or the directory you name

It takes under a minute on a busy 2-core machine (17 s of CPU: one physics
rollout, the commands' start-up and the report's plots).
"""

from __future__ import annotations

import json
import sqlite3
import subprocess
import sys
from pathlib import Path

#: The campaign: the kindle box, the paper's cup and a weak one, one trial.
CAMPAIGN = """\
scenario: random_transport   # the shipped scenario of that name
objects:
- model: package://rt_drake/objects/kindle_box.sdf
cups:
- name: paper                # the paper's cup: r 12.5 mm, mu 0.3, 20 N
- name: weak                 # 1 N of suction: less than the box's weight
  suction_force: 1.0
trials: 1
seed: 0
variants: [constrained]
"""


def rt_drake(*args: str) -> None:
    """Run the ``rt-drake`` command with ``args`` in this Python; fail if it does."""
    subprocess.run([sys.executable, "-m", "rt_drake.cli", *args], check=True)


def main(out: str = "campaign_example") -> None:
    """Write :data:`CAMPAIGN` into ``out``, run it locally, report on it."""
    directory = Path(out)
    directory.mkdir(parents=True, exist_ok=True)
    campaign = directory / "campaign.yaml"
    campaign.write_text(CAMPAIGN)
    database = directory / "campaign.db"
    report = directory / "report"
    # One worker process: the local executor (no Ray), resumable by rerunning.
    rt_drake("experiment", "campaign", str(campaign), "--out", str(database),
             "--executor", "local", "--workers", "1")  # fmt: skip
    rt_drake("experiment", "report", str(database), "--out", str(report))

    with sqlite3.connect(database) as connection:
        rows = connection.execute(
            "SELECT object, cup, variant, status, duration_s, success,"
            " slip_translation_mm, error FROM rollouts ORDER BY cup"
        ).fetchall()
    for obj, cup, variant, status, duration, success, slip, error in rows:
        if status == "ok":
            outcome = (
                f"duration {duration:.3f} s, held {bool(success)}, slip {slip:.2f} mm"
            )
        else:
            outcome = f"error {error}"
        print(f"row: {obj} {cup} {variant} {status}: {outcome}")

    summary = json.loads((report / "summary.json").read_text())
    for group in summary["groups"]:
        counts = group["variants"]["constrained"]
        print(f"held: {group['cup']} {counts['held']}/{counts['ran']}")
    print(f"report: {report}")


if __name__ == "__main__":
    main(*sys.argv[1:2])
