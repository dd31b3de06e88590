"""rt-drake constraint: compute a cup's grasp-stability constraint F w <= g.

Writes an .npz with F (rows, 6), g (rows,), vertices (count, 6),
parameter_names, parameters and format_version, for wrenches
w = [torque; force] (N*m, N) that the cup exerts on the object, about and
in the cup frame C (+z out of the cup into the object).

The cup comes from --scenario FILE (its cup entry) or the paper's defaults;
explicit flags override either. The exact set is cached on disk (in
$RT_DRAKE_CACHE_DIR, default ~/.cache/rt_drake). With --approximate N the
file holds instead the guided inner approximation of at most N vertices,
built from wrenches of a --guide-mass kg object hanging below the cup,
tilted up to 90 degrees and accelerated up to --guide-acceleration m/s^2,
and also covered, samples and exact_rows.

The exact set's memory and time are estimated first (it grows steeply with
--points and --sides); above --max-memory the command refuses with the
estimate and the largest accepted values. --out is checked before any work
and written atomically.
"""

from __future__ import annotations

import argparse
import dataclasses
import time
from pathlib import Path

from rt_drake.cli._args import (
    finite_float,
    nonnegative_float,
    nonnegative_int,
    positive_float,
)
from rt_drake.cli._output import output_file
from rt_drake.contact.exact_cost import DEFAULT_MAX_MEMORY
from rt_drake.errors import InputError

#: Command-line flag -> CupParameters field (ranges: CupParameters.validate).
_CUP_FLAGS = {
    "radius": ("--radius", finite_float, "radius of the circle of contact points, m"),
    "points": ("--points", int, "number of contact points on the rim"),
    "friction": ("--friction", finite_float, "friction coefficient mu"),
    "sides": ("--sides", int, "sides of the linearised friction cone"),
    "suction_force": ("--suction-force", finite_float, "suction force P A, N"),
    "max_normal_force": (
        "--max-normal-force",
        finite_float,
        "normal force bound per point, N",
    ),
}
#: An estimated computation longer than this (s) is announced first.
_ANNOUNCE_S = 10.0


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``constraint`` subcommand."""
    parser = subparsers.add_parser(
        "constraint",
        help="compute a suction cup's contact wrench polytope F w <= g",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument("--scenario", help="take the cup from this scenario file")
    for field, (flag, kind, text) in _CUP_FLAGS.items():
        parser.add_argument(flag, dest=field, type=kind, help=text)
    parser.add_argument("--out", type=Path, required=True, help="output file (.npz)")
    parser.add_argument(
        "--approximate",
        type=int,
        metavar="N",
        help="write the guided approximation with at most N vertices (>= 7)",
    )
    parser.add_argument(
        "--guide-mass", type=positive_float, default=0.5, help="guiding object mass, kg"
    )
    parser.add_argument(
        "--guide-acceleration",
        type=nonnegative_float,
        default=5.0,
        help="largest guiding acceleration, m/s^2",
    )
    parser.add_argument("--samples", type=int, default=2000, help="guiding samples")
    parser.add_argument("--seed", type=nonnegative_int, default=0, help="random seed")
    parser.add_argument(
        "--no-cache", action="store_true", help="do not read or write the cache"
    )
    parser.add_argument(
        "--max-memory",
        type=positive_float,
        default=DEFAULT_MAX_MEMORY / 2**30,
        metavar="GB",
        help="refuse an exact set estimated to need more memory "
        f"(default {DEFAULT_MAX_MEMORY / 2**30:g} GB)",
    )
    parser.set_defaults(run=run)


def _cup(args: argparse.Namespace, scenario: Path | None):
    """Return the cup of ``--scenario`` (or the defaults) with flags applied."""
    from rt_drake.contact import CupParameters

    cup = CupParameters()
    if scenario is not None:
        from rt_drake.model.scenario import load_scenario

        cup = load_scenario(scenario).single_cup("rt-drake constraint")
    overrides = {
        f: getattr(args, f) for f in _CUP_FLAGS if getattr(args, f) is not None
    }
    return dataclasses.replace(cup, **overrides)  # validates


def run(args: argparse.Namespace) -> int:
    """Compute the constraint, write ``args.out`` and return 0."""
    from rt_drake.contact import (
        cached_wrench_polytope,
        guided_approximation,
        object_wrench_sampler,
        save_polytope,
    )
    from rt_drake.contact.approximation import MAX_SAMPLES, MAX_VERTICES
    from rt_drake.contact.exact_cost import check_exact_cost

    for flag, value, low, high in (
        ("--approximate", args.approximate, 7, MAX_VERTICES),
        ("--samples", args.samples, 1, MAX_SAMPLES),
    ):
        if value is not None and not low <= value <= high:
            raise InputError(f"{flag} must be in [{low}, {high}], got {value}")
    scenario = None
    if args.scenario is not None:
        from rt_drake.model.resources import resolve_scenario_path

        scenario = resolve_scenario_path(args.scenario)
    output_file(args.out, "--out", ".npz", {"scenario file": scenario})
    cup = _cup(args, scenario)
    max_memory = args.max_memory * 2**30
    cost = check_exact_cost(cup, max_memory)
    if cost.seconds > _ANNOUNCE_S:
        print(
            f"exact W_c: estimated {cost.seconds:.0f} s and "
            f"{cost.memory / 2**30:.2g} GB for {cup.points} points, {cup.sides} sides"
        )
    start = time.perf_counter()
    exact = cached_wrench_polytope(
        cup, use_cache=not args.no_cache, max_memory=max_memory
    )
    seconds = time.perf_counter() - start
    print(
        f"exact W_c: {len(exact.F)} rows, {len(exact.vertices)} vertices, "
        f"{seconds:.2f} s ({cup})"
    )
    if args.approximate is None:
        save_polytope(args.out, exact)
    else:
        sampler = object_wrench_sampler(
            mass=args.guide_mass,
            max_acceleration=args.guide_acceleration,
            seed=args.seed,
        )
        start = time.perf_counter()
        approx = guided_approximation(
            exact, sampler, args.approximate, seed=args.seed, sample_count=args.samples
        )
        seconds = time.perf_counter() - start
        print(
            f"approximation: {len(approx.F)} rows, {len(approx.vertices)} vertices, "
            f"covers {approx.covered}/{approx.samples} realizable guiding samples "
            f"({approx.fraction:.1%}; {approx.rejected} outside W_c), {seconds:.2f} s"
        )
        approx_set = dataclasses.replace(
            exact, F=approx.F, g=approx.g, vertices=approx.vertices
        )
        save_polytope(
            args.out,
            approx_set,
            covered=approx.covered,
            samples=approx.samples,
            exact_rows=len(exact.F),
        )
    print(f"wrote {args.out}")
    return 0
