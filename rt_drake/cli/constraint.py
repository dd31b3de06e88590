"""``rt-drake constraint``: compute a cup's grasp-stability constraint F w <= g.

Writes an ``.npz`` with ``F`` (rows, 6), ``g`` (rows,), ``vertices``
(count, 6), ``parameter_names``, ``parameters`` and ``format_version``, for
wrenches ``w = [torque; force]`` (N*m, N) that the cup exerts on the object,
about and in the cup frame C (+z out of the cup into the object).

The cup comes from ``--scenario FILE`` (its ``cup`` entry) or the paper's
defaults; explicit flags override either. The exact set is cached (see
``rt_drake.contact.cache``). With ``--approximate N`` the file holds instead
the guided inner approximation of at most N vertices, built from wrenches of
a ``--guide-mass`` kg object hanging below the cup, tilted up to 90 degrees
and accelerated up to ``--guide-acceleration`` m/s^2
(``rt_drake.contact.samplers.object_wrench_sampler``), and also ``covered``,
``samples`` and ``exact_rows``.
"""

from __future__ import annotations

import argparse
import dataclasses
import time
from pathlib import Path

from rt_drake.errors import InputError

#: Command-line flag -> CupParameters field.
_CUP_FLAGS = {
    "radius": ("--radius", float, "radius of the circle of contact points, m"),
    "points": ("--points", int, "number of contact points on the rim"),
    "friction": ("--friction", float, "friction coefficient mu"),
    "sides": ("--sides", int, "sides of the linearised friction cone"),
    "suction_force": ("--suction-force", float, "suction force P A, N"),
    "max_normal_force": (
        "--max-normal-force",
        float,
        "normal force bound per point, N",
    ),
}


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
        "--guide-mass", type=float, default=0.5, help="guiding object mass, kg"
    )
    parser.add_argument(
        "--guide-acceleration",
        type=float,
        default=5.0,
        help="largest guiding acceleration, m/s^2",
    )
    parser.add_argument("--samples", type=int, default=2000, help="guiding samples")
    parser.add_argument("--seed", type=int, default=0, help="random seed")
    parser.add_argument(
        "--no-cache", action="store_true", help="do not read or write the cache"
    )
    parser.set_defaults(run=run)


def _cup(args: argparse.Namespace):
    """Return the cup of ``--scenario`` (or the defaults) with flags applied."""
    from rt_drake.contact import CupParameters

    cup = CupParameters()
    if args.scenario is not None:
        from rt_drake.resources import resolve_scenario_path
        from rt_drake.scenario import load_scenario

        cup = load_scenario(resolve_scenario_path(args.scenario)).cup
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

    cup = _cup(args)
    if args.out.suffix != ".npz":
        raise InputError(f"--out must end in .npz, got '{args.out}'")
    if args.approximate is not None and args.approximate < 7:
        raise InputError(f"--approximate must be >= 7, got {args.approximate}")
    start = time.perf_counter()
    exact = cached_wrench_polytope(cup, use_cache=not args.no_cache)
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
