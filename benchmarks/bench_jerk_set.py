"""Jerk limits with the grasp of a set of objects: duration, CPU, every object held.

Run: ``PYTHONPATH=.:benchmarks nice python benchmarks/bench_jerk_set.py [--paths 5]``.

On bench_retime's MOVE-like paths (lift, swing, set down), the notebook of
``stack_four_objects_paper`` with the uncertainty set ``{mass: 0.2, com:
[0.01, 0.01, 0.005], inertia: 0.2}`` (as ``bench_robust.py``), jerk limits
of 20 x the acceleration limits per second. For each path:

- the robust retime with and without jerk limits, and the nominal object's
  jerk-limited retime: durations, and the CPU time of the retiming thread
  (``time.thread_time``; the machine is shared) of the two robust ones,
  interleaved, ``--repeats`` times, median;
- the worst grasp excess ``max_k (F_k w - g_k) / g_k`` over the set's
  corners and ``--random`` objects drawn from it, at 1 kHz, by another route
  than the retimer's (Drake's body accelerations and Newton-Euler), for
  the robust and the nominal jerk-limited plans;
- the jerk from third differences of the 1 kHz positions over its limit.

OpenBLAS is made single-threaded (unless OPENBLAS_NUM_THREADS is set).
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse  # noqa: E402
import dataclasses  # noqa: E402
import statistics  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402
from bench_retime import move_paths  # noqa: E402

from rt_drake.contact import cached_wrench_polytope  # noqa: E402
from rt_drake.dynamics.cup_frame import CupFrame  # noqa: E402
from rt_drake.dynamics.newton_euler import reference_object_wrenches  # noqa: E402
from rt_drake.model.plant import make_arm_plant  # noqa: E402
from rt_drake.model.resources import scenarios_dir  # noqa: E402
from rt_drake.model.scenario import load_scenario  # noqa: E402
from rt_drake.retiming import GraspConstraint, JointLimits, retime  # noqa: E402
from rt_drake.retiming._check import _sample  # noqa: E402
from rt_drake.retiming.stage_rows import normalised_rows, wrench_ratios  # noqa: E402
from rt_drake.types.object_uncertainty import ObjectUncertainty  # noqa: E402
from rt_drake.uncertainty.object_samples import (  # noqa: E402
    ObjectInertia,
    corners,
    random_objects,
)

SET = ObjectUncertainty(mass=0.2, com=[0.01, 0.01, 0.005], inertia=0.2)


def worst_excess(plant, trajectory, objects, cup) -> float:
    """Largest ``(F_k w - g_k) / g_k`` over the objects and 1 kHz samples."""
    t0, t1 = trajectory.start_time(), trajectory.end_time()
    times = np.append(np.arange(t0, t1, 1e-3), t1)
    q, v, vdot = _sample(trajectory, times)
    wrenches = reference_object_wrenches(plant, objects, CupFrame.of(plant), q, v, vdot)
    polytope = cached_wrench_polytope(cup)
    rows = normalised_rows(polytope.F, polytope.g)
    ratio = wrench_ratios(wrenches.reshape(-1, 6), rows, polytope.g, np.inf)[0]
    return float(ratio.max()) - 1.0


def difference_jerk(trajectory, jerk: np.ndarray) -> float:
    """Largest |q'''| / limit from third differences of q at 1 kHz."""
    step = 1e-3
    t = step * np.arange(int(trajectory.end_time() / step) + 1)
    q = trajectory.sample(t, order=0)[0]
    return float(np.max(np.abs(np.diff(q, 3, axis=0)) / step**3 / jerk))


def main() -> None:
    """Print one line per path, then the summary."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--paths", type=int, default=5)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--random", type=int, default=100)
    args = parser.parse_args()
    scenario = load_scenario(scenarios_dir() / "stack_four_objects_paper.yaml")
    plant = make_arm_plant(scenario)
    context = plant.CreateDefaultContext()
    notebook = dataclasses.replace(scenario.object("notebook"), uncertainty=SET)
    plain = JointLimits.from_plant(plant, scenario.robot)
    jerk = JointLimits(plain.velocity, plain.acceleration, jerk=20 * plain.acceleration)
    assert jerk.jerk is not None
    robust = GraspConstraint.for_scenario_object(notebook, scenario.cup)
    nominal = GraspConstraint.for_cup(robust.held, scenario.cup)
    model = ObjectInertia.of_model(notebook)
    X_OC = notebook.grasp.GetDeterministicValue()
    drawn = random_objects(model, SET, args.random, np.random.default_rng(4))
    objects = [o.held(X_OC) for o in corners(model, SET) + drawn]
    print(f"{len(objects)} objects of the set checked (corners and draws)")
    ratios, cpu_ratio, excesses, nominal_excess, jerks = [], [], [], [], []
    for index, path in enumerate(move_paths(args.paths)):
        limited = retime(plant, path, jerk, robust, context=context)
        free = retime(plant, path, plain, robust, context=context)
        alone = retime(plant, path, jerk, nominal, context=context)
        cpu: dict[str, list[float]] = {"jerk": [], "plain": []}
        for _ in range(args.repeats):
            for name, limits in (("plain", plain), ("jerk", jerk)):
                start = time.thread_time()
                retime(plant, path, limits, robust, context=context)
                cpu[name].append(1e3 * (time.thread_time() - start))
        excess = worst_excess(plant, limited.trajectory, objects, scenario.cup)
        dropped = worst_excess(plant, alone.trajectory, objects, scenario.cup)
        over = difference_jerk(limited.trajectory, jerk.jerk)
        ratios.append(limited.duration / free.duration)
        cpu_jerk, cpu_plain = (statistics.median(cpu[k]) for k in ("jerk", "plain"))
        cpu_ratio.append(cpu_jerk / cpu_plain)
        excesses.append(excess)
        nominal_excess.append(dropped)
        jerks.append(over)
        print(
            f"path {index}: robust {free.duration:.3f} s -> jerk-limited "
            f"{limited.duration:.3f} s (x{ratios[-1]:.3f}, {limited.jerk_lps} LPs, "
            f"{limited.grasp_rows} (point, row, object) rows); nominal jerk-limited "
            f"{alone.duration:.3f} s; CPU ms {cpu_plain:.1f} -> {cpu_jerk:.1f}; "
            f"worst excess robust "
            f"{excess:+.5f}, nominal {dropped:+.3f}; third-difference jerk / limit "
            f"{over:.5f}"
        )
    print(
        f"\nrobust jerk-limited / robust acceleration-limited duration: median "
        f"{statistics.median(ratios):.3f} [{min(ratios):.3f}, {max(ratios):.3f}]; "
        f"CPU ratio median {statistics.median(cpu_ratio):.1f}; worst excess over the "
        f"set at 1 kHz {max(excesses):+.5f} (nominal plans: {min(nominal_excess):+.3f}"
        f" to {max(nominal_excess):+.3f}); worst third-difference jerk / limit "
        f"{max(jerks):.5f}"
    )


if __name__ == "__main__":
    main()
