"""The cycle's floor: how fast the arm's joint limits let any cycle of a scenario go.

    python tools/cycle_floor.py [SCENARIO] [--optimize | --no-optimize]

Plans the cycle as ``rt-drake run`` does (the picks blended, each MOVE under
the grasp constraint, shaped unless --no-optimize), without the physics, and
sets each motion's retimed duration beside a lower bound that holds for *any*
path through the same rest configurations (home, grasp, place), the same
vertical lines (the retreat above a placed object, the descent over
``approach_offset``) and the arm's velocity and acceleration limits alone,
without the grasp constraint.

Bounds per joint j (limits v_j, a_j; a joint that moves by d):

- rest to rest: ``d / v + v / a`` if ``d >= v^2 / a``, else ``2 sqrt(d / a)``;
- one end at rest, the other free: ``d / v + v / (2 a)`` if ``d >= v^2 / (2
  a)``, else ``sqrt(2 d / a)``;
- neither end at rest: ``d / v``.

A motion's floor is the largest of its joints' bounds. The pick (retreat,
transit, descent) is three segments in sequence, each bounded on its own:

- the retreat from rest and the descent to rest, per joint over the line's
  own joint motion ("strict"), and also by the retimer along the line itself,
  the free end at the fastest speed it admits ("along the line": TOPP-RA on
  200 points, tight but discretised, so not a strict bound);
- the transit between the retreat's top and the approach pose: J1 is at rest
  at both (on a vertical line of this arm's cup J1 stays constant: the
  script prints how much it moves), and so is every joint that reverses
  there (its transit motion opposes its motion on the line: its velocity
  passes through 0 at the line's end or beyond it, where it covers at
  least the same distance).

A MOVE's floor is rest to rest from grasp to place (its vertical ends left
out, so the bound is lower still). Per object, the floor plus the vacuum's
fixed waits is the fastest cycle any planner, shaping or retimer could give
with these configurations and limits.

``rt-drake run`` reports the strict floor of each object (``floor_s``,
:func:`rt_drake.experiments.cycle_floors`, which bounds the joints' speeds
at the lines' ends by the lines' tangents instead of setting J1 at rest,
and counts the MOVE's lift and set-down lines as the pick's: its MOVE floor
is above this study's); this study adds the "along the line" figures and
the planned durations.
"""

from __future__ import annotations

import argparse
import sys

import numpy as np
from pydrake.multibody.plant import MultibodyPlant

from rt_drake.errors import RtDrakeError
from rt_drake.model.plant import make_arm_plant
from rt_drake.model.resources import resolve_scenario_path
from rt_drake.model.scenario import load_scenario
from rt_drake.planning import GeometricPath
from rt_drake.retiming import JointLimits, joint_floor, retime
from rt_drake.simulation.online_motions import OnlineMotions, time_at


def per_joint(d: np.ndarray, limits: JointLimits, rest: np.ndarray) -> np.ndarray:
    """Least time (s) for each joint to move by ``d``, ``rest`` of its ends at rest.

    :func:`rt_drake.retiming.joint_floor` (0: at rest, inf: free).
    """
    rest = np.asarray(rest)
    speed_from = np.where(rest >= 1, 0.0, np.inf)
    speed_to = np.where(rest == 2, 0.0, np.inf)
    return joint_floor(d, limits, speed_from, speed_to)


def along_line(
    chain: np.ndarray, plant: MultibodyPlant, limits: JointLimits, free_start: bool
) -> float:
    """TOPP-RA time (s) along a line's IK chain, one end at rest, the other free."""
    line = GeometricPath.from_waypoints(chain)
    s_free = 0.0 if free_start else 1.0
    tangent = np.abs(line.deriv(s_free).ravel())
    low, high = 0.0, float(np.min(limits.velocity / np.maximum(tangent, 1e-12)))

    def timed(speed: float) -> float:
        ends = {"sd_start": speed} if free_start else {"sd_end": speed}
        return retime(plant, line, limits, None, gridpoints=200, **ends).duration

    for _ in range(30):  # the fastest free-end speed the retimer admits
        middle = 0.5 * (low + high)
        try:
            timed(middle)
            low = middle
        except RtDrakeError:
            high = middle
    return timed(low)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenario", nargs="?", default="stack_four_objects")
    parser.add_argument(
        "--optimize",
        action=argparse.BooleanOptionalAction,
        default=None,
        help="shape the MOVEs (default: the scenario's planning.optimize_move)",
    )
    args = parser.parse_args()
    scenario = load_scenario(resolve_scenario_path(args.scenario))
    motions = OnlineMotions(scenario, optimize=args.optimize)
    plant = make_arm_plant(scenario)
    limits = JointLimits.from_plant(plant, scenario.robot)
    waits = scenario.vacuum.attach_s + scenario.vacuum.detach_s
    q = motions.q_home
    totals = np.zeros(5)
    for index, obj in enumerate(scenario.objects):
        retreat = index > 0
        pick = motions.pick(q, obj, retreat=retreat)
        planned = motions.planner.plan_pick(q, obj.name, retreat)
        path = planned.path.path
        q_top = path.value(planned.s_retreat).ravel()
        q_approach = path.value(planned.s_approach).ravel()
        descent = np.asarray(planned.path.descent)
        q_grasp = descent[-1]
        transit = q_approach - q_top
        # at rest at the approach pose: J1, and every joint the descent reverses
        rest_end = (np.sign(descent[1] - descent[0]) * np.sign(transit) < 0).astype(int)
        rest_end[0] = 1
        if retreat:
            rest_start = (np.sign(q_top - q) * np.sign(transit) < 0).astype(int)
            rest_start[0] = 1
            retreat_strict = per_joint(q_top - q, limits, np.ones(6, int)).max()
            top = path.value(np.linspace(0.0, planned.s_retreat, 20))
            retreat_line = along_line(top, plant, limits, free_start=False)
        else:
            rest_start = np.ones(6, int)  # the arm starts at rest
            retreat_strict = retreat_line = 0.0
        transit_floor = per_joint(transit, limits, rest_start + rest_end).max()
        descent_strict = per_joint(q_grasp - q_approach, limits, np.ones(6, int)).max()
        descent_line = along_line(descent, plant, limits, free_start=True)
        pick_strict = retreat_strict + transit_floor + descent_strict
        pick_line = retreat_line + transit_floor + descent_line
        move = motions.move(q_grasp, obj, pick)
        q_place = move.trajectory.value(move.trajectory.end_time()).ravel()
        move_floor = per_joint(q_place - q_grasp, limits, np.full(6, 2)).max()
        pick_s, move_s = pick.trajectory.end_time(), move.trajectory.end_time()
        totals += [pick_s, pick_strict, pick_line, move_s, move_floor]
        print(
            f"{obj.name:14s} pick {pick_s:.3f} s, floor {pick_strict:.3f} strict / "
            f"{pick_line:.3f} along the lines (retreat {retreat_line:.3f}, transit "
            f"{transit_floor:.3f}, descent {descent_line:.3f}; REACH part "
            f"{pick_s - time_at(pick.retimed, planned.s_approach):.3f}; J1 moves "
            f"{np.ptp(descent[:, 0]):.1e} rad on the descent) | MOVE {move_s:.3f} s, "
            f"floor {move_floor:.3f}"
        )
        q = q_place
    mean = totals / len(scenario.objects)
    pick_s, pick_strict, pick_line, move_s, move_floor = mean
    cycle = pick_s + move_s + waits
    strict, lines = pick_strict + move_floor + waits, pick_line + move_floor + waits
    print(
        f"mean per object: pick {pick_s:.3f} (floor {pick_strict:.3f} / "
        f"{pick_line:.3f}), MOVE {move_s:.3f} (floor {move_floor:.3f}); with the "
        f"{waits:g} s of fixed waits: planned {cycle:.3f} s, floor {strict:.3f} s "
        f"strict / {lines:.3f} s along the lines"
    )


if __name__ == "__main__":
    sys.exit(main())
