"""Median wall time to retime 6-DOF MOVE paths, 100 grid points, exact grasp.

Run: ``PYTHONPATH=. python benchmarks/bench_retime.py [--repeats 30]``.

Every method retimes the same paths (lift out of the bin, swing joint 1 by
0.6 to 1.8 rad, set down; the notebook held by the scenario's cup) and is
timed including its dynamics evaluation:

- ``rt_drake.retiming``: ours (precomputed coefficients, row selection with
  exactness check, toppra's seidel LP, lean passes);
- the same with ``engine="toppra"`` (toppra's own TOPPRA class);
- toppra with precomputed coefficients and all rows of one constant F;
- the paper's way: toppra ``SecondOrderConstraint`` whose inverse-dynamics
  callback computes the object wrench with Drake, all rows of F;
- Drake's ``Toppra`` with joint limits and ``AddFrameAccelerationLimit`` on
  the cup frame (a box on its spatial acceleration: another constraint, so
  another duration; timed for reference).

Then the robust grasp (issue 15): ours with every object of the uncertainty
set ``{mass: 0.2, com: [0.01, 0.01, 0.005], inertia: 0.2}`` around the
notebook (``GraspConstraint.robust``), timed interleaved with the nominal
retime on the same paths so that the ratio of the two is measured side by
side, in CPU time of the retiming thread (``time.thread_time``: the machine
is shared) (``--robust-repeats``).

OpenBLAS is made single-threaded (unless OPENBLAS_NUM_THREADS is set): on a
busy 2-core machine its threads made toppra's matrix products 10-50x slower.
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse  # noqa: E402
import statistics  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402
import toppra  # noqa: E402
from pydrake.multibody.optimization import Toppra  # noqa: E402
from toppra.algorithm import TOPPRA  # noqa: E402
from toppra.constraint import (  # noqa: E402
    DiscretizationType,
    JointAccelerationConstraint,
    JointVelocityConstraint,
    SecondOrderConstraint,
)

from rt_drake.dynamics.wrench import (
    object_wrench,
    path_wrench_coefficients,
)
from rt_drake.model.held import held_object_of
from rt_drake.model.plant import (
    CUP_FRAME,
    make_arm_plant,
)
from rt_drake.model.resources import scenarios_dir  # noqa: E402
from rt_drake.model.scenario import load_scenario  # noqa: E402
from rt_drake.retiming import GraspConstraint, JointLimits, retime  # noqa: E402
from rt_drake.retiming.passes import AffineConstraint  # noqa: E402
from rt_drake.types.object_uncertainty import ObjectUncertainty  # noqa: E402
from rt_drake.types.path import (
    GeometricPath,  # noqa: E402
    drake_path,
    path_waypoints_and_knots,
)  # noqa: E402

HOME = np.array([0.0, 0.35, 1.75, 0.0, 1.04, 0.0])


def move_paths(count: int) -> list[GeometricPath]:
    """MOVE-like paths: lift, swing joint 1 (and the wrist), set down.

    As the planner hands them over: ``GeometricPath`` (waypoints, knots and
    its clamped spline).
    """
    paths = []
    for swing in np.linspace(0.6, 1.8, count):
        # Joint 5 lifts by 0.45 rad: with 0.55 the spline overshoots joint 5's
        # limit (95 deg) on the two widest swings, which retime now refuses.
        lift = HOME + [0.0, -0.25, -0.3, 0.0, 0.45, 0.0]
        waypoints = [
            HOME,
            lift,
            lift + [0.5 * swing, 0.05, 0.1, 0.1, -0.1, 0.3 * swing],
            lift + [swing, 0.0, 0.0, 0.0, 0.0, 0.6 * swing],
            HOME + [swing, 0.0, 0.0, 0.0, 0.0, 0.6 * swing],
        ]
        paths.append(GeometricPath.from_waypoints(np.array(waypoints)))
    return paths


def ours(plant, path, limits, grasp, grid, context):
    return retime(plant, path, limits, grasp, grid, context=context).duration


def ours_toppra_loop(plant, path, limits, grasp, grid, context):
    return retime(
        plant, path, limits, grasp, grid, context=context, engine="toppra"
    ).duration


def _spline(path):
    return toppra.SplineInterpolator(
        *path_waypoints_and_knots(path)[::-1], bc_type="clamped"
    )


def _toppra_duration(constraints, spline, grid):
    algorithm = TOPPRA(constraints, spline, grid, solver_wrapper="seidel")
    _, sd, _ = algorithm.compute_parameterization(0.0, 0.0)
    return float(np.sum(2 * np.diff(grid) / (sd[1:] + sd[:-1])))


def toppra_all_rows(plant, path, limits, grasp, grid, context):
    spline = _spline(path)
    w = path_wrench_coefficients(
        plant, grasp.held, spline(grid), spline(grid, 1), spline(grid, 2), context
    )
    constraints = [
        JointVelocityConstraint(limits.velocity),
        JointAccelerationConstraint(limits.acceleration),
        AffineConstraint(*w, grasp.F, grasp.g),
    ]
    return _toppra_duration(constraints, spline, grid)


def paper_way(plant, path, limits, grasp, grid, context):
    spline = _spline(path)

    def inverse_dynamics(q, qd, qdd):
        return object_wrench(plant, grasp.held, q, qd, qdd, context)[0]

    wrench = SecondOrderConstraint(
        inverse_dynamics,
        lambda q: grasp.F,
        lambda q: grasp.g,
        dof=6,
        discretization_scheme=DiscretizationType.Interpolation,
    )
    constraints = [
        JointVelocityConstraint(limits.velocity),
        JointAccelerationConstraint(limits.acceleration),
        wrench,
    ]
    return _toppra_duration(constraints, spline, grid)


def drake_frame_limit(plant, path, limits, grasp, grid, context):
    q_of_s = drake_path(path)
    solver = Toppra(q_of_s, plant, grid)
    solver.AddJointVelocityLimit(-limits.velocity, limits.velocity)
    solver.AddJointAccelerationLimit(-limits.acceleration, limits.acceleration)
    box = np.array([20.0, 20.0, 20.0, 4.0, 4.0, 4.0])  # rad/s^2, m/s^2
    solver.AddFrameAccelerationLimit(plant.GetFrameByName(CUP_FRAME), -box, box)
    return solver.SolvePathParameterization().end_time()


METHODS = {
    "rt_drake.retiming (ours)": ours,
    "ours, toppra's TOPPRA loop": ours_toppra_loop,
    "toppra, precomputed, all rows": toppra_all_rows,
    "paper: SecondOrderConstraint + ID callback": paper_way,
    "Drake Toppra + frame accel limit": drake_frame_limit,
}


#: The uncertainty set of the robust row (issue 15's target set).
UNCERTAINTY = ObjectUncertainty(mass=0.2, com=[0.01, 0.01, 0.005], inertia=0.2)


def robust_vs_nominal(plant, paths, limits, held, cup, R_CO, grid, context, repeats):
    """Median CPU times (ms, this thread's) of the nominal and robust retime.

    Interleaved, retime by retime, so that both see the same machine load;
    ``time.thread_time`` does not count time the thread waited for a core.

    Returns (nominal times, robust times, nominal durations, robust durations).
    """
    nominal = GraspConstraint.for_cup(held, cup)
    robust = GraspConstraint.robust(held, UNCERTAINTY, cup, R_CO)
    times: dict[str, list[float]] = {"nominal": [], "robust": []}
    durations: dict[str, list[float]] = {"nominal": [], "robust": []}
    for path in paths:
        for name, grasp in (("nominal", nominal), ("robust", robust)):
            durations[name].append(ours(plant, path, limits, grasp, grid, context))
        for _ in range(repeats):
            for name, grasp in (("nominal", nominal), ("robust", robust)):
                start = time.thread_time()
                ours(plant, path, limits, grasp, grid, context)
                times[name].append(1e3 * (time.thread_time() - start))
    return times, durations


def main() -> None:
    """Time every method on the same paths and print a table of medians."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=20)
    parser.add_argument("--paths", type=int, default=5)
    parser.add_argument("--gridpoints", type=int, default=100)
    parser.add_argument("--object", default="notebook")
    parser.add_argument("--robust-repeats", type=int, default=30)
    parser.add_argument(
        "--only-robust", action="store_true", help="skip the method comparison"
    )
    args = parser.parse_args()
    scenario = load_scenario(scenarios_dir() / "stack_four_objects.yaml")
    plant = make_arm_plant(scenario)
    context = plant.CreateDefaultContext()
    limits = JointLimits.from_plant(plant, scenario.robot)
    held = held_object_of(scenario.object(args.object))
    grasp = GraspConstraint.for_cup(held, scenario.cup)
    grid = np.linspace(0.0, 1.0, args.gridpoints)
    paths = move_paths(args.paths)
    print(
        f"{len(paths)} MOVE paths, {args.gridpoints} grid points, {args.object}, "
        f"{len(grasp.g)}-row exact grasp polytope, {args.repeats} repeats; "
        f"OPENBLAS_NUM_THREADS={os.environ['OPENBLAS_NUM_THREADS']}"
    )
    print(
        f"{'method':44s} {'median ms':>10s} {'p10 ms':>8s} {'p90 ms':>8s}  durations s"
    )
    for name, method in {} if args.only_robust else METHODS.items():
        times, durations = [], []
        for path in paths:
            durations.append(method(plant, path, limits, grasp, grid, context))  # warm
            for _ in range(args.repeats):
                start = time.perf_counter()
                method(plant, path, limits, grasp, grid, context)
                times.append(1e3 * (time.perf_counter() - start))
        deciles = statistics.quantiles(times, n=10)
        print(
            f"{name:44s} {statistics.median(times):10.2f} {deciles[0]:8.2f} "
            f"{deciles[-1]:8.2f}  " + " ".join(f"{d:.3f}" for d in durations)
        )
    obj = scenario.object(args.object)
    R_CO = obj.grasp.GetDeterministicValue().inverse().rotation().matrix()
    times, durations = robust_vs_nominal(
        plant, paths, limits, held, scenario.cup, R_CO, grid, context,
        args.robust_repeats,
    )  # fmt: skip
    median = {name: statistics.median(t) for name, t in times.items()}
    print(
        f"\nrobust grasp (set {UNCERTAINTY}), interleaved with the nominal, "
        f"{args.robust_repeats} repeats per path, CPU ms (thread_time):"
    )
    for name in ("nominal", "robust"):
        deciles = statistics.quantiles(times[name], n=10)
        print(
            f"{name:44s} {median[name]:10.2f} {deciles[0]:8.2f} {deciles[-1]:8.2f}  "
            + " ".join(f"{d:.3f}" for d in durations[name])
        )
    ratios = [r / n for n, r in zip(times["nominal"], times["robust"], strict=True)]
    print(
        f"robust / nominal: ratio of medians {median['robust'] / median['nominal']:.2f}"
        f", median of paired ratios {statistics.median(ratios):.2f}"
    )


if __name__ == "__main__":
    main()
