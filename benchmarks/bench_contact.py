"""Time the exact contact wrench set and the guided approximation.

    python benchmarks/bench_contact.py [--repeats N] [--cdd]

Exact W_c for the paper's cup (m = 6) and for m = 8 (cache disabled: the
enumeration itself), median of N runs; then the guided approximation with 50
vertices from 2000 guiding samples of ``object_wrench_sampler``. With
``--cdd``, also the straightforward reference: pycddlib's facet enumeration
from the (already pruned) vertices, for m = 6 (tens of seconds).
"""

from __future__ import annotations

import argparse
import statistics
import time
from collections.abc import Callable

import numpy as np

from rt_drake.contact import (
    CupParameters,
    contact_wrench_polytope,
    guided_approximation,
    object_wrench_sampler,
)


def _median_seconds(
    function: Callable[[], object], repeats: int
) -> tuple[float, object]:
    times, result = [], None
    for _ in range(repeats):
        start = time.perf_counter()
        result = function()
        times.append(time.perf_counter() - start)
    return statistics.median(times), result


def _cdd_seconds(vertices: np.ndarray) -> tuple[float, int]:
    import cdd

    start = time.perf_counter()
    matrix = cdd.matrix_from_array(
        np.hstack([np.ones((len(vertices), 1)), vertices]),
        rep_type=cdd.RepType.GENERATOR,
    )
    rows = cdd.copy_inequalities(cdd.polyhedron_from_matrix(matrix)).array
    return time.perf_counter() - start, len(rows)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--cdd", action="store_true", help="also time pycddlib")
    args = parser.parse_args()
    print("exact W_c (minimal H-rep + vertices), cache disabled")
    polytopes = {}
    for points in (6, 8):
        cup = CupParameters(points=points)
        seconds, polytope = _median_seconds(
            lambda cup=cup: contact_wrench_polytope(cup), args.repeats
        )
        polytopes[points] = polytope
        print(
            f"  m={points}: {len(polytope.F)} rows, {len(polytope.vertices)} vertices, "
            f"median {seconds:.3f} s over {args.repeats}"
        )
    samples = object_wrench_sampler(mass=0.55, seed=0)(2000)
    for vertices in (20, 50):
        seconds, approx = _median_seconds(
            lambda n=vertices: guided_approximation(polytopes[6], samples, n, seed=0),
            args.repeats,
        )
        print(
            f"guided approximation (m=6, max {vertices} vertices, 2000 samples): "
            f"{len(approx.F)} rows, {len(approx.vertices)} vertices, covers "
            f"{approx.covered}/{approx.samples} ({approx.fraction:.1%}), "
            f"median {seconds:.3f} s"
        )
    if args.cdd:
        seconds, rows = _cdd_seconds(polytopes[6].vertices)
        print(f"pycddlib facets from the m=6 vertices: {rows} rows, {seconds:.1f} s")


if __name__ == "__main__":
    main()
