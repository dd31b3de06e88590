"""rt-drake experiment transport|cycle|stop|campaign|report: experiments in simulation.

transport: Table I. Random start and goal poses of one object, each MOVE
retimed with and without the grasp constraint and played in the cycle's
physics, plus a speed sweep to the slip. Writes results.json, report.md and
PNG plots. With --optimize, each trial also shapes its MOVE for speed from
the same grasp to the same goal, plays it in the same physics with its own
sweep, and the report compares both (plus optimized.png and
optimized_replay.html). With --robust: each MOVE retimed for the nominal
object and for every object of its uncertainty set, both played with a true
object drawn from the set's hardest corners.

cycle: Table II. The four-object cycle with its timing breakdown (as
rt-drake run), into report.json, report.md and replay.html.

stop: protective stops. Table I's MOVEs (random_transport_paper by
default), each stopped at a random instant and played in physics two ways:
the grasp-aware stop and the joints braking at their limits. Writes
results.json.

campaign and report: validation campaigns over many objects, cups and
transports, into SQLite (see rt-drake experiment campaign --help).
"""

from __future__ import annotations

import argparse
from collections.abc import Callable
from pathlib import Path
from typing import Any

from rt_drake.cli import _campaign_command as campaign
from rt_drake.cli._args import (
    add_cup_physics_flag,
    add_jerk_flag,
    add_optimize_flag,
    int_in,
    nonnegative_int,
)

#: Most random paths (each is planned, retimed twice and simulated ~12 times).
MAX_TRIALS = 1000
#: Most worker processes.
MAX_WORKERS = 64


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
    _add_trial_arguments(
        transport,
        "random_transport",
        "scenario with a random_transport section",
        "number of random paths",
        "sampling and planning seed (default 0)",
    )
    transport.add_argument(
        "--robust",
        action="store_true",
        help="nominal vs robust plans, played with true objects from the object's "
        "uncertainty set",
    )
    transport.add_argument(
        "--sweep",
        action="store_true",
        help="with --robust: also play each robust plan faster until the true "
        "object slips (its critical speed factor; without --robust every "
        "trial is swept)",
    )
    add_optimize_flag(transport, "also optimise each MOVE and play it")
    add_cup_physics_flag(transport)
    add_jerk_flag(transport)
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
    add_jerk_flag(cycle)
    cycle.add_argument("--out", type=Path, required=True, help="output directory")
    cycle.set_defaults(run=run_cycle_experiment)

    _register_stop(which)
    campaign.register(which)  # ``campaign`` and ``report``


def _add_trial_arguments(
    parser: argparse.ArgumentParser,
    scenario: str,
    scenario_help: str,
    n_help: str,
    seed_help: str,
) -> None:
    """Add the arguments of an experiment over random transports.

    ``--scenario``, ``--n``, ``--seed``, ``--object`` and ``--workers``.
    """
    parser.add_argument("--scenario", default=scenario, help=scenario_help)
    parser.add_argument(
        "--n",
        type=int_in(1, MAX_TRIALS),
        default=20,
        help=f"{n_help} (default 20, at most {MAX_TRIALS})",
    )
    parser.add_argument("--seed", type=nonnegative_int, default=0, help=seed_help)
    parser.add_argument(
        "--object", default=None, help="object to carry (default: the scenario's)"
    )
    parser.add_argument(
        "--workers",
        type=int_in(1, MAX_WORKERS),
        default=1,
        help=f"parallel processes (default 1, at most {MAX_WORKERS})",
    )


def _register_stop(which: argparse._SubParsersAction) -> None:
    """Add ``experiment stop``: protective stops of Table I's MOVEs in physics."""
    stop = which.add_parser(
        "stop",
        help="protective stops mid-MOVE in physics: grasp-aware vs joint brake",
    )
    _add_trial_arguments(
        stop,
        "random_transport_paper",
        "scenario with a random_transport section (default random_transport_paper)",
        "number of stopped MOVEs",
        "transports, planning and stop instants seed (default 0)",
    )
    add_jerk_flag(stop)
    stop.add_argument("--out", type=Path, required=True, help="output directory")
    stop.set_defaults(run=run_stop)


def _timed_trials(
    label: str,
    args: argparse.Namespace,
    run: Callable[[Callable[[int, int], None]], dict[str, Any]],
) -> dict[str, Any]:
    """``run(progress)``'s results, with a progress bar and their ``wall_s``.

    ``progress(done, n)`` advances the bar of ``args.n`` trials.
    """
    import time

    from rt_drake.cli._progress import Progress

    bar = Progress(label, args.n, "trial", eta=True)
    start = time.perf_counter()
    try:
        results = run(lambda done, n: bar.step(done, "trials done"))
    finally:
        bar.close()
    results["wall_s"] = time.perf_counter() - start
    return results


def run_stop(args: argparse.Namespace) -> int:
    """Run the stop experiment, write DIR/results.json, print a table; return 0."""
    import json

    from rt_drake.atomic_file import write_text_atomically
    from rt_drake.cli._output import output_directory
    from rt_drake.experiments import STOP_FILES, run_stop_experiment, stop_table
    from rt_drake.model.resources import resolve_scenario_path

    path = resolve_scenario_path(args.scenario)
    output_directory(args.out, "--out", STOP_FILES, {"scenario file": path})
    results = _timed_trials(
        "rt-drake experiment stop",
        args,
        lambda progress: run_stop_experiment(
            path,
            n=args.n,
            seed=args.seed,
            object_name=args.object,
            workers=args.workers,
            progress=progress,
            jerk_limits=not args.no_jerk_limits,
        ),
    )
    written = args.out / STOP_FILES[0]
    write_text_atomically(written, json.dumps(results, indent=1) + "\n")
    print(stop_table(results))
    print(f"{results['wall_s']:.0f} s; wrote {written}")
    return 0


def run_transport(args: argparse.Namespace) -> int:
    """Run the transport experiment and write its outputs; return 0."""
    from rt_drake.cli._output import output_directory
    from rt_drake.errors import InputError
    from rt_drake.experiments import (
        TRANSPORT_FILES,
        optimized_summary,
        run_transport_experiment,
        transport_table,
        write_transport_report,
    )
    from rt_drake.model.resources import resolve_scenario_path

    if args.robust:
        return run_robust_transport(args)
    if args.sweep:
        raise InputError(
            "--sweep is for --robust: experiment transport sweeps every trial"
        )
    path = resolve_scenario_path(args.scenario)
    output_directory(args.out, "--out", TRANSPORT_FILES, {"scenario file": path})
    results = _timed_trials(
        "rt-drake experiment transport",
        args,
        lambda progress: run_transport_experiment(
            path,
            n=args.n,
            seed=args.seed,
            object_name=args.object,
            workers=args.workers,
            optimize=args.optimize,
            out_dir=args.out,
            progress=progress,
            cup_physics=args.cup_physics,
            jerk_limits=not args.no_jerk_limits,
        ),
    )
    written = write_transport_report(results, args.out)
    s = results["summary"]
    print(transport_table(results))
    print(
        f"with the constraint {s['success_constrained']}/{s['n']} succeed, without "
        f"{s['success_unconstrained']}/{s['n']}; critical speed factors "
        f"{s['critical_speed_factors']}; {results['wall_s']:.0f} s"
    )
    if results["optimize"]:
        print(optimized_summary(s))
    print("wrote " + ", ".join(str(p) for p in written))
    return 0


def run_robust_transport(args: argparse.Namespace) -> int:
    """The robust transport experiment: write its outputs; return 0."""
    from rt_drake.cli._output import output_directory
    from rt_drake.errors import InputError
    from rt_drake.experiments import (
        ROBUST_FILES,
        robust_table,
        run_robust_transport_experiment,
        write_robust_report,
    )
    from rt_drake.experiments.robust_report import summary_lines
    from rt_drake.model.resources import resolve_scenario_path

    if args.optimize:
        raise InputError(
            "--robust plays the planner's spline MOVEs: it does not take --optimize"
        )
    path = resolve_scenario_path(args.scenario)
    output_directory(args.out, "--out", ROBUST_FILES, {"scenario file": path})
    results = _timed_trials(
        "rt-drake experiment transport --robust",
        args,
        lambda progress: run_robust_transport_experiment(
            path,
            n=args.n,
            seed=args.seed,
            object_name=args.object,
            workers=args.workers,
            progress=progress,
            cup_physics=args.cup_physics,
            jerk_limits=not args.no_jerk_limits,
            sweep=args.sweep,
        ),
    )
    written = write_robust_report(results, args.out)
    if results["trials"]:
        print(robust_table(results))
    print("\n".join(summary_lines(results)))
    print(f"{results['wall_s']:.0f} s; wrote " + ", ".join(str(p) for p in written))
    return 0


def run_cycle_experiment(args: argparse.Namespace) -> int:
    """The four-object cycle via ``rt-drake run``; return its exit code."""
    from rt_drake.cli import _run as run_command

    namespace = argparse.Namespace(
        scenario=args.scenario,
        out=args.out,
        meshcat=False,
        no_grasp_constraint=False,
        speed=1.0,
        sequential_planning=False,
        seed=0,
        time_step=1e-3,
        optimize=None,
        cup_physics=None,
        no_jerk_limits=args.no_jerk_limits,
        export=None,  # rt-drake run's --export: nothing exported here
    )
    return run_command.run(namespace)
