"""rt-drake plan SCENARIO --object NAME: collision-free paths of one cycle.

Plans APPROACH (from the robot's home), REACH and MOVE for object NAME from
its start pose to its goal pose, prints each phase's timing breakdown and,
with --out, writes the chosen phase's joint waypoints as CSV (one row per
waypoint, radians; # header). The planned path is the clamped cubic spline
through those waypoints with chord-length knots, the input of
rt-drake retime SCENARIO --waypoints FILE.csv --object NAME.

Objects listed before NAME in the scenario are taken as already placed at
their goals (the cycle's order); the others rest at their starts. --out is
checked before planning (a .csv, never the scenario file) and written
atomically.

The MOVE is then shaped for speed under the grasp constraint (the
scenario's planning.optimize_move, on by default; --no-optimize keeps the
planner's spline MOVE, --optimize forces the shaping): the command prints
the spline and the shaped MOVE's durations (both retimed on the
optimiser's adaptive grid) and --out writes the shaped waypoints. The
shaping scores a fixed number of paths (planning.max_evaluations), so the
same seed gives the same path on an idle or a loaded machine.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from rt_drake.cli._args import add_optimize_flag, nonnegative_int, positive_float
from rt_drake.cli._output import output_file
from rt_drake.model.held import held_object_of

PHASES = ("approach", "reach", "move")


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``plan`` subcommand."""
    parser = subparsers.add_parser(
        "plan",
        help="plan the collision-free APPROACH, REACH and MOVE paths of an object",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument(
        "scenario",
        help="scenario YAML file (or a shipped one's name, e.g. stack_four_objects)",
    )
    parser.add_argument("--object", required=True, help="name of the object to move")
    parser.add_argument(
        "--phase",
        choices=(*PHASES, "all"),
        default="all",
        help="phase whose waypoints --out writes (all: plan every phase, write MOVE)",
    )
    parser.add_argument(
        "--seed", type=nonnegative_int, default=0, help="planner seed (default 0)"
    )
    parser.add_argument(
        "--budget",
        type=positive_float,
        default=1.0,
        help="time budget per phase, s (default 1, at most 600)",
    )
    add_optimize_flag(parser, "shape the MOVE for speed under the grasp constraint")
    parser.add_argument("--out", type=Path, help="write the waypoints to this CSV file")
    parser.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    """Plan, print the timings, write the CSV; return 0."""
    from rt_drake.model.resources import resolve_scenario_path

    scenario_path = resolve_scenario_path(args.scenario)
    if args.out is not None:  # before the heavy imports: a quick refusal
        output_file(args.out, "--out", ".csv", {"scenario file": scenario_path})

    import io

    import numpy as np

    from rt_drake.atomic_file import write_text_atomically
    from rt_drake.model.scenario import load_scenario
    from rt_drake.planning import CyclePlanner, PlannedPath

    scenario = load_scenario(scenario_path)
    scenario.object(args.object)
    planner = CyclePlanner(scenario, seed=args.seed, budget_s=args.budget)
    for obj in scenario.objects:
        if obj.name == args.object:
            break
        planner.set_object_pose(obj.name, obj.goal.GetDeterministicValue())
    wanted = PHASES.index("move" if args.phase == "all" else args.phase)
    plans: list[PlannedPath] = []
    for index in range(wanted + 1):
        if index == 0:
            plan = planner.plan_approach(planner.q_home, args.object)
        elif index == 1:
            plan = planner.plan_reach(plans[0].q_goal, args.object)
        else:  # the MOVE lifts along the REACH's descent
            plan = planner.plan_move(plans[1].q_goal, args.object, reach=plans[1])
        plans.append(plan)
        path = plan.path
        print(
            f"{plan.phase.label} {plan.object}: {len(path.waypoints)} waypoints, "
            f"{path.joint_length():.3f} rad; {plan.timing.summary()}"
        )
    optimize = args.optimize
    if optimize is None:
        optimize = scenario.planning.optimize_move
    if optimize and wanted == PHASES.index("move"):
        plans[wanted] = _optimized(scenario, planner, plans[wanted])
    chosen = plans[wanted]
    if args.out is not None:
        names = ",".join(
            planner.scene.plant.get_joint(j).name() for j in planner.scene.bounds.joints
        )
        text = io.StringIO()
        np.savetxt(
            text,
            chosen.path.waypoints,
            fmt="%.17g",
            delimiter=",",
            header=(
                f"rt-drake plan {args.scenario} --object {args.object} "
                f"--phase {chosen.phase.value} --seed {args.seed}\n"
                f"joint positions (rad), one waypoint per row: {names}"
            ),
        )
        write_text_atomically(args.out, text.getvalue())
        print(
            f"wrote {args.out} ({chosen.phase.label}, "
            f"{len(chosen.path.waypoints)} waypoints)"
        )
    return 0


def _optimized(scenario, planner, move):
    """The MOVE shaped for speed; prints both durations."""
    import dataclasses

    from pydrake.common.schema import Transform

    from rt_drake import (
        CupFrame,
        GraspConstraint,
        JointLimits,
        make_arm_plant,
    )
    from rt_drake.shaping import (
        MoveOptimizer,
        MoveOptimizerOptions,
        warm_up,
    )
    from rt_drake.simulation.move_grasp import move_polytope

    plant = make_arm_plant(scenario)
    limits = JointLimits.from_plant(plant, scenario.robot)
    obj = dataclasses.replace(scenario.object(move.object), grasp=Transform(move.X_OC))
    held = held_object_of(obj)
    grasp: GraspConstraint
    if scenario.tool is None:
        grasp = GraspConstraint.for_cup(held, scenario.cup)
    else:  # the set the cycle retimes a multi-cup tool's MOVE under
        grasp = GraspConstraint.for_polytope(held, move_polytope(scenario))
    warm_up()
    options = MoveOptimizerOptions.from_config(scenario.planning)
    cup = CupFrame.of(plant, scenario.robot.cup_frame)
    result = MoveOptimizer(plant, limits, options, cup).optimize(planner, move, grasp)
    verdict = "optimised" if result.improved else "kept (no faster path found)"
    print(
        f"MOVE {verdict}: {result.spline_duration:.3f} s -> {result.duration:.3f} s "
        f"({result.duration / result.spline_duration:.3f}x; both retimed under the "
        f"grasp constraint on the optimiser's grid), tilt up to "
        f"{result.max_tilt_deg:.1f} deg, {result.evaluations} paths scored in "
        f"{1e3 * result.wall_s:.0f} ms ({1e3 * result.cpu_s:.0f} ms of CPU)"
    )
    path = result.path
    return dataclasses.replace(move, path=path, polyline=path.waypoints)
