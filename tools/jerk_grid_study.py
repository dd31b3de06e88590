"""The jerk-limited retime on a grid refined where s'^2 moves (issue 27).

    python tools/jerk_grid_study.py [SCENARIO] [--seed N] [--lines K]

Part 1, straight joint lines from rest to rest (no grasp, the scenario's
jerk limits): the retime on 100 uniform points, and after one
:func:`rt_drake.shaping.jerk_grid` pass (started from that profile), each
divided by Ruckig's time-optimal double-S along the line (the path's
optimum: on a line every joint's limits map to bounds on s).

With ``--end-points N [N ...]``, part 1 adds a column per N: the uniform
retime with N points halving towards each end at rest instead of the
retimer's ``END_POINTS`` (6), and part 2 likewise on the adaptive grid.

Part 2, the cycle's picks (each object's blended pick as ``rt-drake run``
plans it; the first from home) retimed without a grasp: on the adaptive
grid (as before this change); refined once with the LPs started from
TOPP-RA's profile; refined once and twice started from the best profile
so far (as ``MotionRetimer`` now does); CPU per retime beside
(``time.process_time``). Every duration printed holds every limit at the
retimer's 1e-3 contract (``check_trajectory`` at 1 kHz is run on each).
"""

from __future__ import annotations

import argparse
import time
from unittest import mock

import numpy as np
import ruckig
from _cycle_picks import cycle_picks, jerk_cell
from pydrake.trajectories import PiecewisePolynomial

from rt_drake.retiming import JointLimits, RetimeError, check_trajectory, retime
from rt_drake.retiming import _jerk as jerk_module
from rt_drake.shaping import ADAPTIVE_WEIGHT, adaptive_grid, jerk_grid, retime_adaptive


def ruckig_line(step: np.ndarray, limits: JointLimits) -> float:
    """Ruckig's rest-to-rest time along ``q0 + s step``, s from 0 to 1 (s)."""
    scale = np.abs(step)
    setup = ruckig.InputParameter(1)
    setup.current_position, setup.target_position = [0.0], [1.0]
    setup.max_velocity = [float(np.min(limits.velocity / scale))]
    setup.max_acceleration = [float(np.min(limits.acceleration / scale))]
    assert limits.jerk is not None
    setup.max_jerk = [float(np.min(limits.jerk / scale))]
    out = ruckig.Trajectory(1)
    ruckig.Ruckig(1).calculate(setup, out)
    return float(out.duration)


def checked(plant, result, limits) -> float:  # noqa: ANN001
    """``result.duration`` after ``check_trajectory`` passes at 1 kHz."""
    report = check_trajectory(plant, result.trajectory, limits)
    assert report.passed(), report.summary()
    return float(result.duration)


def with_end_points(count: int, plant, path, limits, grid) -> float:  # noqa: ANN001
    """Duration on ``grid``, ``count`` halving points at each end (nan: refused)."""
    with mock.patch.object(jerk_module, "END_POINTS", count):
        try:
            return checked(plant, retime(plant, path, limits, None, grid), limits)
        except RetimeError:
            return float("nan")


def lines(plant, limits: JointLimits, count: int, ends: list[int]) -> None:  # noqa: ANN001
    """Part 1 (module docstring)."""
    extra = "".join(f" {n} end points / Ruckig |" for n in ends)
    print(f"| line | uniform / Ruckig | refined / Ruckig |{extra} Ruckig (s) |")
    print("|---|---:|---:|" + "---:|" * len(ends) + "---:|")
    rng = np.random.default_rng(0)
    base = np.linspace(0.0, 1.0, 101)
    for index in range(count):
        q0 = 0.8 * rng.uniform(-1.0, 1.0, 6)
        step = rng.uniform(-1.0, 1.0, 6) * (0.2 if index < 2 else 1.0)
        line = PiecewisePolynomial.CubicHermite(
            [0.0, 1.0], np.column_stack([q0, q0 + step]), np.column_stack([step, step])
        )
        first = retime(plant, line, limits, None, base)
        grid = jerk_grid(first.gridpoints, first.sd, base)
        again = retime(plant, line, limits, None, grid, jerk_start=first)
        best = min(checked(plant, first, limits), checked(plant, again, limits))
        optimum = ruckig_line(step, limits)
        cells = [first.duration, best]
        cells += [with_end_points(n, plant, line, limits, base) for n in ends]
        ratios = " | ".join(f"{c / optimum:.4f}" for c in cells)
        print(f"| {index} | {ratios} | {optimum:.4f} |")


def timed_retime(plant, path, limits, points, start, cpu: list):  # noqa: ANN001, ANN201
    """``retime`` on ``points`` from ``start`` (None if refused); CPU appended."""
    begin = time.process_time()
    try:
        return retime(plant, path, limits, None, points, jerk_start=start)
    except RetimeError as error:
        print(f"refused: {error}")
        return None
    finally:
        cpu.append(time.process_time() - begin)


def picks(scenario, plant, limits: JointLimits, seed: int, ends: list[int]) -> None:  # noqa: ANN001
    """Part 2 (module docstring)."""
    extra = "".join(f" {n} end points |" for n in ends)
    head = "| pick | adaptive | refined, TOPP-RA start | refined | twice |"
    print(f"{head}{extra} CPU (s) |")
    print("|---|---:|---:|---:|---:|" + "---:|" * len(ends) + "---|")
    for obj, pick in cycle_picks(scenario, seed):
        path = pick.path.path
        profile = retime_adaptive(plant, path, limits.without_jerk(), None)
        grid = adaptive_grid(profile.gridpoints, profile.sd, 100, ADAPTIVE_WEIGHT)
        cpu: list[float] = []
        first = timed_retime(plant, path, limits, grid, None, cpu)
        assert first is not None
        cells = [checked(plant, first, limits)]
        refined = jerk_grid(first.gridpoints, first.sd, grid)
        for start in (None, first):
            again = timed_retime(plant, path, limits, refined, start, cpu)
            cells.append(np.nan if again is None else checked(plant, again, limits))
        best = first if not cells[2] < cells[0] else again
        finer = jerk_grid(best.gridpoints, best.sd, refined, end_halvings=0)
        second = timed_retime(plant, path, limits, finer, best, cpu)
        if second is not None and second.duration < best.duration:
            best = second
        cells.append(checked(plant, best, limits))
        cells += [with_end_points(n, plant, path, limits, grid) for n in ends]
        times = " | ".join(f"{c:.4f}" for c in cells)
        spent = " / ".join(f"{c:.3f}" for c in cpu)
        print(f"| {obj.name} | {times} | {spent} |")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenario", nargs="?", default="stack_four_objects")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--lines", type=int, default=6)
    parser.add_argument("--end-points", type=int, nargs="*", default=[])
    args = parser.parse_args()
    scenario, plant, limits = jerk_cell(parser, args.scenario)
    lines(plant, limits, args.lines, args.end_points)
    picks(scenario, plant, limits, args.seed, args.end_points)


if __name__ == "__main__":
    main()
