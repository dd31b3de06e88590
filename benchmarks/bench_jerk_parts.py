"""Where a jerk-limited retime's CPU goes, on Table I's MOVEs.

Run: ``PYTHONPATH=. nice python benchmarks/bench_jerk_parts.py [--n 20] [--seed 0]``.

The MOVEs and limits are :mod:`bench_jerk`'s (Table I's, shipped jerk
limits, 100 grid points). Each retime runs ``--repeats`` times with the
jerk-limited retimer's parts wrapped by thread-CPU timers
(``time.thread_time``; the machine is shared); per part, the median over
the retimes of its CPU ms per retime. The parts nest: "LPs (HiGHS)" is
inside "LP wrapper", which is inside "LP rows and LPs"; "TOPP-RA and the
rest" is the retime's CPU outside ``jerk_limited``. An acceleration-limited
retime of the same MOVE is timed before each (not a part), and the floor
of this scheme printed: TOPP-RA and the rest, HiGHS's runs and the dense
points (Drake's path coefficients), the parts that no Python around the
LPs can remove, as a multiple of the acceleration-limited retime.
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import collections  # noqa: E402
import functools  # noqa: E402
import statistics  # noqa: E402
import time  # noqa: E402

from bench_jerk import jerk_bench  # noqa: E402

from rt_drake.retiming import (  # noqa: E402
    JointLimits,
    _jerk,
    _jerk_lp,
    _jerk_points,
    _jerk_problem,
    retime,
)

#: CPU ms of each part in the current retime.
SPENT: collections.Counter = collections.Counter()


def timed(name, function):  # noqa: ANN001, ANN201
    """``function`` adding its thread CPU ms to ``SPENT[name]``."""

    @functools.wraps(function)
    def wrapper(*args, **kwargs):  # noqa: ANN002, ANN003, ANN202
        start = time.thread_time()
        try:
            return function(*args, **kwargs)
        finally:
            SPENT[name] += 1e3 * (time.thread_time() - start)

    return wrapper


def main() -> None:
    """Print the median CPU ms per part of a jerk-limited retime."""
    bench = jerk_bench(__doc__.splitlines()[0])
    args, plant, context = bench.args, bench.plant, bench.context
    shipped, moves = bench.shipped, bench.moves
    parts = {
        "jerk_limited (all but TOPP-RA)": (_jerk, "jerk_limited"),
        "LP rows and LPs (solve_lp)": (_jerk, "solve_lp"),
        "LP wrapper (WarmLP.solve)": (_jerk_lp.WarmLP, "solve"),
        "LPs (HiGHS run)": (_jerk_lp.WarmLP, "_run"),
        "LP rows per selection (_fixed_rows)": (_jerk_problem, "_fixed_rows"),
        "jerk rows per LP": (_jerk_problem, "jerk_rows"),
        "grasp screen": (_jerk_points.DensePoints, "grasp_screen"),
        "jerk ratios": (_jerk_points.JerkPoints, "per_joint"),
        "duration by quadrature": (_jerk, "quadrature_duration"),
    }
    for name, (owner, attribute) in parts.items():
        setattr(owner, attribute, timed(name, getattr(owner, attribute)))
    # The points and the path's coefficients there (Drake): static methods.
    for name, cls in (
        ("dense points", _jerk.DensePoints),
        ("jerk points", _jerk.JerkPoints),
    ):
        cls.of = staticmethod(timed(name, cls.of))
    # retime imports jerk_limited by name: wrap it there too.
    from rt_drake.retiming import _solve

    _solve.jerk_limited = _jerk.jerk_limited
    plain = JointLimits.from_plant(plant, bench.scenario.robot)
    per_part: dict[str, list[float]] = collections.defaultdict(list)
    plain_cpu: list[float] = []
    floor: list[float] = []
    for path, grasp in moves:
        retime(plant, path, shipped, grasp, 100, context=context)  # not timed
        for _ in range(args.repeats):
            start = time.thread_time()
            retime(plant, path, plain, grasp, 100, context=context)
            plain_cpu.append(1e3 * (time.thread_time() - start))
            SPENT.clear()
            start = time.thread_time()
            retime(plant, path, shipped, grasp, 100, context=context)
            total = 1e3 * (time.thread_time() - start)
            per_part["retime (total)"].append(total)
            for name in [*parts, "dense points", "jerk points"]:
                per_part[name].append(SPENT[name])
            topp = total - SPENT["jerk_limited (all but TOPP-RA)"]
            per_part["TOPP-RA and the rest"].append(topp)
            floor.append(topp + SPENT["LPs (HiGHS run)"] + SPENT["dense points"])
    print(f"{len(moves)} MOVEs x {args.repeats}: median CPU ms per jerk-limited retime")
    for name, values in per_part.items():
        print(f"  {name:36s} {statistics.median(values):6.1f}")
    accelerated = statistics.median(plain_cpu)
    total = statistics.median(per_part["retime (total)"])
    print(
        f"acceleration-limited retime {accelerated:.1f} ms; the jerk-limited one "
        f"{total / accelerated:.1f}x it (with the timers); its floor (TOPP-RA and "
        f"the rest + HiGHS runs + dense points) {statistics.median(floor):.1f} ms, "
        f"{statistics.median(floor) / accelerated:.1f}x"
    )


if __name__ == "__main__":
    main()
