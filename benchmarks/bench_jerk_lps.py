"""The jerk-limited retime's LPs on Table I's MOVEs: HiGHS runs, iterations, CPU.

Run: ``PYTHONPATH=. nice python benchmarks/bench_jerk_lps.py [--n 20] [--seed 0]``.

The MOVEs and limits are :mod:`bench_jerk`'s (Table I's, shipped jerk
limits, 100 grid points). Each MOVE is retimed once untimed, then
``--repeats`` times with ``WarmLP.solve`` (one LP: its cutting-plane
sub-LPs) and ``WarmLP._run`` (one HiGHS ``run``) wrapped by thread-CPU
timers (``time.thread_time``; the machine is shared). Printed, for the first
LP of each retime (from the crash basis at TOPP-RA's profile) and for the
later ones (warm-started): HiGHS runs per LP, simplex iterations per LP,
the median CPU ms of an LP and the CPU ms per retime in them and in their
HiGHS runs; and the fits ``ms of a run = fixed + per iteration x
iterations`` and ``fixed + per row x rows of its model + per iteration x
iterations`` over all runs.
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import time  # noqa: E402

import numpy as np  # noqa: E402
from bench_jerk import jerk_bench  # noqa: E402

from rt_drake.retiming import _jerk_lp, retime  # noqa: E402

_SOLVE = _jerk_lp.WarmLP.solve
_RUN = _jerk_lp.WarmLP._run
#: Per LP: (index in its retime, HiGHS runs, iterations, CPU ms, CPU ms in runs).
LPS: list[tuple[int, int, int, float, float]] = []
#: Per HiGHS run: (CPU ms, iterations, rows of its model).
RUNS: list[tuple[float, int, int]] = []
_CURRENT = {"runs": 0, "ms": 0.0}


def solve(self, *args, **kwargs):  # noqa: ANN001, ANN002, ANN003, ANN201
    """``WarmLP.solve``, recording its runs, iterations and CPU in LPS."""
    index = getattr(self, "_bench_index", 0)
    self._bench_index = index + 1
    _CURRENT.update(runs=0, ms=0.0)
    iterations, start = self.iterations, time.thread_time()
    try:
        return _SOLVE(self, *args, **kwargs)
    finally:
        LPS.append(
            (
                index,
                _CURRENT["runs"],
                self.iterations - iterations,
                1e3 * (time.thread_time() - start),
                _CURRENT["ms"],
            )
        )


def run(self):  # noqa: ANN001, ANN201
    """``WarmLP._run``, recording its CPU and iterations in RUNS."""
    iterations, start = self.iterations, time.thread_time()
    try:
        return _RUN(self)
    finally:
        ms = 1e3 * (time.thread_time() - start)
        _CURRENT["runs"] += 1
        _CURRENT["ms"] += ms
        RUNS.append((ms, self.iterations - iterations, self._highs.getNumRow()))


def main() -> None:
    """Print the first and the later LPs' runs, iterations and CPU."""
    bench = jerk_bench(__doc__.splitlines()[0])
    args, plant, context = bench.args, bench.plant, bench.context
    shipped, moves = bench.shipped, bench.moves
    _jerk_lp.WarmLP.solve = solve  # type: ignore[method-assign]
    _jerk_lp.WarmLP._run = run  # type: ignore[method-assign]
    for path, grasp in moves:  # not counted
        retime(plant, path, shipped, grasp, 100, context=context)
    LPS.clear()
    RUNS.clear()
    retimes = 0
    for path, grasp in moves:
        for _ in range(args.repeats):
            retime(plant, path, shipped, grasp, 100, context=context)
            retimes += 1
    lps = np.array(LPS, dtype=float)
    print(f"{len(moves)} MOVEs x {args.repeats}: {retimes} jerk-limited retimes")
    for name, chosen in (("first LP", lps[:, 0] == 0), ("later LPs", lps[:, 0] > 0)):
        part = lps[chosen]
        print(
            f"  {name:9s}: {len(part)} LPs, HiGHS runs per LP {part[:, 1].mean():.2f}, "
            f"iterations per LP {part[:, 2].mean():.1f}, CPU ms per LP median "
            f"{np.median(part[:, 3]):.2f}; per retime {part[:, 3].sum() / retimes:.1f}"
            f" ms, of which HiGHS runs {part[:, 4].sum() / retimes:.1f}"
        )
    runs = np.array(RUNS, dtype=float)
    slope, fixed = np.polyfit(runs[:, 1], runs[:, 0], 1)
    print(
        f"  a HiGHS run: {fixed:.2f} ms + {1e3 * slope:.1f} us per simplex iteration"
        f" (fit over {len(runs)} runs); runs per retime {len(runs) / retimes:.1f}"
    )
    design = np.column_stack([np.ones(len(runs)), runs[:, 2], runs[:, 1]])
    fit = np.linalg.lstsq(design, runs[:, 0], rcond=None)[0]
    print(
        f"  with the model's rows: {fit[0]:.2f} ms + {1e3 * fit[1]:.2f} us per row "
        f"+ {1e3 * fit[2]:.1f} us per iteration; rows per run median "
        f"{np.median(runs[:, 2]):.0f}, iterations per run median "
        f"{np.median(runs[:, 1]):.0f}"
    )


if __name__ == "__main__":
    main()
