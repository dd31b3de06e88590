"""CPU time of the cycle's first pick plan (on its critical path), with jerk limits.

Run: ``PYTHONPATH=. nice python benchmarks/bench_jerk_first_plan.py [--repeats 4]``.

``rt-drake run`` (``stack_four_objects``, jerk limits on, as by default)
cannot move before the first object's APPROACH and REACH are planned and
retimed: that plan is the cycle's "plan on critical path" (the later
objects' plans overlap the motion). Here the same OnlineMotions (grasp
constraint on, seed 0, the scenario's MOVE shaping setting) plans them
``--repeats`` times, each with a new OnlineMotions, and prints the CPU time
of the planning thread (``time.thread_time``; the machine is shared) and
the wall time; the first repeat warms the caches (numba, polytopes) and is
left out of the median.

OpenBLAS is made single-threaded (unless OPENBLAS_NUM_THREADS is set).
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse  # noqa: E402
import statistics  # noqa: E402
import time  # noqa: E402

from rt_drake.model.resources import resolve_scenario_path  # noqa: E402
from rt_drake.model.scenario import load_scenario  # noqa: E402
from rt_drake.simulation import OnlineMotions  # noqa: E402


def main() -> None:
    """Print the CPU and wall time of each repeat, then the medians."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenario", nargs="?", default="stack_four_objects")
    parser.add_argument("--repeats", type=int, default=4)
    args = parser.parse_args()
    scenario = load_scenario(resolve_scenario_path(args.scenario))
    obj = scenario.objects[0]
    cpu, wall = [], []
    for repeat in range(args.repeats):
        motions = OnlineMotions(
            scenario, grasp_constraint=True, seed=0, optimize=None, jerk_limits=True
        )
        start_cpu, start_wall = time.thread_time(), time.perf_counter()
        approach = motions.approach(motions.q_home, obj)
        motions.reach(approach.q_end, obj)
        spent, waited = time.thread_time() - start_cpu, time.perf_counter() - start_wall
        print(
            f"repeat {repeat}: APPROACH + REACH plan CPU {spent:.3f} s, "
            f"wall {waited:.3f} s"
        )
        if repeat:
            cpu.append(spent)
            wall.append(waited)
    print(
        f"median over repeats 1..{args.repeats - 1}: CPU "
        f"{statistics.median(cpu):.3f} s, wall {statistics.median(wall):.3f} s"
    )


if __name__ == "__main__":
    main()
