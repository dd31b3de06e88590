"""The jerk-limited retime's LP step, replayed: variants of it and HiGHS's floor.

Run: ``PYTHONPATH=. nice python benchmarks/bench_jerk_replay.py [--n 20] [--seed 0]
[--repeats 6] [--check]``.

Every LP of the jerk-limited retimes of :mod:`bench_jerk`'s MOVEs (Table
I's, shipped jerk limits, 100 grid points) is captured once: the
arguments of ``WarmLP.guess`` and ``WarmLP.solve`` and the optimum. Each
retime's sequence of LPs is then replayed (the same LPs, whatever the
variant returns) through:

- ``shipped``: :class:`rt_drake.retiming._jerk_lp.WarmLP` as the retimer runs it
  (the compiled dual simplex, :class:`rt_drake.retiming._band_lp.BandLP`,
  HiGHS where it gives no answer);
- ``highs``: ``WarmLP(compiled=False)``, HiGHS alone with its cutting planes
  (the LP step before session 8);
- ``dantzig``, ``unscaled``, ``one-thread``: ``highs`` with one HiGHS option
  changed (Dantzig pricing, no scaling, ``threads`` 1);
- ``knot-pairs``: ``highs`` where a jerk row cut at one side of a knot brings
  the same joint's row on the other side and at the neighbouring knots'
  sides, and the first sub-LP takes the other side of every jerk row it
  takes (:class:`KnotPairs`);

interleaved per MOVE in a rotating order, ``--repeats`` times, CPU by
``time.process_time`` (the machine is shared: ratios, not milliseconds).
Printed per variant: the median over MOVEs of its CPU in the LP step over
``shipped``'s in the same repeat, HiGHS runs and simplex iterations over
the MOVEs (``shipped``: its own iterations, and HiGHS's runs where it fell
back), and the largest difference of an optimum from the captured one
(relative to ``max(1, |z|)``).

``--check``: each captured LP solved once more by ``shipped`` and by
``scipy.optimize.linprog(method="highs")`` with feasibility tolerances of
1e-10 (every row, not cutting planes): the largest relative difference of
the optimal values and the largest excess of a row or bound of
``shipped``'s optimum (relative to ``max(1, |bound|)``).

Then HiGHS's floor on the solved model of every captured LP (median ms):
``run`` again with nothing changed (no iteration), ``passModel`` +
``setBasis`` + ``run`` from the optimal basis (what a warm LP costs before
its first iteration), and a model kept instead: its jerk rows deleted and
added again, the costs changed, ``setBasis`` + ``run``.
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import statistics  # noqa: E402
import time  # noqa: E402
from collections.abc import Callable  # noqa: E402

import highspy as _highspy  # noqa: E402
import numpy as np  # noqa: E402
from bench_jerk import jerk_bench  # noqa: E402
from scipy.optimize import linprog  # noqa: E402

from rt_drake.retiming import _jerk_lp, retime  # noqa: E402
from rt_drake.retiming._jerk_problem import Kind  # noqa: E402
from rt_drake.retiming._jerk_rows import KIND_SHIFT  # noqa: E402

#: One retime's LPs: ("guess", z) or ("solve", arguments, optimum).
Trace = list[tuple]
#: Jerk-point indices of a knot's other side and of the neighbouring knots'
#: sides (33 jerk points per segment: the end of one segment, index 32, and
#: the start of the next, index 33, lie at the same s).
KNOT_OFFSETS = (-1, 1, -32, -33, -34, 32, 33, 34)
_JERK = (int(Kind.JERK), int(Kind.JERK) + 1)


def _with_neighbours(keys: np.ndarray, rows: np.ndarray, offsets) -> np.ndarray:  # noqa: ANN001
    """Rows whose keys are those of ``rows``' jerk rows with the point shifted."""
    jerk = rows[np.isin(keys[rows] >> KIND_SHIFT, _JERK)]
    if not jerk.size:
        return np.zeros(0, dtype=int)
    ordered = np.argsort(keys)
    sorted_keys = keys[ordered]
    wanted = np.concatenate([keys[jerk] + (d << 24) for d in offsets])
    at = np.minimum(np.searchsorted(sorted_keys, wanted), len(keys) - 1)
    return ordered[at[sorted_keys[at] == wanted]]


class KnotPairs(_jerk_lp.WarmLP):
    """HiGHS's WarmLP whose jerk cuts bring their knot's other side and neighbours."""

    def __init__(self) -> None:  # noqa: D107
        super().__init__(compiled=False)

    def solve(self, c, A_ub, b_ub, keys, A_eq, b_eq, bounds, always):  # noqa: ANN001, ANN201, D102
        # The rows WarmLP.solve's first sub-LP takes, and their jerk pairs.
        taken = always.copy()
        if self._start is not None:
            near = _jerk_lp.GUESS if self._keys is None else _jerk_lp.WARM_GUESS
            slack = near * np.maximum(1.0, np.abs(b_ub))
            taken |= _jerk_lp._product(A_ub, self._start) >= b_ub - slack
        if self._keys is not None:
            taken |= _jerk_lp._member(keys, self._keys[self._rows != 1])
        taken[_with_neighbours(keys, np.flatnonzero(taken), (-1, 1))] = True
        return super().solve(c, A_ub, b_ub, keys, A_eq, b_eq, bounds, taken)

    def _cuts(self, working, value, b_ub, slack, keys):  # noqa: ANN001, ANN201
        broken = super()._cuts(working, value, b_ub, slack, keys)
        more = _with_neighbours(keys, broken, KNOT_OFFSETS)
        return np.union1d(broken, more[~working[more]])


def with_option(name: str, value: object) -> Callable[[], _jerk_lp.WarmLP]:
    """A WarmLP factory with one HiGHS option changed."""

    def make() -> _jerk_lp.WarmLP:
        solver = _jerk_lp.WarmLP(compiled=False)
        solver._highs.setOptionValue(name, value)
        return solver

    return make


VARIANTS: dict[str, Callable[[], _jerk_lp.WarmLP]] = {
    "shipped": _jerk_lp.WarmLP,
    "highs": lambda: _jerk_lp.WarmLP(compiled=False),
    "dantzig": with_option("simplex_dual_edge_weight_strategy", 0),
    "unscaled": with_option("simplex_scale_strategy", 0),
    "one-thread": with_option("threads", 1),
    "knot-pairs": KnotPairs,
}


def capture(bench) -> list[Trace]:  # noqa: ANN001
    """Every WarmLP's calls in the jerk-limited retimes of the MOVEs."""
    traces: list[Trace] = []
    cls = _jerk_lp.WarmLP
    init, solve = cls.__init__, cls.solve
    guess = cls.guess

    def started(self):  # noqa: ANN001, ANN202
        init(self)
        self._trace = []
        traces.append(self._trace)

    def guessed(self, z):  # noqa: ANN001, ANN202
        self._trace.append(("guess", np.array(z)))
        return guess(self, z)

    def solved(self, *args):  # noqa: ANN002, ANN202
        z, status = solve(self, *args)
        self._trace.append(("solve", args, None if z is None else z.copy()))
        return z, status

    cls.__init__, cls.guess, cls.solve = started, guessed, solved  # type: ignore[method-assign]
    try:
        for path, grasp in bench.moves:
            retime(bench.plant, path, bench.shipped, grasp, 100, context=bench.context)
    finally:
        cls.__init__, cls.guess, cls.solve = init, guess, solve  # type: ignore[method-assign]
    return traces


def replay(make: Callable[[], _jerk_lp.WarmLP], trace: Trace) -> tuple[float, ...]:
    """CPU s, HiGHS runs, iterations and the largest difference from the optima."""
    start = time.process_time()
    solver = make()
    worst = 0.0
    band = solver._band
    for item in trace:
        if item[0] == "guess":
            solver.guess(item[1])
            continue
        z, _ = solver.solve(*item[1])
        ref = item[2]
        apart = np.abs(z - ref) / np.maximum(1.0, np.abs(ref))
        worst = max(worst, float(np.max(apart)))
    seconds = time.process_time() - start
    iterations = solver.iterations + (0 if band is None else band.iterations)
    return seconds, solver.solves, iterations, worst


def check(traces: list[Trace]) -> tuple[float, float, int]:
    """Largest relative difference from scipy's optimal value, largest excess."""
    gap = excess = 0.0
    fallbacks = 0
    for trace in traces:
        solver = _jerk_lp.WarmLP()
        for item in trace:
            if item[0] == "guess":
                solver.guess(item[1])
                continue
            c, A_ub, b_ub, keys, A_eq, b_eq, bounds, always = item[1]
            before = solver.fallbacks
            z, _ = solver.solve(*item[1])
            A_ub = A_ub.tocsr()  # scipy's, for linprog (a RowMatrix from solve_lp)
            fallbacks += solver.fallbacks - before
            reference = linprog(
                c, A_ub=A_ub, b_ub=b_ub, A_eq=A_eq, b_eq=b_eq,
                bounds=list(map(tuple, bounds)), method="highs",
                options={
                    "primal_feasibility_tolerance": 1e-10,
                    "dual_feasibility_tolerance": 1e-10,
                },
            )  # fmt: skip
            assert reference.status == 0, reference.message
            gap = max(gap, abs(c @ z - reference.fun) / max(1.0, abs(reference.fun)))
            over = [
                (A_ub @ z - b_ub) / np.maximum(1.0, np.abs(b_ub)),
                np.abs(A_eq @ z - b_eq) / np.maximum(1.0, np.abs(b_eq)),
            ]
            for side, sign in ((0, -1.0), (1, 1.0)):
                finite = np.isfinite(bounds[:, side])
                limit = bounds[finite, side]
                over.append(sign * (z[finite] - limit) / np.maximum(1.0, np.abs(limit)))
            excess = max(excess, max(float(np.max(o)) for o in over if o.size))
    return gap, excess, fallbacks


def floor(traces: list[Trace], repeats: int) -> dict[str, list[float]]:
    """HiGHS's ms on each captured LP's solved model (module docstring)."""
    out: dict[str, list[float]] = {"run again": [], "passModel": [], "kept": []}
    for trace in traces:
        solver = _jerk_lp.WarmLP(compiled=False)
        for item in trace:
            if item[0] == "guess":
                solver.guess(item[1])
                continue
            solver.solve(*item[1])
            for name, ms in _floor_of(solver, repeats).items():
                out[name].append(ms)
    return out


def _timed(function: Callable[[], object], repeats: int) -> float:
    """Median CPU ms of ``function()`` over ``repeats`` calls."""
    times = []
    for _ in range(repeats):
        start = time.process_time()
        function()
        times.append(1e3 * (time.process_time() - start))
    return statistics.median(times)


def _floor_of(solver: _jerk_lp.WarmLP, repeats: int) -> dict[str, float]:
    """The floor's three timings on the solver's solved model (module docstring)."""
    highs = solver._highs
    lp, basis = highs.getLp(), highs.getBasis()
    out = {"run again": _timed(highs.run, repeats)}

    def passed() -> None:
        highs.passModel(lp)
        highs.setBasis(basis)
        highs.run()

    out["passModel"] = _timed(passed, repeats)
    highs.passModel(lp)  # the model as solved, rows in its order
    jerk = np.flatnonzero(np.isin(_model_keys(solver) >> KIND_SHIFT, _JERK))
    if not jerk.size:
        return out
    jerk = jerk.astype(np.int32)
    _, start, index, value = highs.getRowsEntries(len(jerk), jerk)
    entries = (np.asarray(start), np.asarray(index), np.asarray(value))
    lower = np.asarray(lp.row_lower_)[jerk]
    upper = np.asarray(lp.row_upper_)[jerk]
    cost = np.asarray(lp.col_cost_)
    columns = np.arange(len(cost), dtype=np.int32)
    moved = _highspy.HighsBasis()  # the rows' statuses with the jerk rows last
    statuses = list(basis.row_status)
    others = np.setdiff1d(np.arange(len(statuses)), jerk)
    moved.col_status = basis.col_status
    moved.row_status = [statuses[i] for i in np.concatenate([others, jerk])]
    last = np.arange(highs.getNumRow() - len(jerk), highs.getNumRow(), dtype=np.int32)

    def kept(rows: np.ndarray) -> None:
        """The jerk rows ``rows`` deleted and added again (last), the basis set."""
        highs.deleteRows(len(rows), rows)
        highs.addRows(len(rows), lower, upper, len(entries[1]), *entries)
        highs.changeColsCost(len(cost), columns, cost)
        highs.setBasis(moved)
        highs.run()

    kept(jerk)  # untimed: the jerk rows moved to the end
    out["kept"] = _timed(lambda: kept(last), repeats)
    return out


def _model_keys(solver: _jerk_lp.WarmLP) -> np.ndarray:
    """Keys of the rows of HiGHS's model in its order (equality rows: -1)."""
    assert solver._keys is not None
    head = solver._head
    eq = np.full(solver._highs.getNumRow() - len(solver._keys), -1, dtype=np.int64)
    return np.concatenate([solver._keys[:head], eq, solver._keys[head:]])


def main() -> None:
    """Print the variants' CPU, runs, iterations and optima, then the floor."""
    bench = jerk_bench(__doc__.splitlines()[0], check=True)
    traces = capture(bench)
    if bench.args.check:
        gap, excess, fallbacks = check(traces)
        print(
            f"{sum(len(t) - 1 for t in traces)} LPs against scipy's HiGHS (tolerances "
            f"1e-10): largest relative difference of the optimal value {gap:.1e}, "
            f"largest relative excess of a row or bound {excess:.1e}; the "
            f"compiled solver fell back to HiGHS on {fallbacks} LPs"
        )
        return
    names = list(VARIANTS)
    ratios: dict[str, list[float]] = {name: [] for name in names}
    shipped_ms: list[float] = []
    runs = dict.fromkeys(names, 0)
    iterations = dict.fromkeys(names, 0)
    worst = dict.fromkeys(names, 0.0)
    for trace in traces:  # once untimed: HiGHS and the compiled kernels warm
        replay(_jerk_lp.WarmLP, trace)
    for repeat in range(bench.args.repeats):
        for index, trace in enumerate(traces):
            turn = (repeat + index) % len(names)
            cpu = {}
            for name in names[turn:] + names[:turn]:
                seconds, solves, steps, apart = replay(VARIANTS[name], trace)
                cpu[name] = seconds
                worst[name] = max(worst[name], apart)
                if repeat == 0:
                    runs[name] += solves
                    iterations[name] += steps
            shipped_ms.append(1e3 * cpu["shipped"])
            for name in names:
                ratios[name].append(cpu[name] / cpu["shipped"])
    print(
        f"{len(traces)} retimes, {sum(len(t) - 1 for t in traces)} LPs; the LP "
        f"step of shipped: median {statistics.median(shipped_ms):.1f} ms CPU "
        "per retime"
    )
    print("variant     CPU / shipped (median)  HiGHS runs  iterations  max |dz|")
    for name in names:
        print(
            f"{name:11s} {statistics.median(ratios[name]):22.3f}  {runs[name]:10d}  "
            f"{iterations[name]:10d}  {worst[name]:.1e}"
        )
    print("\nHiGHS's floor on each solved model, median ms over the LPs:")
    for name, values in floor(traces, 3).items():
        print(f"  {name:10s} {statistics.median(values):.3f} ({len(values)} LPs)")


if __name__ == "__main__":
    main()
