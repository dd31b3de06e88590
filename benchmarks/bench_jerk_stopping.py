"""The jerk-limited retime's sequence of LPs stopped earlier, or started wider.

Run: ``PYTHONPATH=. nice python benchmarks/bench_jerk_stopping.py [--n 20] [--seed 0]``.

The MOVEs and limits are :mod:`bench_jerk`'s (Table I's, shipped jerk
limits, 100 grid points). Each variant sets constants of
:mod:`rt_drake.retiming._jerk` for its retimes:

- ``CONVERGED``: the change of the duration that ends a round's LPs;
- ``MAX_LPS``: a round's LPs at most (1: every LP is followed by the check
  at the dense points);
- ``FIRST_DENSE`` / ``FIRST_JERK``: the points of each segment in the first
  round's LPs (the ends, the middle too, or all of them: the points a later
  round would add, entered at once).

Per MOVE, the variants are timed interleaved (``time.thread_time``, the
machine is shared), ``--repeats`` times, with one acceleration-limited retime
per repeat; printed per variant: the median CPU ms of a jerk-limited retime
and its ratio to the acceleration-limited median, the LPs and rounds over
the MOVEs, each MOVE's duration over the default's (median, min, max), and
how many MOVEs hold every limit at 1 kHz within 1e-3 (``check_trajectory``
and third differences of the positions, as ``bench_jerk.py``'s (c)).
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import time  # noqa: E402

import numpy as np  # noqa: E402
from bench_jerk import jerk_bench, third_difference_jerk  # noqa: E402

from rt_drake.retiming import (  # noqa: E402
    JointLimits,
    _jerk,
    _solve,
    check_trajectory,
    retime,
)

#: (name, constants of _jerk) per variant; the first is the default.
VARIANTS = [
    ("default", {}),
    ("CONVERGED 3e-3", {"CONVERGED": 3e-3}),
    ("CONVERGED 1e-2", {"CONVERGED": 1e-2}),
    ("CONVERGED 3e-2", {"CONVERGED": 3e-2}),
    ("MAX_LPS 1", {"MAX_LPS": 1}),
    ("MAX_LPS 2", {"MAX_LPS": 2}),
    ("first LPs: jerk also mid-segment", {"FIRST_JERK": (0, 16, 32)}),
    ("first LPs: every jerk point", {"FIRST_JERK": tuple(range(33))}),
    ("first LPs: every dense point", {"FIRST_DENSE": tuple(range(9))}),
]
#: Rounds of the last jerk-limited retime (read off its JerkProfile).
ROUNDS: list[int] = []
_RESULT = _solve.jerk_result


def jerk_result(jerk, *args):  # noqa: ANN001, ANN002, ANN201
    """``jerk_result``, recording the profile's rounds in ROUNDS."""
    ROUNDS.append(jerk.rounds)
    return _RESULT(jerk, *args)


def main() -> None:
    """Print each variant's CPU, LPs, rounds, durations and limits held."""
    bench = jerk_bench(__doc__.splitlines()[0])
    args, plant, context = bench.args, bench.plant, bench.context
    shipped, moves = bench.shipped, bench.moves
    plain = JointLimits.from_plant(plant, bench.scenario.robot)
    assert shipped.jerk is not None
    _solve.jerk_result = jerk_result
    defaults = {key: getattr(_jerk, key) for _, values in VARIANTS for key in values}

    def use(values: dict) -> None:
        for key, default in defaults.items():
            setattr(_jerk, key, values.get(key, default))

    count, m = len(VARIANTS), len(moves)
    cpu = np.zeros((count, m, args.repeats))
    plain_cpu = np.zeros((m, args.repeats))
    duration, lps, rounds = (np.zeros((count, m)) for _ in range(3))
    held = np.zeros(count, dtype=int)
    for j, (path, grasp) in enumerate(moves):
        for i, (_, values) in enumerate(VARIANTS):
            use(values)
            result = retime(plant, path, shipped, grasp, 100, context=context)
            duration[i, j], lps[i, j], rounds[i, j] = (
                result.duration,
                result.jerk_lps,
                ROUNDS[-1],
            )
            check = check_trajectory(plant, result.trajectory, shipped, grasp)
            third = np.max(third_difference_jerk(result.trajectory) / shipped.jerk)
            held[i] += bool(check.passed()) and third <= 1.0 + 1e-3
        for r in range(args.repeats):
            start = time.thread_time()
            retime(plant, path, plain, grasp, 100, context=context)
            plain_cpu[j, r] = 1e3 * (time.thread_time() - start)
            for i, (_, values) in enumerate(VARIANTS):
                use(values)
                start = time.thread_time()
                retime(plant, path, shipped, grasp, 100, context=context)
                cpu[i, j, r] = 1e3 * (time.thread_time() - start)
    use({})
    base = float(np.median(plain_cpu))
    print(
        f"{m} MOVEs x {args.repeats}: acceleration-limited retime median {base:.1f} ms"
    )
    for i, (name, _) in enumerate(VARIANTS):
        ratio = duration[i] / duration[0]
        jerk = float(np.median(cpu[i]))
        print(
            f"  {name:34s} {jerk:6.1f} ms ({jerk / base:4.1f}x); "
            f"LPs {lps[i].sum():4.0f}, rounds {rounds[i].sum():3.0f}; "
            "duration / default median "
            f"{np.median(ratio):.6f} [{ratio.min():.6f}, {ratio.max():.6f}]; "
            f"{held[i]}/{m} hold at 1 kHz"
        )


if __name__ == "__main__":
    main()
