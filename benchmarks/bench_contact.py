"""Time the exact contact wrench set and the guided approximation.

    python benchmarks/bench_contact.py [--repeats N] [--cdd]
    python benchmarks/bench_contact.py --tools [--repeats N] [--max-facets K]

Exact W_c for the paper's cup (m = 6) and for m = 8 (cache disabled: the
enumeration itself), median of N runs; then the guided approximation with 50
vertices from 2000 guiding samples of ``object_wrench_sampler``. With
``--cdd``, also the straightforward reference: pycddlib's facet enumeration
from the (already pruned) vertices, for m = 6 (tens of seconds).

With ``--tools``, instead: the exact tool set W_T (cache disabled) for tools
of the paper's cup (r = 0.0125 m, 6 points, mu = 0.3, 4 sides, 20 N suction,
33.3 N per point): 1 cup at T's origin, 2 cups 0.12 m apart, 4 cups at the
corners of a 0.12 x 0.08 m rectangle, median of N runs; a walk that finds
more than K facets is stopped (its count and time are printed, once). Then
guided inner approximations for the 2- and 4-cup tools from 2000 guiding
samples of a 1.8 kg carton (CoM 0.05 m below T), with their coverage.
"""

from __future__ import annotations

import argparse
import statistics
import time
from collections.abc import Callable

import numpy as np

from rt_drake.contact import (
    CupMount,
    CupParameters,
    ToolParameters,
    ToolWrenchSet,
    TooManyFacetsError,
    contact_wrench_polytope,
    guided_approximation,
    object_wrench_sampler,
    tool_wrench_polytope,
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


def _tools() -> dict[str, ToolParameters]:
    """The benchmark's tools, of the paper's cup, with T on the contact plane."""
    cup = CupParameters()
    return {
        "1 cup": ToolParameters.single(cup),
        "2 cups, 0.12 m apart": ToolParameters(
            cups=[CupMount(cup, p_TC=[x, 0.0, 0.0]) for x in (0.06, -0.06)]
        ),
        "4 cups, 0.12 x 0.08 m rectangle": ToolParameters(
            cups=[
                CupMount(cup, p_TC=[x, y, 0.0])
                for x in (0.06, -0.06)
                for y in (0.04, -0.04)
            ]
        ),
    }


def _bench_tools(repeats: int, max_facets: int) -> None:
    print(f"exact W_T (minimal H-rep + vertices), cache disabled, median of {repeats}")
    exact = {}
    for name, tool in _tools().items():
        try:
            seconds, polytope = _median_seconds(
                lambda tool=tool: tool_wrench_polytope(tool, max_facets), repeats
            )
        except TooManyFacetsError as error:
            print(
                f"  {name}: stopped, more than {max_facets} facets "
                f"({error.found} found in {error.seconds:.0f} s)"
            )
            continue
        exact[name] = polytope
        print(
            f"  {name}: {len(polytope.F)} rows, {len(polytope.vertices)} vertices, "
            f"median {seconds:.2f} s"
        )
    samples = object_wrench_sampler(mass=1.8, p_CoOcm_C=(0.0, 0.0, 0.05), seed=0)(2000)
    for name, tool in list(_tools().items())[1:]:
        sources = [("support + LP", ToolWrenchSet(tool))]
        if name in exact:
            sources.insert(0, ("exact", exact[name]))
        for source, polytope in sources:
            for vertices in (50, 100):
                start = time.perf_counter()
                approx = guided_approximation(polytope, samples, vertices, seed=0)
                seconds = time.perf_counter() - start
                print(
                    f"guided approximation of {name} from the {source} set, "
                    f"max {vertices} vertices: {len(approx.F)} rows, "
                    f"{len(approx.vertices)} vertices, covers "
                    f"{approx.covered}/{approx.samples} realizable samples "
                    f"({approx.fraction:.1%}; {approx.rejected} not realizable), "
                    f"{seconds:.1f} s"
                )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--cdd", action="store_true", help="also time pycddlib")
    parser.add_argument("--tools", action="store_true", help="multi-cup tools")
    parser.add_argument("--max-facets", type=int, default=200_000)
    args = parser.parse_args()
    if args.tools:
        _bench_tools(args.repeats, args.max_facets)
        return
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
