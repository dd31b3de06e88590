"""``rt-drake experiment transport|cycle``: the paper's experiments in simulation.

``transport``: Table I. Random start and goal poses of one object, each MOVE
retimed with and without the grasp constraint and played in the cycle's
physics, plus a speed sweep to the slip. Writes ``results.json``,
``report.md`` and PNG plots. With ``--robust``: each MOVE retimed for the
nominal object and for every object of its uncertainty set, both played with
a true object drawn from the set's hardest corners.

``cycle``: Table II. The four-object cycle with its timing breakdown (as
``rt-drake run``), into ``report.json``, ``report.md`` and ``replay.html``.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from rt_drake.cli._args import positive_int


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``experiment`` subcommand and its two experiments."""
    parser = subparsers.add_parser(
        "experiment",
        help="reproduce the paper's experiments in simulation",
        description=__doc__,
    )
    which = parser.add_subparsers(dest="experiment", required=True)

    transport = which.add_parser(
        "transport", help="Table I: random transports, with and without the constraint"
    )
    transport.add_argument(
        "--scenario",
        default="random_transport",
        help="scenario with a random_transport section",
    )
    transport.add_argument(
        "--n", type=positive_int, default=20, help="number of random paths (default 20)"
    )
    transport.add_argument(
        "--seed", type=int, default=0, help="sampling and planning seed (default 0)"
    )
    transport.add_argument(
        "--object", default=None, help="object to carry (default: the scenario's)"
    )
    transport.add_argument(
        "--workers", type=positive_int, default=1, help="parallel processes (default 1)"
    )
    transport.add_argument(
        "--robust",
        action="store_true",
        help="nominal vs robust plans, played with true objects from the object's "
        "uncertainty set",
    )
    transport.add_argument("--out", type=Path, required=True, help="output directory")
    transport.set_defaults(run=run_transport)

    cycle = which.add_parser(
        "cycle", help="Table II: the four-object cycle's timing breakdown"
    )
    cycle.add_argument(
        "--scenario",
        default="stack_four_objects",
        help="scenario (default stack_four_objects)",
    )
    cycle.add_argument("--out", type=Path, required=True, help="output directory")
    cycle.set_defaults(run=run_cycle_experiment)


def run_transport(args: argparse.Namespace) -> int:
    """Run the transport experiment and write its outputs; return 0."""
    import time

    from rt_drake.experiments import (
        run_transport_experiment,
        transport_table,
        write_transport_report,
    )
    from rt_drake.resources import resolve_scenario_path

    if args.robust:
        return run_robust_transport(args)
    start = time.perf_counter()
    results = run_transport_experiment(
        resolve_scenario_path(args.scenario),
        n=args.n,
        seed=args.seed,
        object_name=args.object,
        workers=args.workers,
    )
    results["wall_s"] = time.perf_counter() - start
    written = write_transport_report(results, args.out)
    s = results["summary"]
    print(transport_table(results))
    print(
        f"with the constraint {s['success_constrained']}/{s['n']} succeed, without "
        f"{s['success_unconstrained']}/{s['n']}; critical speed factors "
        f"{s['critical_speed_factors']}; {results['wall_s']:.0f} s"
    )
    print("wrote " + ", ".join(str(p) for p in written))
    return 0


def run_robust_transport(args: argparse.Namespace) -> int:
    """The robust transport experiment: write its outputs; return 0."""
    import time

    from rt_drake.experiments import (
        robust_table,
        run_robust_transport_experiment,
        write_robust_report,
    )
    from rt_drake.experiments.robust_report import summary_lines
    from rt_drake.resources import resolve_scenario_path

    start = time.perf_counter()
    results = run_robust_transport_experiment(
        resolve_scenario_path(args.scenario),
        n=args.n,
        seed=args.seed,
        object_name=args.object,
        workers=args.workers,
    )
    results["wall_s"] = time.perf_counter() - start
    written = write_robust_report(results, args.out)
    print(robust_table(results))
    print("\n".join(summary_lines(results)))
    print(f"{results['wall_s']:.0f} s; wrote " + ", ".join(str(p) for p in written))
    return 0


def run_cycle_experiment(args: argparse.Namespace) -> int:
    """The four-object cycle via ``rt-drake run``; return its exit code."""
    from rt_drake.cli import run as run_command

    namespace = argparse.Namespace(
        scenario=args.scenario,
        out=args.out,
        meshcat=False,
        no_grasp_constraint=False,
        speed=1.0,
        seed=0,
        time_step=1e-3,
    )
    return run_command.run(namespace)
