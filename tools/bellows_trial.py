"""Play Table I trials under the bellows cup, with catalogue parameters scaled.

    python tools/bellows_trial.py SCENARIO [--trials 0 1] [--seed 0]
        [--scale NAME=FACTOR ...] [--cup-physics bellows] [--no-jerk-limits]
        [--constrained-only | --free-only] [--sweep]

For each trial of ``experiment transport`` (same sampling and planner seed,
the same grasp: from the cup, or APPROACH and REACH from home): plan the
MOVE, retime it under the grasp constraint and under the joint limits only
(both with the scenario's jerk limits, if it gives any; the constrained one
also with ``planning.grasp_ramp_s``), and play both in the simulated cell;
``--sweep`` also plays the constrained MOVE faster until it slips.
``--scale`` multiplies catalogue parameters of the bellows cup (a
sensitivity sweep: ``--scale lateral_stiffness=0.5``); ``--scale
pressure=1.358`` makes its pull 20 N. Prints one line per rollout: duration,
slip on the lip (mm, deg), motion on the tool (mm, deg: the slip plus the
bellows' deflection), held.
"""

from __future__ import annotations

import argparse
import dataclasses
import time

from _bellows_common import trial_move

from rt_drake.experiments._rollout import (
    critical_speed,
    rollout_scenario,
    simulate_move,
)
from rt_drake.experiments._transport_experiment import transport_inputs
from rt_drake.model.cup_physics import load_bellows_cup
from rt_drake.model.resources import resolve_scenario_path
from rt_drake.planning import sample_transports
from rt_drake.simulation import _station as station_module


def main() -> None:
    """Run the trials and print one line per rollout."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenario")
    parser.add_argument("--trials", type=int, nargs="+", default=[0])
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--scale", nargs="*", default=[])
    parser.add_argument("--cup-physics", default="bellows")
    parser.add_argument("--no-jerk-limits", action="store_true")
    only = parser.add_mutually_exclusive_group()
    only.add_argument(
        "--constrained-only", action="store_true", help="skip the joint-limits MOVE"
    )
    only.add_argument(
        "--free-only",
        action="store_true",
        help="play only the joint-limits MOVE (without the grasp constraint)",
    )
    parser.add_argument(
        "--sweep",
        action="store_true",
        help="also play the constrained MOVE faster until it slips (critical speed)",
    )
    args = parser.parse_args()
    path = resolve_scenario_path(args.scenario)
    scenario, name = transport_inputs(path, max(args.trials) + 1, 1, None)
    scenario = scenario.with_cup_physics(args.cup_physics)
    factors = {k: float(v) for k, v in (s.split("=") for s in args.scale)}
    cup = load_bellows_cup(scenario.cup_physics.cup).scaled(**factors)
    # The station loads the catalogue cup by name: hand it the scaled one.
    station_module.load_bellows_cup = lambda _name: cup  # type: ignore[attr-defined]
    pairs = sample_transports(scenario, max(args.trials) + 1, args.seed)
    jerk = bool(scenario.robot.jerk_limits) and not args.no_jerk_limits
    for i in args.trials:
        cpu = time.process_time()
        try:
            trial = trial_move(scenario, name, *pairs[i], args.seed, i, jerk)
            move = trial.move
            print(
                f"trial {i} planned: grasp margin {move.grasp_margin:.3f}, planning "
                f"and retiming {time.process_time() - cpu:.1f} s CPU; {move.guarantee}",
                flush=True,
            )
            free = trial.motions.retime_path(move.planned.path, grasp=None)
        except Exception as error:  # noqa: BLE001 (a study: report and go on)
            message = " ".join(str(error).split())[:150]
            print(f"trial {i}: no MOVE: {type(error).__name__}: {message}", flush=True)
            continue
        q_grasp = trial.q_grasp
        world = rollout_scenario(dataclasses.replace(trial.scenario), q_grasp)
        plays = (
            [] if args.sweep or args.free_only else [("constrained", move.trajectory)]
        )
        if not args.constrained_only:
            plays.append(("joint limits only", free.trajectory))
        if args.sweep:  # its first rollout, at speed 1, is the constrained one
            start = time.perf_counter()
            critical, sweep = critical_speed(world, q_grasp, move.trajectory)
            _print(i, "constrained", move.trajectory, sweep[0][1], start, factors)
            print(f"trial {i} critical speed factor: {critical}", flush=True)
        for label, trajectory in plays:
            start = time.perf_counter()
            rollout = simulate_move(world, q_grasp, trajectory)
            _print(i, label, trajectory, rollout, start, factors)


def _print(i, label, trajectory, rollout, start, factors) -> None:
    slip = rollout.as_dict()
    print(
        f"trial {i} {label}: {trajectory.end_time():.3f} s, slip "
        f"{slip['max_translation_mm']:.2f} mm {slip['max_rotation_deg']:.2f} "
        f"deg (on the tool {slip['on_tool_translation_mm']:.2f} mm "
        f"{slip['on_tool_rotation_deg']:.2f} deg), "
        f"{'held' if rollout.success else 'SLIP'} "
        f"({time.perf_counter() - start:.1f} s wall) {factors or ''}",
        flush=True,
    )


if __name__ == "__main__":
    main()
