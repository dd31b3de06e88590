"""Soundness and tightness of the robust grasp on the benchmark's MOVE paths.

Run: ``PYTHONPATH=. python benchmarks/bench_robust.py [--random 200]``.

For each MOVE path of ``bench_retime.py`` (the notebook, 100 grid points),
retime for every object of the set ``{mass: 0.2, com: [0.01, 0.01, 0.005],
inertia: 0.2}`` (with the scenario's cup, and with the cup's friction and
suction known only down to 0.25 and 18 N), then:

- sound: at 1 kHz, the wrench of each object of a dense sample (the set's
  corners and ``--random`` uniform draws, bodies only) by another route than the
  retimer's (Drake's body accelerations and Newton-Euler,
  :func:`rt_drake.dynamics.newton_euler.reference_object_wrenches`), against the
  exact wrench sets of the cups at both ends of the suction range: the
  largest ``max_k F_k w / g_k - 1`` (the retimer's contract: <= 1e-3);
- tight: the robust duration over the duration retimed with every object of
  the sample stacked (a lower bound of the robust optimum: target <= 1.03);
- the nominal plan's worst excess for the same objects.
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse  # noqa: E402
import dataclasses  # noqa: E402

import numpy as np  # noqa: E402
from bench_retime import move_paths  # noqa: E402

from rt_drake.contact import cached_wrench_polytope  # noqa: E402
from rt_drake.dynamics.cup_frame import CupFrame  # noqa: E402
from rt_drake.dynamics.newton_euler import reference_object_wrenches  # noqa: E402
from rt_drake.model.plant import make_arm_plant  # noqa: E402
from rt_drake.model.resources import scenarios_dir  # noqa: E402
from rt_drake.model.scenario import load_scenario  # noqa: E402
from rt_drake.retiming import GraspConstraint, JointLimits, retime  # noqa: E402
from rt_drake.retiming.stage_rows import (
    normalised_rows,
    wrench_ratios,
)  # noqa: E402
from rt_drake.types.object_uncertainty import ObjectUncertainty  # noqa: E402
from rt_drake.uncertainty.object_samples import (
    ObjectInertia,
    corners,
    random_objects,
)

UNCERTAINTY = ObjectUncertainty(mass=0.2, com=[0.01, 0.01, 0.005], inertia=0.2)


def worst_excess(plant, trajectory, objects, polytopes) -> float:
    """Largest ``max_k F_k w / g_k - 1`` over the objects, samples and sets."""
    times = np.append(np.arange(0.0, trajectory.duration, 1e-3), trajectory.duration)
    q, v, vdot = trajectory.sample(times, order=2)
    wrenches = reference_object_wrenches(
        plant, objects, CupFrame.of(plant), q, v, vdot
    ).reshape(-1, 6)
    return max(
        float(wrench_ratios(wrenches, normalised_rows(F, g), g, np.inf)[0].max()) - 1.0
        for F, g in polytopes
    )


def main() -> None:
    """Print one row per path and cup."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--paths", type=int, default=5)
    parser.add_argument("--random", type=int, default=200)
    args = parser.parse_args()
    scenario = load_scenario(scenarios_dir() / "stack_four_objects.yaml")
    plant = make_arm_plant(scenario)
    limits = JointLimits.from_plant(plant, scenario.robot)
    obj = dataclasses.replace(scenario.object("notebook"), uncertainty=UNCERTAINTY)
    X_OC = obj.grasp.GetDeterministicValue()
    model = ObjectInertia.of_model(obj)
    sample = corners(model, UNCERTAINTY) + random_objects(
        model, UNCERTAINTY, args.random, np.random.default_rng(0)
    )
    held = [o.held(X_OC) for o in sample]
    cups = {
        "known cup": scenario.cup,
        "friction >= 0.25, suction >= 18 N": dataclasses.replace(
            scenario.cup, friction_min=0.25, suction_force_min=18.0
        ),
    }
    print(
        f"{len(held)} objects ({len(held) - args.random} corners, {args.random} "
        "random), 1 kHz, independent wrench route"
    )
    print(
        f"{'path':>4s} {'cup':36s} {'nominal s':>9s} {'robust s':>9s} "
        f"{'bound s':>9s} {'tight':>7s} {'robust excess':>14s} {'nominal excess':>15s}"
    )
    for index, path in enumerate(move_paths(args.paths)):
        for label, cup in cups.items():
            robust = GraspConstraint.for_scenario_object(obj, cup)
            nominal = GraspConstraint.for_cup(robust.held, cup)
            # The exact sets at both ends of the suction range, lowest friction.
            ends = [
                cached_wrench_polytope(
                    dataclasses.replace(cup.worst_case(), suction_force=force)
                )
                for force in (cup.worst_case().suction_force, cup.suction_force)
            ]
            polytopes = [(p.F, p.g) for p in ends]
            r_robust = retime(plant, path, limits, robust)
            r_nominal = retime(plant, path, limits, nominal)
            stacked = GraspConstraint.for_objects(held, cup)
            r_bound = retime(plant, path, limits, stacked)
            print(
                f"{index:4d} {label:36s} {r_nominal.duration:9.3f} "
                f"{r_robust.duration:9.3f} {r_bound.duration:9.3f} "
                f"{r_robust.duration / r_bound.duration:7.4f} "
                f"{worst_excess(plant, r_robust.trajectory, held, polytopes):+14.2e} "
                f"{worst_excess(plant, r_nominal.trajectory, held, polytopes):+15.3f}"
            )


if __name__ == "__main__":
    main()
