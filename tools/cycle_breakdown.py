"""Where a cycle's time goes: each motion's segments against their floors (issue 27).

    python tools/cycle_breakdown.py [SCENARIO] [--no-jerk-limits] [--seed N]

Plans and retimes the cycle as ``rt-drake run`` does (the same
:class:`~rt_drake.simulation.OnlineMotions`, the scenario's jerk limits
unless --no-jerk-limits), without the physics, and splits each object's
motion time into the floor's segments (:func:`rt_drake.experiments.cycle_floors`):

- the pick's retreat (to ``s_retreat``), transit (to ``s_approach``) and
  descent (to the grasp), each timed on the retimed pick
  (:func:`~rt_drake.simulation.online_motions.time_at`);
- the MOVE as run (shaped, grasp constraint, jerk limits), and the same
  geometric path retimed again (a) without the grasp, (b) without the jerk
  limits, (c) without either. ``as run - (a)`` is the grasp's price on that
  path, ``(c) - floor`` the path's shape at the joint limits alone, against
  the MOVE's floor, which counts its vertical lift and set-down lines
  (:mod:`rt_drake.experiments.cycle_floor`: the lift from rest to the top
  of its line, the carry between the lines' tops, the set-down to rest);
  "floor without lines" is rest to rest from grasp to place, as the report
  counted the MOVE before session 4.

Every retime here uses the cycle's grids (adaptive, see
:mod:`rt_drake.simulation.online_motions`), so the columns compare like
with like. The pick is retimed without the
grasp (no object held) and so has no grasp price; its ``no jerk`` column is
the same path at the acceleration limits.
The fixed waits (ATTACH, DETACH) are the scenario's and are printed apart.
"""

from __future__ import annotations

import argparse
import dataclasses
import sys

import numpy as np

from rt_drake.dynamics.cup_frame import CupFrame
from rt_drake.experiments import cycle_floors
from rt_drake.model.plant import make_arm_plant
from rt_drake.model.resources import resolve_scenario_path
from rt_drake.model.scenario import load_scenario
from rt_drake.retiming import JointLimits, segment_floor
from rt_drake.shaping import retime_adaptive
from rt_drake.simulation.online_motions import OnlineMotions, time_at


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenario", nargs="?", default="stack_four_objects")
    parser.add_argument("--no-jerk-limits", action="store_true")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    scenario = load_scenario(resolve_scenario_path(args.scenario))
    jerk_on = not args.no_jerk_limits and bool(scenario.robot.jerk_limits)
    motions = OnlineMotions(scenario, seed=args.seed, jerk_limits=jerk_on)
    jerk = np.array(scenario.robot.jerk_limits) if jerk_on else None
    shaped = scenario.planning.optimize_move
    floors = cycle_floors(scenario, args.seed, jerk=jerk, shaped=shaped)
    bare_floors = cycle_floors(scenario, args.seed, shaped=shaped)
    plant = make_arm_plant(scenario)
    cup = CupFrame.of(plant, scenario.robot.cup_frame)
    context = plant.CreateDefaultContext()
    limits = JointLimits.from_plant(plant, scenario.robot, jerk=jerk_on)
    no_jerk = dataclasses.replace(limits, jerk=None)

    def timed(path, grasp, jerk_limited: bool) -> float:  # noqa: ANN001
        """Duration (s) on the grids the cycle uses (OnlineMotions' docstring)."""
        profile = retime_adaptive(plant, path, no_jerk, grasp, context=context, cup=cup)
        if not jerk_limited:
            return profile.duration
        return motions.retime_on_profile(path, grasp, profile).duration

    q = motions.q_home
    rows = []
    for index, (obj, floor, bare) in enumerate(
        zip(scenario.objects, floors, bare_floors, strict=True)
    ):
        pick = motions.pick(q, obj, retreat=index > 0)
        planned = motions.planner.plan_pick(q, obj.name, index > 0)
        t_top = time_at(pick.retimed, planned.s_retreat) if index > 0 else 0.0
        t_app = time_at(pick.retimed, planned.s_approach)
        t_pick = pick.trajectory.end_time()
        pick_nojerk = timed(pick.planned.path, None, False)
        q_grasp = pick.q_end
        move = motions.move(q_grasp, obj, pick)
        path = move.planned.path
        move_s = move.trajectory.end_time()
        move_nograsp = timed(path, None, jerk_on)
        move_nojerk = timed(path, move.grasp, False)
        move_bare = timed(path, None, False)
        no_lines = segment_floor(q_grasp, move.q_end, limits, 0.0, 0.0, jerk)
        rows.append(
            (
                obj.name,
                t_top,
                floor.retreat_s,
                t_app - t_top,
                floor.transit_s,
                t_pick - t_app,
                floor.descent_s,
                pick_nojerk,
                move_s,
                move_nograsp,
                move_nojerk,
                move_bare,
                floor.move_s,
                bare.move_s,
                no_lines,
                t_pick + move_s,
                floor.motion_s,
                bare.motion_s,
            )
        )
        q = move.q_end
    head = (
        "object",
        "retreat",
        "floor",
        "transit",
        "floor",
        "descent",
        "floor",
        "pick no jerk",
        "MOVE",
        "no grasp",
        "no jerk",
        "neither",
        "floor",
        "floor no jerk",
        "floor without lines",
        "motion",
        "floor",
        "floor no jerk",
    )
    print("| " + " | ".join(head) + " |")
    print("|---|" + "---:|" * (len(head) - 1))
    for row in rows:
        print(f"| {row[0]} | " + " | ".join(f"{v:.3f}" for v in row[1:]) + " |")
    mean = np.mean([row[1:] for row in rows], axis=0)
    print("| mean | " + " | ".join(f"{v:.3f}" for v in mean) + " |")
    waits = scenario.vacuum.attach_s + scenario.vacuum.detach_s
    print(f"waits (ATTACH + DETACH, {scenario.vacuum.model}): {waits:.3f} s per object")


if __name__ == "__main__":
    sys.exit(main())
