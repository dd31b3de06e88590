"""The jerk retime's first LP on other LP backends, side by side.

Run: ``PYTHONPATH=. nice python benchmarks/bench_jerk_backends.py [--n 20] [--seed 0]``.

The MOVEs and limits are :mod:`bench_jerk`'s (Table I's, shipped jerk
limits, 100 grid points). Each MOVE's first LP (linearised at TOPP-RA's
profile) is taken from a jerk-limited retime as the retimer hands it to
``WarmLP.solve`` and solved, CPU timed by ``time.thread_time`` (the machine
is shared), ``--repeats`` times each:

- ``WarmLP``: as the retimer does (HiGHS dual simplex from the crash basis
  at TOPP-RA's profile, rows as cutting planes);
- HiGHS dual simplex on the whole LP (every row), cold;
- HiGHS's interior point (IPX) on the whole LP, no crossover;
- Clarabel (interior point, through Drake's ``ClarabelSolver``) on the whole
  LP, the program's construction included.

Printed per backend: the median CPU ms over the MOVEs' medians, the MOVEs
it solved, and the largest relative difference of its objective from
``WarmLP``'s.
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import time  # noqa: E402

import highspy  # noqa: E402
import numpy as np  # noqa: E402
from bench_jerk import jerk_bench  # noqa: E402
from pydrake.solvers import ClarabelSolver, MathematicalProgram  # noqa: E402
from scipy import sparse  # noqa: E402

from rt_drake.retiming import _jerk_lp, retime  # noqa: E402

_GUESS, _SOLVE = _jerk_lp.WarmLP.guess, _jerk_lp.WarmLP.solve
#: (guess, arguments of WarmLP.solve) of each retime's first LP.
FIRST: list[tuple[np.ndarray, tuple]] = []


def guess(self, z):  # noqa: ANN001, ANN201
    """``WarmLP.guess``, keeping the guess for the recorded first LP."""
    self._bench_guess = np.array(z)
    return _GUESS(self, z)


def solve(self, *args):  # noqa: ANN001, ANN002, ANN201
    """``WarmLP.solve``, recording the first LP of each WarmLP."""
    if not getattr(self, "_bench_seen", False):
        self._bench_seen = True
        FIRST.append((self._bench_guess, args))
    return _SOLVE(self, *args)


def warm(start: np.ndarray, args: tuple) -> tuple[float, float | None]:
    """CPU ms and objective of the retimer's own solve."""
    begin = time.thread_time()
    lp = _jerk_lp.WarmLP()
    lp.guess(start)
    z, _ = _SOLVE(lp, *args)
    ms = 1e3 * (time.thread_time() - begin)
    return ms, None if z is None else float(args[0] @ z)


def whole_highs(args: tuple, options: dict) -> tuple[float, float | None]:
    """CPU ms and objective of HiGHS on every row at once."""
    c, A, b, _, A_eq, b_eq, bounds, _ = args
    begin = time.thread_time()
    highs = highspy.Highs()
    highs.setOptionValue("output_flag", False)
    highs.setOptionValue("presolve", "off")
    for key, value in options.items():
        highs.setOptionValue(key, value)
    M = sparse.vstack([A, A_eq]).tocsr()
    n = A.shape[1]
    highs.passModel(
        n, M.shape[0], M.nnz, int(highspy.MatrixFormat.kRowwise),
        int(highspy.ObjSense.kMinimize), 0.0, np.asarray(c, dtype=float),
        bounds[:, 0].astype(float), bounds[:, 1].astype(float),
        np.concatenate([np.full(len(b), -np.inf), b_eq]),
        np.concatenate([b, b_eq]), M.indptr.astype(np.int32),
        M.indices.astype(np.int32), M.data.astype(float), np.zeros(n, np.int32),
    )  # fmt: skip
    highs.run()
    ms = 1e3 * (time.thread_time() - begin)
    if highs.getModelStatus() != highspy.HighsModelStatus.kOptimal:
        return ms, None
    return ms, float(c @ np.asarray(highs.getSolution().col_value))


def clarabel(args: tuple) -> tuple[float, float | None]:
    """CPU ms and objective of Clarabel (Drake) on every row at once."""
    c, A, b, _, A_eq, b_eq, bounds, _ = args
    begin = time.thread_time()
    prog = MathematicalProgram()
    z = prog.NewContinuousVariables(A.shape[1])
    prog.AddLinearCost(c, 0.0, z)
    prog.AddLinearConstraint(A, np.full(len(b), -np.inf), b, z)
    prog.AddLinearEqualityConstraint(A_eq, b_eq, z)
    prog.AddBoundingBoxConstraint(bounds[:, 0], bounds[:, 1], z)
    result = ClarabelSolver().Solve(prog)
    ms = 1e3 * (time.thread_time() - begin)
    return ms, float(c @ result.GetSolution(z)) if result.is_success() else None


def main() -> None:
    """Print each backend's CPU on the first LPs and its objective's agreement."""
    bench = jerk_bench(__doc__.splitlines()[0])
    args, plant, context = bench.args, bench.plant, bench.context
    shipped, moves = bench.shipped, bench.moves
    _jerk_lp.WarmLP.guess = guess  # type: ignore[method-assign]
    _jerk_lp.WarmLP.solve = solve  # type: ignore[method-assign]
    for path, grasp in moves:
        retime(plant, path, shipped, grasp, 100, context=context)
    _jerk_lp.WarmLP.guess, _jerk_lp.WarmLP.solve = _GUESS, _SOLVE
    backends = {
        "WarmLP (the retimer's)": warm,
        "HiGHS simplex, every row, cold": lambda s, a: whole_highs(a, {}),
        "HiGHS IPX, every row, no crossover": lambda s, a: whole_highs(
            a, {"solver": "ipm", "run_crossover": "off"}
        ),
        "Clarabel (Drake), every row": lambda s, a: clarabel(a),
    }
    rows = [a[1].shape[0] for _, a in FIRST]
    print(
        f"{len(FIRST)} first LPs: {np.median(rows):.0f} inequality rows (median), "
        f"{FIRST[0][1][1].shape[1]} columns (first MOVE)"
    )
    reference = [warm(s, a)[1] for s, a in FIRST]
    for name, run in backends.items():
        medians, gaps, solved = [], [], 0
        for (start, lp_args), ref in zip(FIRST, reference, strict=True):
            runs = [run(start, lp_args) for _ in range(args.repeats)]
            medians.append(float(np.median([ms for ms, _ in runs])))
            value = runs[-1][1]
            if value is not None and ref is not None:
                solved += 1
                gaps.append(abs(value - ref) / max(abs(ref), 1e-300))
        gap = f"{max(gaps):.1e}" if gaps else "-"
        print(
            f"  {name:36s} {np.median(medians):6.1f} ms; solved {solved}/"
            f"{len(FIRST)}; objective vs WarmLP's, largest relative gap {gap}"
        )


if __name__ == "__main__":
    main()
