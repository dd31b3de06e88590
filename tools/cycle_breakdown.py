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
  path, ``(c) - floor`` the path's (its shape and its vertical ends) at the
  joint limits alone;
- the MOVE's floor with its vertical ends (``--end-height``, m, default
  0.02: every MOVE of the default scenario, spline or shaped, rises and
  sets down vertically over at least 2 cm): the lift from rest to the top
  of its end line (top free), the transit between the two lines' tops
  (joint speeds bounded by the lines' tangents there,
  :func:`~rt_drake.retiming.junction_speeds`) and the set-down to rest,
  each bounded by :func:`~rt_drake.retiming.segment_floor` as the pick's
  retreat, transit and descent are. It is still a lower bound for any MOVE
  through those lines; the reported floor leaves the ends out.

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
from pydrake.math import RigidTransform

from rt_drake.dynamics.cup_frame import CupFrame
from rt_drake.experiments import cycle_floors
from rt_drake.model.plant import make_arm_plant
from rt_drake.model.resources import resolve_scenario_path
from rt_drake.model.scenario import load_scenario
from rt_drake.retiming import JointLimits, junction_speeds, segment_floor
from rt_drake.shaping import retime_adaptive
from rt_drake.simulation.online_motions import OnlineMotions, time_at


def raised(motions: OnlineMotions, q: np.ndarray, height: float) -> np.ndarray:
    """The configuration with the cup ``height`` m straight above its pose at q."""
    X_WC = motions.planner.scene.cup_pose(q)
    X_up = RigidTransform(X_WC.rotation(), X_WC.translation() + [0.0, 0.0, height])
    q_up = motions.planner.ik.solve(X_up, q, q)
    if q_up is None:
        raise SystemExit(f"no IK {height} m above {q.round(3).tolist()}")
    return q_up


def move_floor_with_ends(
    motions: OnlineMotions,
    q_grasp: np.ndarray,
    q_place: np.ndarray,
    height: float,
    limits: JointLimits,
    jerk: np.ndarray | None,
) -> float:
    """Floor (s) of a MOVE that rises and sets down vertically over ``height`` m."""
    q_up, q_down = raised(motions, q_grasp, height), raised(motions, q_place, height)
    below_up = raised(motions, q_grasp, height - 0.005)
    below_down = raised(motions, q_place, height - 0.005)
    transit = q_down - q_up
    speed_start = junction_speeds(q_up - below_up, transit, limits)
    speed_end = junction_speeds(below_down - q_down, -transit, limits)
    lift = segment_floor(q_grasp, q_up, limits, 0.0, np.inf, jerk)
    middle = segment_floor(q_up, q_down, limits, speed_start, speed_end, jerk)
    lower = segment_floor(q_down, q_place, limits, np.inf, 0.0, jerk)
    return float(lift + middle + lower)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenario", nargs="?", default="stack_four_objects")
    parser.add_argument("--no-jerk-limits", action="store_true")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--end-height", type=float, default=0.02)
    args = parser.parse_args()
    scenario = load_scenario(resolve_scenario_path(args.scenario))
    jerk_on = not args.no_jerk_limits and bool(scenario.robot.jerk_limits)
    motions = OnlineMotions(scenario, seed=args.seed, jerk_limits=jerk_on)
    jerk = np.array(scenario.robot.jerk_limits) if jerk_on else None
    floors = cycle_floors(scenario, args.seed, jerk=jerk)
    bare_floors = cycle_floors(scenario, args.seed)
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
        ends = move_floor_with_ends(
            motions, q_grasp, move.q_end, args.end_height, limits, jerk
        )
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
                ends,
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
        "floor with ends",
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
