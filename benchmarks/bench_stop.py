"""CPU time of a protective stop beside the retime of its MOVE, and what it costs.

Run: ``PYTHONPATH=. python benchmarks/bench_stop.py [--paths 6] [--instants 9]``;
``--jerk K`` (jerk limits K x the acceleration limits, per second) runs the
jerk-limited comparison instead (:func:`jerk_main`); ``--table [PERIOD ...]``
the stop tables' cost (:func:`table_main`, jerk 20x unless ``--jerk``).

The MOVE-like paths of ``bench_retime.py`` (lift, swing joint 1 by 0.6 to
1.8 rad, set down; the notebook on the scenario's cup, 100 grid points) are
retimed under the grasp; each is stopped at ``--instants`` evenly spaced
instants strictly inside it, grasp-aware (``protective_stop``) and by the
joint brake (``joint_brake_stop``). Interleaved on the same paths, in CPU
time of this thread (``time.thread_time``: the machine is shared): the
retime of the whole MOVE, each stop. Also: the stop times (s) and the
joint brake's grasp margin at 1 kHz (negative: the wrench leaves the grasp
set), so the price of keeping the grasp is measured beside its cost.

OpenBLAS is made single-threaded (unless OPENBLAS_NUM_THREADS is set).
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse  # noqa: E402
import dataclasses  # noqa: E402
import statistics  # noqa: E402
import time  # noqa: E402
from typing import Any  # noqa: E402

import numpy as np  # noqa: E402

from rt_drake.model.held import held_object_of  # noqa: E402
from rt_drake.model.plant import make_arm_plant  # noqa: E402
from rt_drake.model.resources import scenarios_dir  # noqa: E402
from rt_drake.model.scenario import load_scenario  # noqa: E402
from rt_drake.retiming import (  # noqa: E402
    GraspConstraint,
    JointLimits,
    Margin,
    check_trajectory,
    joint_brake_stop,
    protective_stop,
    retime,
)

HOME = np.array([0.0, 0.35, 1.75, 0.0, 1.04, 0.0])


def move_paths(count: int) -> list[np.ndarray]:
    """Waypoints of MOVE-like paths: lift, swing joint 1 (and the wrist), set down."""
    paths = []
    for swing in np.linspace(0.6, 1.8, count):
        lift = HOME + [0.0, -0.25, -0.3, 0.0, 0.45, 0.0]
        paths.append(
            np.array(
                [
                    HOME,
                    lift,
                    lift + [0.5 * swing, 0.05, 0.1, 0.1, -0.1, 0.3 * swing],
                    lift + [swing, 0.0, 0.0, 0.0, 0.0, 0.6 * swing],
                    HOME + [swing, 0.0, 0.0, 0.0, 0.0, 0.6 * swing],
                ]
            )
        )
    return paths


def cpu(call):  # noqa: ANN001, ANN201
    """(result, CPU seconds of this thread)."""
    start = time.thread_time()
    value = call()
    return value, time.thread_time() - start


@dataclasses.dataclass(frozen=True)
class Cell:
    """The bench's arm, its limits and the notebook's grasp, warmed up."""

    plant: Any
    context: Any
    limits: JointLimits
    grasp: GraspConstraint


def cell(jerk: float | None) -> Cell:
    """stack_four_objects' arm, its joint limits (with ``jerk`` x the
    acceleration limits per second as jerk limits, if given) and the
    notebook's grasp; one retime and one stop run first (compile, warm up)."""
    scenario = load_scenario(scenarios_dir() / "stack_four_objects.yaml")
    plant = make_arm_plant(scenario)
    limits = JointLimits.from_plant(plant, scenario.robot)
    if jerk is not None:
        limits = dataclasses.replace(limits, jerk=jerk * limits.acceleration)
    grasp = GraspConstraint.for_cup(
        held_object_of(scenario.object("notebook")), scenario.cup
    )
    path0 = move_paths(1)[0]
    warm = retime(plant, path0, limits, grasp)
    protective_stop(plant, path0, limits, warm, 0.3 * warm.duration, grasp)
    return Cell(plant, plant.CreateDefaultContext(), limits, grasp)


def timed_stops(c: Cell, path: np.ndarray, result, t: float):  # noqa: ANN001, ANN201
    """``(held, held CPU s, brake, brake CPU s)``: the grasp-aware stop and
    the joint brake of ``result`` (the retimed ``path``) at ``t``."""
    held, held_cpu = cpu(
        lambda: protective_stop(
            c.plant, path, c.limits, result, t, c.grasp, context=c.context
        )
    )
    brake, brake_cpu = cpu(
        lambda: joint_brake_stop(c.plant, path, c.limits, result, t, context=c.context)
    )
    return held, held_cpu, brake, brake_cpu


def summary_row(name: str, values: list[float], scale: float, unit: str) -> str:
    """A Markdown row: median, min and max of ``values`` x ``scale``."""
    v = np.asarray(values) * scale
    return (
        f"| {name} | {statistics.median(v):.4g} | {v.min():.4g} | "
        f"{v.max():.4g} | {unit} |"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--paths", type=int, default=6)
    parser.add_argument("--instants", type=int, default=9)
    parser.add_argument("--jerk", type=float, default=None)
    parser.add_argument("--sweep", type=int, default=24)
    parser.add_argument("--table", type=float, nargs="*", default=None)
    args = parser.parse_args()
    if args.table is not None:
        table_main(args.paths, args.jerk or 20.0, args.table or [0.01, 0.05])
        return
    if args.jerk is not None:
        jerk_main(args.paths, args.instants, args.jerk, args.sweep)
        return
    c = cell(None)
    retimes, held_cpu, brake_cpu = [], [], []
    held_time, brake_time, brake_margin, held_margin = [], [], [], []
    for path in move_paths(args.paths):
        for k in range(1, args.instants + 1):
            result, seconds = cpu(
                lambda p=path: retime(c.plant, p, c.limits, c.grasp, context=c.context)
            )
            retimes.append(seconds)
            t = k / (args.instants + 1) * result.duration
            held, seconds, brake, brake_seconds = timed_stops(c, path, result, t)
            held_cpu.append(seconds)
            brake_cpu.append(brake_seconds)
            held_time.append(held.duration)
            brake_time.append(brake.duration)
            for stop, out in ((held, held_margin), (brake, brake_margin)):
                check = check_trajectory(c.plant, stop.stop, c.limits, c.grasp)
                out.append(check.margins[Margin.GRASP].value)
    count = len(retimes)
    print(f"{args.paths} paths x {args.instants} instants = {count} stops")
    print("| quantity | median | min | max | unit |")
    print("|---|---:|---:|---:|---|")
    print(summary_row("retime of the MOVE (CPU)", retimes, 1e3, "ms"))
    print(summary_row("protective_stop (CPU)", held_cpu, 1e3, "ms"))
    print(summary_row("joint_brake_stop (CPU)", brake_cpu, 1e3, "ms"))
    print(summary_row("grasp-aware stop time", held_time, 1.0, "s"))
    print(summary_row("joint-brake stop time", brake_time, 1.0, "s"))
    print(summary_row("grasp margin, grasp-aware stop", held_margin, 1.0, "1"))
    print(summary_row("grasp margin, joint-brake stop", brake_margin, 1.0, "1"))
    left = sum(m < -1e-3 for m in brake_margin)
    print(f"joint-brake stops leaving the grasp set (margin < -1e-3): {left}/{count}")


def ruckig_stop(v: np.ndarray, a: np.ndarray, limits: JointLimits) -> float:
    """Slowest joint's time-optimal jerk-limited stop from (v, a), each apart.

    Ruckig (velocity interface, target v = a = 0) per joint with its own
    velocity, acceleration and jerk limits: no path, no grasp, no
    synchronisation, so a lower bound for a stop of all joints along a path.
    """
    from ruckig import ControlInterface, InputParameter, Result, Ruckig, Trajectory

    assert limits.jerk is not None
    slowest = 0.0
    for j in range(len(v)):
        otg, inp, out = Ruckig(1), InputParameter(1), Trajectory(1)
        inp.control_interface = ControlInterface.Velocity
        inp.current_position, inp.current_velocity = [0.0], [float(v[j])]
        inp.current_acceleration = [float(a[j])]
        inp.target_velocity, inp.target_acceleration = [0.0], [0.0]
        inp.max_velocity = [float(limits.velocity[j])]
        inp.max_acceleration = [float(limits.acceleration[j])]
        inp.max_jerk = [float(limits.jerk[j])]
        assert otg.calculate(inp, out) == Result.Working
        slowest = max(slowest, out.duration)
    return slowest


def jerk_main(paths: int, instants: int, factor: float, sweep: int) -> None:
    """Jerk-limited stops beside the full search, a sweep and Ruckig.

    On the MOVE-like paths, retimed under the grasp with jerk limits
    ``factor`` x the acceleration limits, each stop is compared with the
    fastest of ``sweep`` jerk-limited stops at evenly spaced distances from
    the acceleration-limited shortest one to the path's end (the reference
    search, with the MOVE's own remainder and the stop itself: ``--sweep 0``
    skips it), the search from the simulated braking's guess with the full
    search from the acceleration-limited distance (``guided_stop(...,
    simulate=False)``, session 3's), case by case, and the joint brake with
    Ruckig's per-joint stops (:func:`ruckig_stop`). CPU time of this thread.
    """
    from rt_drake.dynamics.cup_frame import CupFrame
    from rt_drake.retiming._jerk_stop import JerkStopProblem
    from rt_drake.retiming._joint_path import as_joint_path
    from rt_drake.retiming._stop import guided_stop, path_state_at

    c = cell(factor)
    plant, context, limits, grasp = c.plant, c.context, c.limits, c.grasp
    cup = CupFrame.of(plant)
    rows: dict[str, list[float]] = {
        k: []
        for k in (
            "retime", "stop_cpu", "brake_cpu", "held", "best", "ratio", "brake",
            "ruckig", "brake_ratio", "held_margin", "brake_margin", "jerk_margin",
            "full_cpu", "full", "vs_full",
        )
    }  # fmt: skip
    cases: list[str] = []
    for path in move_paths(paths):
        result, seconds = cpu(lambda p=path: retime(plant, p, limits, grasp))
        rows["retime"].append(seconds)
        spline = as_joint_path(path)
        for k in range(1, instants + 1):
            t = k / (instants + 1) * result.duration
            held, seconds, brake, brake_seconds = timed_stops(c, path, result, t)
            rows["stop_cpu"].append(seconds)
            rows["brake_cpu"].append(brake_seconds)
            full, seconds = cpu(
                lambda p=path, r=result, t=t: guided_stop(
                    plant, p, limits, r, t, grasp, context, None, None,
                    simulate=False,
                )
            )  # fmt: skip
            rows["full_cpu"].append(seconds)
            rows["full"].append(full.duration)
            rows["vs_full"].append(held.duration / full.duration)
            cases.append(
                f"| {len(cases)} | {t:.3f} | {held.duration:.4f} | "
                f"{full.duration:.4f} | {held.duration / full.duration:.4f} | "
                f"{rows['stop_cpu'][-1] * 1e3:.0f} | {seconds * 1e3:.0f} |"
            )
            s, sd, sdd = path_state_at(result, t)
            problem = JerkStopProblem(
                plant, spline, limits, grasp, context, cup, t, s, sd, sdd,
                result.gridpoints, result.sd**2,
            )  # fmt: skip
            low = held.s_stop - s if held.s_stop < 1.0 else 0.02
            candidates = [result.trajectory.end_time() - t]
            for length in np.linspace(0.5 * low, 1.0 - s, sweep, endpoint=False):
                stop = problem.stop(float(length))
                if stop is not None:
                    candidates.append(stop.duration)
            best = min(candidates)
            _, v, a = (x[0] for x in result.trajectory.sample(np.array([t]), 2))
            floor = ruckig_stop(v, a, limits)
            rows["held"].append(held.duration)
            rows["best"].append(best)
            rows["ratio"].append(held.duration / best)
            rows["brake"].append(brake.duration)
            rows["ruckig"].append(floor)
            rows["brake_ratio"].append(brake.duration / floor)
            for stop, key in ((held, "held_margin"), (brake, "brake_margin")):
                check = check_trajectory(plant, stop.stop, limits, grasp)
                rows[key].append(check.margins[Margin.GRASP].value)
            whole = check_trajectory(plant, held.trajectory, limits, grasp)
            rows["jerk_margin"].append(whole.margins[Margin.JERK].value)

    def row(name: str, key: str, scale: float, unit: str) -> str:
        return summary_row(name, rows[key], scale, unit)

    count = len(rows["held"])
    print(f"jerk {factor:g} x acceleration /s; {paths} paths x {instants} = {count}")
    print("| quantity | median | min | max | unit |")
    print("|---|---:|---:|---:|---|")
    print(row("jerk-limited retime of the MOVE (CPU)", "retime", 1e3, "ms"))
    print(row("protective_stop, jerk-limited (CPU)", "stop_cpu", 1e3, "ms"))
    print(row("joint_brake_stop, jerk-limited (CPU)", "brake_cpu", 1e3, "ms"))
    print(row("protective_stop, full search (reference, CPU)", "full_cpu", 1e3, "ms"))
    print(row("grasp-aware stop time", "held", 1.0, "s"))
    print(row("grasp-aware stop time, full search (reference)", "full", 1.0, "s"))
    print(row("grasp-aware / full search's", "vs_full", 1.0, "1"))
    print(row(f"fastest of the {sweep}-distance sweep", "best", 1.0, "s"))
    print(row("grasp-aware / sweep's fastest", "ratio", 1.0, "1"))
    print(row("joint-brake stop time", "brake", 1.0, "s"))
    print(row("Ruckig per joint, slowest", "ruckig", 1.0, "s"))
    print(row("joint brake / Ruckig", "brake_ratio", 1.0, "1"))
    print(row("grasp margin, grasp-aware stop", "held_margin", 1.0, "1"))
    print(row("grasp margin, joint-brake stop", "brake_margin", 1.0, "1"))
    print(row("jerk margin, MOVE + grasp-aware stop", "jerk_margin", 1.0, "1"))
    left = sum(m < -1e-3 for m in rows["brake_margin"])
    print(f"joint-brake stops leaving the grasp set (margin < -1e-3): {left}/{count}")
    print()
    print(
        "| case | t (s) | stop (s) | full search (s) | ratio | CPU ms | full CPU ms |"
    )
    print("|---:|---:|---:|---:|---:|---:|---:|")
    print("\n".join(cases))


def table_main(paths: int, factor: float, periods: list[float]) -> None:
    """CPU of ``stop_table`` per MOVE and per stop, beside the MOVE's retime.

    Jerk limits ``factor`` x the acceleration limits per second, the
    notebook's grasp; for each period, each path's table, and a
    ``protective_stop`` computed alone at every third instant of it (its
    duration beside the table's: the table's search starts from a guess).
    """
    from rt_drake import stop_table

    c = cell(factor)
    plant, context, limits, grasp = c.plant, c.context, c.limits, c.grasp
    print("| period | MOVE | duration | retime CPU | table CPU | stops | per stop |")
    print("|---:|---:|---:|---:|---:|---:|---:|")
    ratios: list[float] = []
    alone_cpu: list[float] = []
    for period in periods:
        for i, path in enumerate(move_paths(paths)):
            result, seconds = cpu(lambda p=path: retime(plant, p, limits, grasp))
            table, table_cpu = cpu(
                lambda p=path, r=result, h=period: stop_table(
                    plant, p, limits, r, h, grasp, context=context
                )
            )
            n = len(table.times)
            print(
                f"| {period * 1e3:g} ms | {i} | {result.duration:.3f} s | "
                f"{seconds * 1e3:.0f} ms | {table_cpu:.2f} s | {n} | "
                f"{table_cpu / n * 1e3:.0f} ms |"
            )
            if period != periods[-1]:
                continue
            for k in range(1, n - 1, 3):
                t = float(table.times[k])
                alone, seconds = cpu(
                    lambda p=path, r=result, t=t: protective_stop(
                        plant, p, limits, r, t, grasp, context=context
                    )
                )
                alone_cpu.append(seconds)
                if alone.duration > 0.0:
                    ratios.append(table.stops[k].duration / alone.duration)
    r = np.asarray(ratios)
    print(
        f"table stop / stop alone, duration, {len(r)} instants: median "
        f"{np.median(r):.4f}, min {r.min():.4f}, max {r.max():.4f}; "
        f"stop alone CPU median {np.median(alone_cpu) * 1e3:.0f} ms"
    )


if __name__ == "__main__":
    main()
