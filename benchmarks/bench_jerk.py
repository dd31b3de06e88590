"""Jerk-limited retiming on Table I's MOVEs: duration, CPU cost, limits held.

Run: ``PYTHONPATH=. nice python benchmarks/bench_jerk.py [--n 20] [--seed 0]``.

The MOVEs are Table I's (``random_transport_paper``, seed 0): each transport
planned as ``rt-drake experiment transport`` plans it (the object sealed on
the cup at its start, the faster of the two grasp yaw flips), retimed under
the grasp constraint of the notebook at 100 grid points. For each MOVE:

(a) the duration with the scenario's jerk limits (``robot.jerk_limits``)
    and with jerk limits of 5x, 10x and 20x the acceleration limits (per
    second), divided by the acceleration-limited duration (TOPP-RA);
(b) the CPU time of the retiming thread (``time.thread_time``; the machine
    is shared) of one acceleration-limited and one jerk-limited retime
    (shipped limits), interleaved, ``--repeats`` times, median per MOVE;
    and the share of the jerk-limited retime spent in the LPs
    (``WarmLP.solve``: the compiled dual simplex, HiGHS where it gives no
    answer), the CPU time of the first LP and of each later one, and the
    LPs left to HiGHS;
(c) every limit of the jerk-limited MOVE (shipped limits) at 1 kHz:
    ``check_trajectory`` (velocity, acceleration, position, jerk from
    differences of the 1 kHz accelerations, grasp by Newton-Euler) and the
    jerk from third differences of the 1 kHz positions.

OpenBLAS is made single-threaded (unless OPENBLAS_NUM_THREADS is set).
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse  # noqa: E402
import dataclasses  # noqa: E402
import statistics  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

from rt_drake.experiments._transport_experiment import (  # noqa: E402
    move_from_the_cup,
    transport_scenario,
)
from rt_drake.model.plant import make_arm_plant  # noqa: E402
from rt_drake.model.resources import scenarios_dir  # noqa: E402
from rt_drake.model.scenario import load_scenario  # noqa: E402
from rt_drake.planning import PlanningError, sample_transports  # noqa: E402
from rt_drake.retiming import (  # noqa: E402
    JointLimits,
    _jerk_lp,  # noqa: E402
    check_trajectory,
    retime,
    warm_up,
)
from rt_drake.simulation import OnlineMotions  # noqa: E402

#: Jerk limits of the curve, as multiples of the acceleration limits (1/s).
FACTORS = (5.0, 10.0, 20.0)
#: CPU ms of each LP (``WarmLP.solve``) since the last reset, by :func:`timed_solve`.
IN_LPS: list[float] = []
#: LPs the compiled solver left to HiGHS (``WarmLP.fallbacks``), and all LPs.
FALLBACKS = [0, 0]
_SOLVE = _jerk_lp.WarmLP.solve


def timed_solve(self, *args, **kwargs):  # noqa: ANN001, ANN002, ANN003, ANN201
    """``WarmLP.solve``, appending its thread CPU time (ms) to IN_LPS."""
    before = getattr(self, "fallbacks", 0)
    start = time.thread_time()
    try:
        return _SOLVE(self, *args, **kwargs)
    finally:
        IN_LPS.append(1e3 * (time.thread_time() - start))
        FALLBACKS[0] += getattr(self, "fallbacks", 0) - before
        FALLBACKS[1] += 1


def planned_moves(
    n: int, seed: int, name: str = "random_transport_paper"
) -> list[tuple[object, object]]:
    """Table I's MOVEs: (path, grasp) of each transport that plans.

    ``name``: the shipped scenario whose transports are sampled.
    """
    scenario = load_scenario(scenarios_dir() / f"{name}.yaml")
    moves = []
    for index, (X_start, X_goal) in enumerate(sample_transports(scenario, n, seed)):
        one = transport_scenario(scenario, "notebook", X_start, X_goal)
        motions = OnlineMotions(
            one, grasp_constraint=True, seed=seed + index, optimize=False
        )
        try:
            move = move_from_the_cup(motions, one.objects[0], X_start)
        except PlanningError as error:
            print(f"transport {index}: not planned ({error})")
            continue
        assert move.planned is not None
        moves.append((move.planned.path, move.grasp))
    return moves


@dataclasses.dataclass(frozen=True)
class JerkBench:
    """What the jerk benches share: their arguments and Table I's MOVEs.

    ``plant`` is the paper scenario's arm, ``shipped`` its shipped limits
    with jerk, ``moves`` the (path, grasp) pairs of ``planned_moves``.
    """

    args: argparse.Namespace
    scenario: object
    plant: object
    context: object
    shipped: JointLimits
    moves: list[tuple[object, object]]


def jerk_bench(description: str, check: bool = False) -> JerkBench:
    """Parse ``--n --seed --repeats`` (``--check``), build the arm, warm up, plan."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--n", type=int, default=20)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--repeats", type=int, default=3)
    if check:
        parser.add_argument("--check", action="store_true")
    args = parser.parse_args()
    scenario = load_scenario(scenarios_dir() / "random_transport_paper.yaml")
    plant = make_arm_plant(scenario)
    shipped = JointLimits.from_plant(plant, scenario.robot, jerk=True)
    warm_up()
    moves = planned_moves(args.n, args.seed)
    return JerkBench(
        args, scenario, plant, plant.CreateDefaultContext(), shipped, moves
    )


def third_difference_jerk(trajectory, step: float = 1e-3) -> np.ndarray:
    """|q'''| from third differences of q sampled every ``step`` s, (M-3, n)."""
    t = step * np.arange(int(trajectory.end_time() / step) + 1)
    q = trajectory.sample(t, order=0)[0]
    return np.abs(np.diff(q, 3, axis=0)) / step**3


def main() -> None:
    """Print (a), (b), (c) for Table I's MOVEs."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=20)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--gridpoints", type=int, default=100)
    parser.add_argument(
        "--durations",
        help="write the jerk-limited durations (shipped limits; .npy, full "
        "precision) to this file, to compare two trees' results",
    )
    args = parser.parse_args()
    scenario = load_scenario(scenarios_dir() / "random_transport_paper.yaml")
    plant = make_arm_plant(scenario)
    context = plant.CreateDefaultContext()
    plain = JointLimits.from_plant(plant, scenario.robot)
    shipped = JointLimits.from_plant(plant, scenario.robot, jerk=True)
    assert shipped.jerk is not None
    print(
        "shipped jerk limits / acceleration limits (1/s): "
        + " ".join(f"{r:.2f}" for r in shipped.jerk / shipped.acceleration)
    )
    warm_up()
    moves = planned_moves(args.n, args.seed)
    print(f"{len(moves)} MOVEs planned (random_transport_paper, seed {args.seed})")
    grid = args.gridpoints
    ratios: dict[str, list[float]] = {"shipped": [], **{f"{f:g}x": [] for f in FACTORS}}
    cpu_plain, cpu_jerk, lps, highs = [], [], [], []
    jerk_durations: list[float] = []
    first_lp, warm_lp = [], []
    _jerk_lp.WarmLP.solve = timed_solve  # type: ignore[method-assign]
    worst_check, worst_difference, passed = np.inf, 0.0, 0
    for index, (path, grasp) in enumerate(moves):
        base = retime(plant, path, plain, grasp, grid, context=context)
        limited = retime(plant, path, shipped, grasp, grid, context=context)
        ratios["shipped"].append(limited.duration / base.duration)
        jerk_durations.append(limited.duration)
        lps.append(limited.jerk_lps)
        for factor in FACTORS:
            scaled = JointLimits(
                plain.velocity, plain.acceleration, jerk=factor * plain.acceleration
            )
            other = retime(plant, path, scaled, grasp, grid, context=context)
            ratios[f"{factor:g}x"].append(other.duration / base.duration)
        for _ in range(args.repeats):
            for limits, times in ((plain, cpu_plain), (shipped, cpu_jerk)):
                IN_LPS.clear()
                start = time.thread_time()
                retime(plant, path, limits, grasp, grid, context=context)
                times.append(1e3 * (time.thread_time() - start))
            highs.append(sum(IN_LPS) / times[-1])
            first_lp.append(IN_LPS[0])
            warm_lp.extend(IN_LPS[1:])
        check = check_trajectory(plant, limited.trajectory, shipped, grasp)
        difference = float(
            np.max(third_difference_jerk(limited.trajectory) / shipped.jerk)
        )
        worst_check = min(worst_check, check.min_margin())
        worst_difference = max(worst_difference, difference)
        passed += bool(check.passed()) and difference <= 1.0 + 1e-3
        print(
            f"MOVE {index:2d}: {base.duration:.3f} s -> {limited.duration:.3f} s "
            f"(x{limited.duration / base.duration:.3f}, {limited.jerk_lps} LPs); "
            f"min margin {check.min_margin():+.5f}, third-difference jerk / limit "
            f"{difference:.5f}"
        )
    if args.durations:
        np.save(args.durations, np.array(jerk_durations))
    print("\n(a) jerk-limited / acceleration-limited duration, median [min, max]:")
    for name, values in ratios.items():
        print(
            f"  {name:8s} {statistics.median(values):.3f} "
            f"[{min(values):.3f}, {max(values):.3f}]"
        )
    print(
        f"\n(b) CPU ms per retime ({args.repeats} repeats per MOVE, interleaved): "
        f"acceleration-limited median {statistics.median(cpu_plain):.1f}, "
        f"jerk-limited median {statistics.median(cpu_jerk):.1f}, ratio "
        f"{statistics.median(cpu_jerk) / statistics.median(cpu_plain):.1f}; "
        f"LPs per jerk-limited retime median {statistics.median(lps):g}, max {max(lps)}"
        f"; share of the jerk-limited retime in its LPs (WarmLP.solve) median "
        f"{100 * statistics.median(highs):.0f} %; CPU ms of the first LP median "
        f"{statistics.median(first_lp):.1f}, of each later (warm-started) LP "
        f"median {statistics.median(warm_lp):.1f}"
    )
    print(f"LPs the compiled solver left to HiGHS: {FALLBACKS[0]} of {FALLBACKS[1]}")
    print(
        f"\n(c) {passed}/{len(moves)} jerk-limited MOVEs hold every limit at 1 kHz "
        f"within 1e-3: worst check margin {worst_check:+.5f}, worst third-"
        f"difference jerk / limit {worst_difference:.5f}"
    )


if __name__ == "__main__":
    main()
