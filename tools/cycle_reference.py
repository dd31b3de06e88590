"""The cycle's reference: each motion's KTO, retimed as the cycle retimes it (issue 27).

    OPENBLAS_NUM_THREADS=1 python tools/cycle_reference.py [SCENARIO] [--seed N]
        [--time-limit S] [--jerk-control-points N] [--only I ...] [--json FILE]

How fast could a path optimiser make this cell's cycle? For each object of
the cycle, as ``rt-drake run`` plans and plays it
(:class:`~rt_drake.simulation.OnlineMotions`, the scenario's jerk limits),
two Drake KinematicTrajectoryOptimizations (KTO) per motion:

- the MOVE: the KTO of ``tools/kto_reference.py`` (the grasp's rows at
  samples, the shaped family's 3 cm vertical ends, the tilt bound,
  collision samples where the planner's check finds the path colliding),
  with velocity and acceleration bounds, started from the shaped MOVE the
  cycle plays timed at the acceleration limits (``acc``); and the same with
  the grasp-constrained motion's jerk bounds and zero acceleration at both
  ends (``jerk``, :class:`_cycle_kto.JerkKto`), started from that MOVE as
  the cycle plays it (its jerk-limited retime);
- the pick (no object held): :class:`_cycle_kto.PickKto`, the blended
  pick's line ends and lines, collision samples on the transit; ``acc``
  started from the blended pick at the acceleration limits, ``jerk`` (jerk
  bounds, rest at both ends) from it as the cycle retimes a pick. The first
  object's pick, which the cycle stages (a straight APPROACH timed by
  Ruckig, then the REACH), is compared with the KTO from home through the
  same approach pose.

Each KTO gives two motions: its own trajectory (``T``; it is a trajectory,
playable as it is), and its path retimed as the cycle retimes that motion
(the MOVE: the grasp, the acceleration limits on the optimiser's adaptive
grid, then the jerk limits on points placed by that profile,
``OnlineMotions.retime_on_profile``; the pick: ``OnlineMotions.retime_free``).
A motion counts if its path passes the planner's dense collision check
(with the carried object on the MOVE), stays on its lines (the pick:
``line_deviation``, 1 mm and 0.5 deg) or vertical ends (the MOVE: 1 mm)
and its tilt bound, and it holds every limit (and the grasp) at 1 kHz
within :data:`OWN_TOLERANCE_PCT` (``check_trajectory``). The reference
motion is the fastest of the played one and those that count (an
optimiser may keep what it has). Per object: the reference cycle time =
the fixed waits (ATTACH + DETACH) + the reference pick + the reference
MOVE; its ``floor_ratio`` = that / (the waits + the floor's motion,
:func:`rt_drake.experiments.cycle_floors` with the jerk limits). Printed
per KTO: ``own T / retimed``. Durations in s, CPU in s of this process
(``time.process_time``; each solve capped by ``--time-limit``).
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys
import time
import types
from pathlib import Path

import numpy as np
from _cycle_kto import JerkKto, PickKto
from kto_reference import (
    TILT_TOLERANCE,
    Kto,
    add_kto_arguments,
    path_of,
    solve_and_check,
    solve_collision_free,
)

from rt_drake import check_trajectory
from rt_drake.errors import RtDrakeError
from rt_drake.experiments import cycle_floors
from rt_drake.model.resources import resolve_scenario_path
from rt_drake.model.scenario import load_scenario
from rt_drake.planning._pick import line_deviation
from rt_drake.planning.dense_check import check_path
from rt_drake.shaping import retime_adaptive, vertical_drift
from rt_drake.shaping._options import VERTICAL_DRIFT
from rt_drake.simulation import OnlineMotions
from rt_drake.types.phase import Phase

#: %: the most a KTO's own trajectory may exceed a limit (``check_trajectory``
#: at 1 kHz, relative) and still count as a motion the cell could play.
OWN_TOLERANCE_PCT = 0.1


def _timed(own, retimed, path_ok: bool) -> dict:  # noqa: ANN001
    """A KTO's two timings: its own trajectory and its path retimed as the cycle.

    ``own`` and ``retimed``: (duration s, ``check_trajectory``) of each; the
    reference takes the fastest that holds (path clean and on its lines,
    limits within :data:`OWN_TOLERANCE_PCT`).
    """
    (own_s, own_check), (retimed_s, retimed_check) = own, retimed
    own_pct, retimed_pct = (
        -100 * own_check.min_margin(),
        -100 * retimed_check.min_margin(),
    )
    holds = [s for s, pct in ((own_s, own_pct), (retimed_s, retimed_pct))
             if path_ok and pct <= OWN_TOLERANCE_PCT]  # fmt: skip
    return {
        "kto_T_s": own_s, "own_worst_pct": own_pct,
        "kto_s": retimed_s, "retimed_worst_pct": retimed_pct,
        "valid": path_ok, "best_s": min(holds, default=np.inf),
    }  # fmt: skip


def pick_reference(motions: OnlineMotions, q_start, obj, retreat: bool, args) -> dict:  # noqa: ANN001
    """The blended pick and its KTO, both retimed as the cycle retimes a pick."""
    planner, limits = motions.planner, motions._limits  # noqa: SLF001 - a study
    plant, context, cup = motions._plant, motions._context, motions._cup  # noqa: SLF001
    chain = motions._optimizer.chain  # noqa: SLF001
    motions._place_objects_for(obj)  # noqa: SLF001
    planned = planner.plan_pick(q_start, obj.name, retreat)
    profile = retime_adaptive(
        plant, planned.path.path, limits.without_jerk(), None, context=context, cup=cup
    )
    blended = motions.retime_free(planned.path.path, profile=profile)
    kw = {"context": context, "cup": cup}
    out = {"blended_s": blended.duration, "blended_acc_s": profile.duration}

    def scene():  # noqa: ANN202
        return planner.prepare(Phase.REACH, obj.name, q_start, planned.path.X_OC)

    # Each KTO from the blended pick timed as it bounds it: at the
    # acceleration limits, or as the cycle plays it (under the jerk limits).
    variants = (("acc", limits.without_jerk(), profile), ("jerk", limits, blended))
    for name, bounds, guess in variants:
        setup = types.SimpleNamespace(planner=planner, limits=bounds)

        def solve_once(options, extra, bounds=bounds, setup=setup, guess=guess):  # noqa: ANN001, ANN202
            kto = PickKto(chain, planned, guess, retreat, bounds, options)
            kto.collision_taus = list(extra)
            solved = kto.solve(setup, scene())
            found = path_of(solved.trajectory, kto)
            return kto, solved, found, check_path(scene(), found[0])

        found = solve_collision_free(solve_once, _variant(args, name, pick=True))
        kto, solved, (path, s_up, s_down, _), collision = found.solution
        prepared = scene()
        X_start, X_grasp = (prepared.cup_pose(q) for q in (kto.q0, kto.q1))
        lines = [line_deviation(prepared, path, s_down, 1.0, X_grasp)]
        if retreat:
            lines.append(line_deviation(prepared, path, 0.0, s_up, X_start))
        traj = solved.trajectory
        at_acceleration_limits = retime_adaptive(
            plant, path, limits.without_jerk(), None, **kw
        )
        retimed = motions.retime_free(path, profile=at_acceleration_limits)
        timed = _timed(
            (traj.end_time(), check_trajectory(plant, traj, limits, **kw)),
            (retimed.duration,
             check_trajectory(plant, retimed.trajectory, limits, **kw)),
            bool(collision.ok and all(d.ok for d in lines)),
        )  # fmt: skip
        out[name] = {
            **timed, "kto_acc_s": at_acceleration_limits.duration,
            "collision": collision.reason or "ok",
            "line_mm": 1e3 * max(d.offset_m for d in lines),
            "line_deg": float(np.degrees(max(d.tilt_rad for d in lines))),
            "feasible": solved.feasible, "stopped": solved.stopped,
            "cpu_s": found.cpu_s, "retries": found.retries,
        }  # fmt: skip
    out["cpu_s"] = out["acc"]["cpu_s"] + out["jerk"]["cpu_s"]
    return out


def _variant(args: argparse.Namespace, name: str, pick: bool) -> argparse.Namespace:
    """The KTO options of one variant: ``acc`` or ``jerk`` (its control points)."""
    points = args.pick_control_points if pick else args.control_points
    if name == "jerk":
        points = args.jerk_control_points
    changes = {"control_points": points}
    if pick:
        changes["collision_samples"] = args.pick_collision_samples
    return argparse.Namespace(**{**vars(args), **changes})


def move_reference(motions: OnlineMotions, q_grasp, obj, reach, played, args) -> dict:  # noqa: ANN001
    """The shaped MOVE (planned again, as the cycle) and its KTOs, retimed as played.

    Two KTOs from the shaped MOVE: ``kto_reference.Kto`` (acceleration
    bounds, as that tool) and :class:`JerkKto` (the grasp-constrained
    motion's jerk bounds too).
    """
    planner, optimizer = motions.planner, motions._optimizer  # noqa: SLF001
    plant, context, cup = motions._plant, motions._context, motions._cup  # noqa: SLF001
    limits = motions._grasp_limits  # noqa: SLF001
    motions._place_objects_for(obj)  # noqa: SLF001
    spline = planner.plan_move(q_grasp, obj.name, reach=reach)
    grasp = motions.grasp_for(obj, spline.X_OC)
    optimized = optimizer.optimize(planner, spline, grasp)
    setup = types.SimpleNamespace(planner=planner, limits=limits)
    kw = {"context": context, "cup": cup}
    out = {
        "played_s": played.trajectory.end_time(),
        "replanned_same": bool(
            np.array_equal(optimized.path.waypoints, played.planned.path.waypoints)
        ),
        "shaped_acc_s": optimized.duration,
        "improved": optimized.improved,
    }
    # The jerk-bounded KTO starts from the shaped MOVE as played (its
    # jerk-limited retime), the other from its acceleration-limited retime.
    played_retime = motions.retime_on_profile(optimized.path, grasp, optimized.retimed)
    as_played = dataclasses.replace(optimized, retimed=played_retime)
    if not optimized.improved:  # Kto starts from the spline path's retime then
        as_played = dataclasses.replace(as_played, spline_retimed=played_retime)
    for name, kind, start in (("acc", Kto, optimized), ("jerk", JerkKto, as_played)):

        def solve_once(options, extra, kind=kind, start=start):  # noqa: ANN001, ANN202
            return solve_and_check(
                setup, optimizer, spline, grasp, start, options, extra, kind
            )

        found = solve_collision_free(solve_once, _variant(args, name, pick=False))
        _, solved, (path, s_up, s_down, _), collision = found.solution
        tilt = optimizer.chain.tilt(path.value(np.linspace(0, 1, 1000))).max()
        drift = max(
            vertical_drift(optimizer.chain, path, 0.0, s_up),
            vertical_drift(optimizer.chain, path, s_down, 1.0),
        )
        profile = optimizer.retime(path, grasp)
        retimed = motions.retime_on_profile(path, grasp, profile)
        traj = solved.trajectory
        ok = collision.ok and drift <= VERTICAL_DRIFT
        ok = ok and tilt <= optimizer.options.tilt_bound + TILT_TOLERANCE
        timed = _timed(
            (traj.end_time(), check_trajectory(plant, traj, limits, grasp, **kw)),
            (retimed.duration,
             check_trajectory(plant, retimed.trajectory, limits, grasp, **kw)),
            bool(ok),
        )  # fmt: skip
        out[name] = {
            **timed, "kto_acc_s": profile.duration,
            "collision": collision.reason or "ok",
            "tilt_deg": float(np.degrees(tilt)), "drift_mm": 1e3 * drift,
            "feasible": solved.feasible, "stopped": solved.stopped,
            "cpu_s": found.cpu_s, "retries": found.retries,
        }  # fmt: skip
    out["cpu_s"] = out["acc"]["cpu_s"] + out["jerk"]["cpu_s"]
    return out


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenario", nargs="?", default="stack_four_objects")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--pick-control-points", type=int, default=20)
    parser.add_argument("--pick-collision-samples", type=int, default=30)
    parser.add_argument("--jerk-control-points", type=int, default=32)
    parser.add_argument("--only", type=int, nargs="+", default=None,
                        help="solve these objects' KTOs (indices; the cycle's "
                        "motions are planned for all)")  # fmt: skip
    parser.add_argument("--json", type=Path, default=None)
    add_kto_arguments(parser)
    parser.set_defaults(time_limit=30.0)
    args = parser.parse_args()
    try:
        return run(args)
    except RtDrakeError as error:
        print(f"cycle_reference.py: {error}", file=sys.stderr)
        return 2


def run(args: argparse.Namespace) -> int:
    """The reference of ``args.scenario``'s cycle (module docstring); exit status.

    Raises:
        RtDrakeError: the scenario cannot be loaded or its cycle planned.
    """
    scenario = load_scenario(resolve_scenario_path(args.scenario))
    if not scenario.planning.optimize_move:
        print(f"{args.scenario}: planning.optimize_move is off; the MOVE's KTO "
              "starts from the shaped MOVE", file=sys.stderr)  # fmt: skip
        return 2
    count = len(scenario.objects)
    outside = [i for i in args.only or () if not 0 <= i < count]
    if outside:
        print(f"--only {outside[0]}: {args.scenario} has objects 0 to {count - 1}",
              file=sys.stderr)  # fmt: skip
        return 2
    jerk = np.array(scenario.robot.jerk_limits) if scenario.robot.jerk_limits else None
    motions = OnlineMotions(scenario, seed=args.seed, jerk_limits=jerk is not None)
    floors = cycle_floors(scenario, args.seed, jerk=jerk, shaped=True)
    waits = scenario.vacuum.attach_s + scenario.vacuum.detach_s
    rows, q = [], motions.q_home
    for index, (obj, floor) in enumerate(zip(scenario.objects, floors, strict=True)):
        start = time.process_time()
        pick = motions.pick(q, obj, retreat=index > 0)
        move = motions.move(pick.q_end, obj, pick)
        if args.only is not None and index not in args.only:
            q = move.q_end
            continue
        picked = pick_reference(motions, q, obj, index > 0, args)
        moved = move_reference(motions, pick.q_end, obj, pick.planned, move, args)
        picked["played_s"] = pick.trajectory.end_time()
        row = {
            "object": obj.name,
            "pick": picked,
            "move": moved,
            "pick_floor_s": floor.retreat_s + floor.transit_s + floor.descent_s,
            "move_floor_s": floor.move_s,
            "motion_floor_s": floor.motion_s,
            "cpu_s": time.process_time() - start,
        }
        for part in (picked, moved):
            part["reference_s"] = min(
                part["played_s"], part["acc"]["best_s"], part["jerk"]["best_s"]
            )
        rows.append(row)
        print(json.dumps(row), flush=True)
        q = move.q_end
    summary = summarise(rows, waits)
    print_tables(rows, summary)
    if args.only is not None:
        print(f"(means over objects {sorted(set(args.only))} only)")
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps({"rows": rows, "summary": summary}, indent=1))
    return 0


def summarise(rows: list[dict], waits: float) -> dict:
    """Per object means (s): played, KTO-only and reference cycles against the floor."""

    def mean(key) -> float:  # noqa: ANN001
        return float(np.mean([key(r) for r in rows]))

    floor = waits + mean(lambda r: r["motion_floor_s"])
    played = waits + mean(lambda r: r["pick"]["played_s"] + r["move"]["played_s"])
    reference = waits + mean(
        lambda r: r["pick"]["reference_s"] + r["move"]["reference_s"]
    )
    return {
        "waits_s": waits,
        "floor_s": floor,
        "played_s": played,
        "played_ratio": played / floor,
        "reference_s": reference,
        "reference_ratio": reference / floor,
        "reference_gain_s": played - reference,
    }


def print_tables(rows: list[dict], summary: dict) -> None:
    """The per-object table (markdown; KTO cells ``own T / retimed``) and the cycle."""
    head = (
        "| object | pick played | pick KTO (acc. bounds) | pick KTO (jerk bounds) "
        "| pick floor | MOVE played "
        "| MOVE KTO (acc. bounds) | MOVE KTO (jerk bounds) | MOVE floor "
        "| reference motion | floor motion | valid (pick, MOVE) | KTO CPU s |"
    )
    print(head)
    print("|---|" + "---:|" * 10 + "---|---:|")

    def kto(part: dict) -> str:
        return f"{part['kto_T_s']:.3f} / {part['kto_s']:.3f}"

    for r in rows:
        p, m = r["pick"], r["move"]
        cells = [
            f"{p['played_s']:.3f}", kto(p["acc"]), kto(p["jerk"]),
            f"{r['pick_floor_s']:.3f}",
            f"{m['played_s']:.3f}", kto(m["acc"]), kto(m["jerk"]),
            f"{r['move_floor_s']:.3f}",
            f"{p['reference_s'] + m['reference_s']:.3f}",
            f"{r['motion_floor_s']:.3f}",
            ", ".join(str(x[k]["valid"]) for x in (p, m) for k in ("acc", "jerk")),
            f"{p['cpu_s']:.1f} + {m['cpu_s']:.1f}",
        ]  # fmt: skip
        print(f"| {r['object']} | " + " | ".join(cells) + " |")
    s = summary
    print(
        f"per object: waits {s['waits_s']:.3f}, floor {s['floor_s']:.3f}; played "
        f"{s['played_s']:.3f} ({s['played_ratio']:.4f}); reference "
        f"{s['reference_s']:.3f} ({s['reference_ratio']:.4f}), "
        f"{s['reference_gain_s']:.3f} s less"
    )


if __name__ == "__main__":
    sys.exit(main())
