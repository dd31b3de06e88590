"""Jerk limits, the grasp of a set of objects and torque limits together.

Run: ``PYTHONPATH=.:benchmarks:tests nice python
benchmarks/bench_jerk_set_torque.py [--n 5] [--seed 0] [--tight 0.4]``.

The MOVEs of ``random_transport_uncertain`` (the notebook known to +-20 %
in mass and inertia, +-(10, 10, 5) mm in CoM), seed 0, planned as
``rt-drake experiment transport`` plans them, each with its own grasp of
the set. Jerk limits: ``random_transport``'s (the same VS-060, each joint
reaching its acceleration limit in 50 ms); torque limits: the URDF's
efforts (``robot.limit_torques``), and with ``--tight F`` those times F too.
For each MOVE, at 100 grid points:

- durations: jerk + set (no torques), jerk + set + torques, and the tight
  torques' (a torque refused at rest is counted, not timed);
- CPU of the retiming thread (``time.thread_time``; the machine is
  shared) of jerk + set, jerk + set + torques and the acceleration-limited
  set + torques, interleaved, ``--repeats`` times, median;
- the limits held by each torque-limited plan at 1 kHz, by routes
  independent of the retimer's rows: every joint torque of every body
  corner of the set and ``--random`` objects drawn from it by Drake's
  inverse dynamics with the object welded at the cup
  (``tests/torque_reference.py``), the grasp of the same objects by
  Newton-Euler, the jerk by third differences of the positions, the
  velocity, acceleration and position limits by ``check_trajectory``.

OpenBLAS is made single-threaded (unless OPENBLAS_NUM_THREADS is set).
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse  # noqa: E402
import dataclasses  # noqa: E402
import statistics  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402
from bench_jerk import planned_moves  # noqa: E402
from bench_jerk_set import difference_jerk, worst_excess  # noqa: E402
from pydrake.math import RigidTransform, RotationMatrix  # noqa: E402
from torque_reference import TorqueReference  # noqa: E402

from rt_drake.model.plant import make_arm_plant  # noqa: E402
from rt_drake.model.resources import scenarios_dir  # noqa: E402
from rt_drake.model.scenario import load_scenario  # noqa: E402
from rt_drake.retiming import (  # noqa: E402
    JointLimits,
    Margin,
    RetimeError,
    check_trajectory,
    retime,
    warm_up,
)
from rt_drake.retiming._check import _sample  # noqa: E402
from rt_drake.uncertainty.object_samples import (  # noqa: E402
    ObjectInertia,
    corners,
    random_objects,
)

NAME = "random_transport_uncertain"


def torque_ratio(reference, objects, trajectory, torque) -> float:
    """Largest ``|tau_j| / tau_max_j`` over the objects at 1 kHz."""
    t0, t1 = trajectory.start_time(), trajectory.end_time()
    times = np.append(np.arange(t0, t1, 1e-3), t1)
    tau = reference.torques(objects, *_sample(trajectory, times))
    return float(np.max(np.abs(tau) / torque))


def held(plant, scenario, reference, objects, result, limits) -> str:
    """Every limit of a torque-limited plan at 1 kHz, as one line."""
    trajectory = result.trajectory
    joints = dataclasses.replace(limits, torque=None)
    check = check_trajectory(plant, trajectory, joints)
    torque = torque_ratio(reference, objects, trajectory, limits.torque)
    grasp = worst_excess(plant, trajectory, objects, scenario.cup)
    return (
        f"torque/limit {torque:.5f}, grasp excess {grasp:+.5f}"
        f", jerk/limit {difference_jerk(trajectory, limits.jerk):.5f}"
        f", joints {'pass' if check.passed() else 'FAIL'}"
    )


def _objects(notebook, model, uncertainty, drawn, nominal):
    """The set's body corners and the drawn objects, held as the MOVE holds it.

    The MOVE's grasp is the scenario's ``X_OC`` or its yaw flip
    (``CyclePlanner.grasps``): the one whose nominal object is the grasp's.
    """
    X_OC = notebook.grasp.GetDeterministicValue()
    flip = RigidTransform(RotationMatrix.MakeZRotation(np.pi))
    for candidate in (X_OC, X_OC @ flip):
        if np.allclose(model.held(candidate).I_Scm_C, nominal.I_Scm_C) and np.allclose(
            model.held(candidate).p_CoScm_C, nominal.p_CoScm_C
        ):
            return [o.held(candidate) for o in corners(model, uncertainty) + drawn]
    raise AssertionError("the MOVE's grasp is neither X_OC nor its flip")


def main() -> None:
    """Print one line per MOVE, then the summary."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=5)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--random", type=int, default=20)
    parser.add_argument("--tight", type=float, default=None)
    args = parser.parse_args()
    scenario = load_scenario(scenarios_dir() / f"{NAME}.yaml")
    jerk = load_scenario(scenarios_dir() / "random_transport.yaml").robot.jerk_limits
    plant = make_arm_plant(scenario)
    context = plant.CreateDefaultContext()
    plain = JointLimits.from_plant(plant, scenario.robot, torque=True)
    assert plain.torque is not None
    torque = dataclasses.replace(plain, jerk=np.array(jerk, dtype=float))
    no_torque = dataclasses.replace(torque, torque=None)
    tight = None
    if args.tight is not None:
        tight = dataclasses.replace(torque, torque=args.tight * plain.torque)
    print(f"torque limits {plain.torque} N m; jerk limits {torque.jerk} rad/s^3")
    notebook = scenario.object("notebook")
    uncertainty = notebook.uncertainty
    assert uncertainty is not None
    model = ObjectInertia.of_model(notebook)
    drawn = random_objects(model, uncertainty, args.random, np.random.default_rng(4))
    reference = TorqueReference(scenario)
    warm_up()
    moves = planned_moves(args.n, args.seed, NAME)
    print(f"{len(moves)} MOVEs planned ({NAME}, seed {args.seed})")
    rows = []
    for index, (path, grasp) in enumerate(moves):
        assert grasp.is_robust
        objects = _objects(notebook, model, uncertainty, drawn, grasp.held)
        set_only = retime(plant, path, no_torque, grasp, context=context)
        with_torque = retime(plant, path, torque, grasp, context=context)
        cpu: dict[str, list[float]] = {"set": [], "torque": [], "acceleration": []}
        acceleration = dataclasses.replace(torque, jerk=None)
        for _ in range(args.repeats):
            for name, limits in (
                ("acceleration", acceleration),
                ("set", no_torque),
                ("torque", torque),
            ):
                start = time.thread_time()
                retime(plant, path, limits, grasp, context=context)
                cpu[name].append(1e3 * (time.thread_time() - start))
        median = {k: statistics.median(v) for k, v in cpu.items()}
        slower = with_torque.duration / set_only.duration
        line = (
            f"MOVE {index}: jerk+set {set_only.duration:.3f} s, +torque "
            f"{with_torque.duration:.3f} s (x{slower:.4f}"
            f", torque margin {float(with_torque.margins[Margin.TORQUE].min()):.3f})"
            f"; CPU ms "
            f"jerk+set {median['set']:.0f}, +torque {median['torque']:.0f}, "
            f"acceleration-limited set+torque {median['acceleration']:.0f}; "
            + held(plant, scenario, reference, objects, with_torque, torque)
        )
        row = {
            "ratio": slower,
            "cpu": median["torque"] / median["set"],
            "jerk_cost": median["torque"] / median["acceleration"],
        }
        if tight is not None:
            try:
                squeezed = retime(plant, path, tight, grasp, context=context)
            except RetimeError as error:
                line += f"\n  tight x{args.tight}: refused ({error})"
            else:
                row["tight"] = squeezed.duration / set_only.duration
                line += (
                    f"\n  tight x{args.tight}: {squeezed.duration:.3f} s "
                    f"(x{row['tight']:.4f}); "
                    + held(plant, scenario, reference, objects, squeezed, tight)
                )
        print(line, flush=True)
        rows.append(row)
    ratio = [r["ratio"] for r in rows]
    print(
        f"\njerk+set+torque / jerk+set duration: median {statistics.median(ratio):.4f}"
        f" [{min(ratio):.4f}, {max(ratio):.4f}]; CPU +torque / jerk+set median "
        f"{statistics.median(r['cpu'] for r in rows):.2f}; CPU jerk / acceleration "
        f"(set+torque) median {statistics.median(r['jerk_cost'] for r in rows):.2f}"
    )
    squeezed = [r["tight"] for r in rows if "tight" in r]
    if squeezed:
        print(
            f"tight x{args.tight}: {len(squeezed)}/{len(rows)} retimed, duration "
            f"/ jerk+set median {statistics.median(squeezed):.4f} "
            f"[{min(squeezed):.4f}, {max(squeezed):.4f}]"
        )


if __name__ == "__main__":
    main()
