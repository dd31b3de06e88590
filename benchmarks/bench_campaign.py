"""Campaign throughput: the local executor and Ray side by side, and Ray's overhead.

One small campaign (the notebook and the kindle box, the paper's cup,
``--trials`` transports each, the ``constrained`` variant: one physics
rollout per row) is run into a fresh database by the local executor
(``--workers`` processes) and then by the Ray executor (a Ray instance
started here with ``--workers`` CPUs). Reported per executor: wall time
from the call to the last row (worker start-up and shared inputs included),
rollouts per minute over that wall time, the mean wall and CPU time of a row
in its worker, and the share of the workers' time spent outside rows
(start-up: spawning, imports, shared inputs; then waiting for the last rows).
Ray is started before both runs (``--ray-first`` runs its campaign first).

Then the per-task overhead: the round trip of a trivial task (submit, run,
get the result), one at a time, through Ray and through a local process
pool; and the amortised cost per trivial task when ``--burst`` of them are
in flight at once.

Run: ``OPENBLAS_NUM_THREADS=1 python benchmarks/bench_campaign.py``
(``--trials N``, ``--workers N``).
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import time
import warnings
from concurrent.futures import ProcessPoolExecutor
from multiprocessing import get_context
from pathlib import Path

try:
    import rt_drake  # noqa: F401
except ImportError:  # a source checkout without `pip install -e .`
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from rt_drake.experiments.campaign import (  # noqa: E402
    ExecutorKind,
    load_campaign,
    make_executor,
    run_campaign,
)
from rt_drake.experiments.campaign._report import read_rows  # noqa: E402
from rt_drake.experiments.campaign._row_types import Status  # noqa: E402

CAMPAIGN = """\
scenario: random_transport
objects:
- model: package://rt_drake/objects/notebook.sdf
- model: package://rt_drake/objects/kindle_box.sdf
cups:
- name: paper
trials: {trials}
seed: 0
variants: [constrained]
"""


def noop(x: int) -> int:
    """A trivial task."""
    return x


def run(kind: ExecutorKind, path: Path, out: Path, workers: int) -> dict[str, float]:
    """Run the campaign into a fresh database; wall time and row statistics."""
    campaign = load_campaign(path)
    start = time.perf_counter()
    result = run_campaign(campaign, out, make_executor(kind, workers=workers))
    wall = time.perf_counter() - start
    _, rows = read_rows(out)
    assert result.computed == len(rows) and all(r["status"] is Status.OK for r in rows)
    busy = sum(r["wall_s"] for r in rows)
    return {
        "rows": len(rows),
        "wall_s": wall,
        "per_min": 60.0 * len(rows) / wall,
        "row_s": busy / len(rows),
        "cpu_s": sum(r["cpu_s"] for r in rows) / len(rows),
        "idle": 1.0 - busy / (workers * wall),
    }


def round_trips(submit_and_get, n: int) -> float:
    """Median seconds of one submit + result, ``n`` times in a row."""
    times = []
    for i in range(n):
        start = time.perf_counter()
        submit_and_get(i)
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trials", type=int, default=2)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--round-trips", type=int, default=200)
    parser.add_argument("--burst", type=int, default=1000)
    parser.add_argument(
        "--ray-first", action="store_true", help="run Ray's campaign before the local"
    )
    args = parser.parse_args()

    import ray

    results: dict[str, dict[str, float]] = {}
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "bench.yaml"
        path.write_text(CAMPAIGN.format(trials=args.trials))
        start = time.perf_counter()
        with warnings.catch_warnings():  # Ray's notices of future changes
            warnings.simplefilter("ignore", FutureWarning)
            ray.init(
                num_cpus=args.workers, include_dashboard=False, log_to_driver=False
            )
        ray_init_s = time.perf_counter() - start
        order = [ExecutorKind.LOCAL, ExecutorKind.RAY]
        for kind in reversed(order) if args.ray_first else order:
            database = Path(tmp) / f"{kind.value}.db"
            results[kind.value] = run(kind, path, database, args.workers)

        remote = ray.remote(num_cpus=1)(noop)
        ray.get([remote.remote(i) for i in range(2 * args.workers)])  # warm workers
        ray_trip = round_trips(lambda i: ray.get(remote.remote(i)), args.round_trips)
        start = time.perf_counter()
        ray.get([remote.remote(i) for i in range(args.burst)])
        ray_burst = (time.perf_counter() - start) / args.burst
        ray.shutdown()

        context = get_context("spawn")
        with ProcessPoolExecutor(args.workers, mp_context=context) as pool:
            list(pool.map(noop, range(2 * args.workers)))  # start the workers
            pool_trip = round_trips(
                lambda i: pool.submit(noop, i).result(), args.round_trips
            )
            start = time.perf_counter()
            list(pool.map(noop, range(args.burst)))
            pool_burst = (time.perf_counter() - start) / args.burst

    rows = results["local"]["rows"]
    print(f"\n{rows} rows (constrained rollouts) per executor, {args.workers} workers")
    print(
        "| executor | wall (s) | rollouts/min | mean row in its worker: wall (s) "
        "| CPU (s) | workers' time outside rows |"
    )
    print("|---|---:|---:|---:|---:|---:|")
    for name, r in sorted(results.items()):
        print(
            f"| {name} | {r['wall_s']:.1f} | {r['per_min']:.2f} | {r['row_s']:.1f} "
            f"| {r['cpu_s']:.1f} | {100 * r['idle']:.0f} % |"
        )
    print(f"\nray.init(num_cpus={args.workers}): {ray_init_s:.1f} s (not in the wall)")
    print("| trivial task | Ray | local process pool |")
    print("|---|---:|---:|")
    print(
        f"| round trip, one at a time (median of {args.round_trips}) | "
        f"{1e3 * ray_trip:.2f} ms | {1e3 * pool_trip:.2f} ms |"
    )
    print(
        f"| per task, {args.burst} in flight | {1e3 * ray_burst:.3f} ms | "
        f"{1e3 * pool_burst:.3f} ms |"
    )


if __name__ == "__main__":
    main()
