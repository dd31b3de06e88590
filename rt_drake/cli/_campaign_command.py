"""rt-drake experiment campaign|report: validation campaigns at scale.

campaign CAMPAIGN.yaml --out DB: every (object, cup, trial, variant) row of
the campaign, run locally (--executor local, --workers N processes) or on
Ray (--executor ray, --ray-address to join a cluster), committed one by one
into the SQLite file DB. The same command resumes an interrupted campaign.
Exit code 0 when every row is in the database (failed rows included:
failures are data), 130 on Ctrl-C.

report DB --out DIR: summary tables (summary.md, .csv, .json) and plots
from the database.

Both are subcommands of rt-drake experiment.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from rt_drake.cli._args import int_in

#: Most local processes or Ray CPUs one command may ask for.
MAX_WORKERS = 64

#: Exit code after Ctrl-C (128 + SIGINT), as shells report it.
EXIT_INTERRUPTED = 130


def register(which: argparse._SubParsersAction) -> None:
    """Add ``campaign`` and ``report`` to the ``experiment`` subcommands."""
    campaign = which.add_parser(
        "campaign",
        help="a validation campaign: objects x cups x trials x variants, into SQLite",
        description=__doc__,
    )
    campaign.add_argument("campaign", type=Path, help="campaign file (YAML)")
    campaign.add_argument(
        "--out", type=Path, required=True, help="results database (SQLite file)"
    )
    campaign.add_argument(
        "--executor",
        choices=("local", "ray"),
        default="local",
        help="where rows run: local processes (default) or Ray",
    )
    campaign.add_argument(
        "--workers",
        type=int_in(1, MAX_WORKERS),
        default=None,
        help="local processes, or CPUs of a Ray started here "
        f"(default: all CPUs, at most {MAX_WORKERS})",
    )
    campaign.add_argument(
        "--ray-address",
        default=None,
        help="join this Ray cluster (e.g. auto, or ray://head:10001) instead of "
        "starting Ray here",
    )
    campaign.add_argument(
        "--retry-failed",
        action="store_true",
        help="compute the error and crashed rows again (infeasible rows are kept)",
    )
    campaign.set_defaults(run=run_campaign_command)

    report = which.add_parser(
        "report", help="summary tables and plots of a campaign database"
    )
    report.add_argument("database", type=Path, help="results database (SQLite file)")
    report.add_argument("--out", type=Path, required=True, help="output directory")
    report.set_defaults(run=run_report_command)


def run_campaign_command(args: argparse.Namespace) -> int:
    """Run (or resume) the campaign; return 0, or 130 if interrupted."""
    from rt_drake.errors import InputError
    from rt_drake.experiments.campaign import (
        ExecutorKind,
        load_campaign,
        make_executor,
        run_campaign,
    )

    kind = ExecutorKind(args.executor)
    if args.ray_address is not None and kind is not ExecutorKind.RAY:
        raise InputError("a Ray address is only used by the ray executor")
    campaign = load_campaign(args.campaign)
    executor = make_executor(kind, workers=args.workers, address=args.ray_address)
    try:
        run = run_campaign(campaign, args.out, executor, retry_failed=args.retry_failed)
    except KeyboardInterrupt:
        print(
            f"interrupted: every finished row is in {args.out}; run the same "
            "command to resume",
            file=sys.stderr,
        )
        return EXIT_INTERRUPTED
    print(
        f"{run.total} rows in {args.out} ({run.resumed} resumed, {run.computed} "
        f"computed, {run.failed} failed); {run.wall_s:.0f} s"
    )
    return 0


def run_report_command(args: argparse.Namespace) -> int:
    """Write the report of a campaign database; return 0."""
    from rt_drake.experiments.campaign import write_campaign_report

    written = write_campaign_report(args.database, args.out)
    print(written[1].read_text())
    print("wrote " + ", ".join(str(p) for p in written))
    return 0
