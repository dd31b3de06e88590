"""rt-drake run [SCENARIO]: simulate the whole pick-and-place cycle.

Every object is approached, reached, attached, moved (planned and retimed
online, critically fast under the grasp constraint) and detached, in a Drake
simulation with suction physics. Prints the paper's Table II for this run
and writes report.json, report.md and replay.html (a Meshcat recording that
plays offline) into --out, checked before the simulation starts (a
directory, none of its files an input) and written atomically. Each object
and the cycle are set against their floor (floor_s: the least time the
arm's joint limits allow through the same configurations and vertical
lines, without the grasp, plus ATTACH and DETACH; floor_ratio: total /
floor). Each MOVE is shaped for speed unless --no-optimize (or the
scenario's planning.optimize_move: false). --export DIR also writes every
executed motion, <object>_pick and <object>_move, as a ROS 2 bag (.mcap)
or a CSV at --export-period (see rt-drake export).
"""

from __future__ import annotations

import argparse
from pathlib import Path

from rt_drake.cli._args import (
    add_cup_physics_flag,
    add_jerk_flag,
    add_optimize_flag,
    float_in,
    nonnegative_int,
)

#: The file written beside the report.
REPLAY_FILE = "replay.html"


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``run`` subcommand."""
    parser = subparsers.add_parser(
        "run",
        help="simulate the pick-and-place cycle and report its timing",
        description=__doc__,
    )
    parser.add_argument(
        "scenario",
        nargs="?",
        default="stack_four_objects",
        help="scenario YAML file or shipped name (default: stack_four_objects)",
    )
    parser.add_argument(
        "--out", type=Path, default=Path("out/run"), help="output directory"
    )
    parser.add_argument(
        "--meshcat",
        action="store_true",
        help="also keep serving the live Meshcat until Ctrl-C",
    )
    parser.add_argument(
        "--no-grasp-constraint",
        action="store_true",
        help="retime MOVE with joint limits only (objects may slip)",
    )
    parser.add_argument(
        "--speed",
        type=float_in(0.0, 100.0, low_open=True),
        default=1.0,
        metavar="FACTOR",
        help="play every MOVE FACTOR times faster than retimed (default 1, max 100)",
    )
    parser.add_argument(
        "--seed", type=nonnegative_int, default=0, help="planner seed (default 0)"
    )
    parser.add_argument(
        "--sequential-planning",
        action="store_true",
        help="plan each motion when its phase starts, as the paper did, instead "
        "of during the motion and wait before it (the arm waits for all of it)",
    )
    add_optimize_flag(parser, "shape each MOVE for speed")
    add_cup_physics_flag(parser)
    add_jerk_flag(parser)
    parser.add_argument(
        "--time-step",
        type=float_in(1e-4, 0.01),
        default=1e-3,
        metavar="SECONDS",
        help="simulation step, 0.0001 to 0.01 (default 0.001; smaller steps reduce "
        "the numerical creep of held objects, ~1.6 mm per MOVE at 1 ms)",
    )
    parser.add_argument(
        "--export",
        type=Path,
        metavar="DIR",
        help="also write every executed motion for a controller into DIR",
    )
    parser.add_argument(
        "--export-format",
        choices=("mcap", "csv"),
        default="mcap",
        help="format of the --export files (default mcap)",
    )
    parser.add_argument(
        "--export-period",
        type=float_in(1e-6, 1.0),
        default=0.002,
        metavar="SECONDS",
        help="sampling period of the --export files (default 0.002)",
    )
    parser.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    """Simulate, print the table, write the report; return 0."""
    import time

    import numpy as np
    from pydrake.geometry import StartMeshcat

    from rt_drake.atomic_file import write_text_atomically
    from rt_drake.cli._output import output_directory
    from rt_drake.cli._progress import Progress
    from rt_drake.cli._run_export import RecordingMotions, export_motions
    from rt_drake.experiments import (
        REPORT_FILES,
        RunSettings,
        cycle_floors,
        cycle_report,
        summary_line,
        table_markdown,
        write_report,
    )
    from rt_drake.model.resources import resolve_scenario_path
    from rt_drake.model.scenario import load_scenario
    from rt_drake.simulation import OnlineMotions, StationOptions, run_cycle
    from rt_drake.types.phase import Phase

    path = resolve_scenario_path(args.scenario)
    output_directory(
        args.out, "--out", (*REPORT_FILES, REPLAY_FILE), {"scenario file": path}
    )
    scenario = load_scenario(path).with_cup_physics(args.cup_physics)
    export = _export_plan(args, scenario, path)
    meshcat = StartMeshcat()
    motions = OnlineMotions(
        scenario,
        grasp_constraint=not args.no_grasp_constraint,
        move_speed=args.speed,
        seed=args.seed,
        optimize=args.optimize,
        jerk_limits=not args.no_jerk_limits,
    )
    recorder = None if export is None else RecordingMotions(motions)
    optimize = (
        scenario.planning.optimize_move if args.optimize is None else args.optimize
    )
    if optimize and args.no_grasp_constraint:  # said once, not a silent fallback
        print(
            "MOVE shaping off: it shapes under the grasp constraint, which "
            "--no-grasp-constraint turns off; the spline MOVEs are played"
        )
    phases = [p for p in Phase if p is not Phase.DONE]
    names = [o.name for o in scenario.objects]
    progress = Progress("rt-drake run", len(names) * len(phases), "phase")

    def show(index: int, phase: Phase) -> None:
        if phase is Phase.DONE:
            progress.step(len(names) * len(phases), "done")
            return
        where = f"object {index + 1}/{len(names)} {names[index]}: {phase.label}"
        progress.step(index * len(phases) + phases.index(phase), where)

    start = time.perf_counter()
    try:
        result = run_cycle(
            scenario,
            motions if recorder is None else recorder,
            meshcat=meshcat,
            options=StationOptions(time_step=args.time_step),
            pipelined=not args.sequential_planning,
            progress=show,
        )
    finally:
        progress.close()
    wall_s = time.perf_counter() - start
    settings = RunSettings(
        scenario=str(path),
        grasp_constraint=not args.no_grasp_constraint,
        speed=args.speed,
        pipelined_planning=not args.sequential_planning,
        vacuum=scenario.vacuum.model,
        time_step_s=args.time_step,
        sim_time_s=result.sim_time,
        max_tracking_error_rad=result.max_tracking_error,
        simulation_wall_s=wall_s,
        cup_physics=scenario.cup_physics.kind,
    )
    # the floor under the same limits as the motions: the jerk's too if applied
    jerk = [] if args.no_jerk_limits else scenario.robot.jerk_limits
    floors = cycle_floors(
        scenario,
        args.seed,
        jerk=np.array(jerk) if jerk else None,
        shaped=optimize and not args.no_grasp_constraint,
    )
    report = cycle_report(result.records, settings, floors)
    json_path, md_path = write_report(report, args.out)
    replay = args.out / REPLAY_FILE
    write_text_atomically(replay, meshcat.StaticHtml())
    print(table_markdown(report))
    for entry in report.objects:
        print(f"MOVE {entry.name} holds {entry.guarantee}")
    print(f"{summary_line(report)}; simulated in {wall_s:.1f} s wall")
    print(f"wrote {json_path}, {md_path}, {replay}")
    if recorder is not None and export is not None:
        written = export_motions(recorder.motions, args.export, *export)
        print(f"exported {len(written)} motions to {args.export}")
    if args.meshcat:
        print(f"Meshcat: {meshcat.web_url()} (Ctrl-C to stop)")
        try:
            while True:
                time.sleep(1.0)
        except KeyboardInterrupt:
            pass
    return 0


def _export_plan(args: argparse.Namespace, scenario, path: Path):  # noqa: ANN001, ANN202
    """(format, period, joint names) of ``--export``, checked; None without it.

    The directory and its files are checked before the simulation starts.
    """
    if args.export is None:
        return None
    from rt_drake.cli._output import output_directory
    from rt_drake.cli._run_export import KINDS, export_file_name
    from rt_drake.errors import InputError
    from rt_drake.export import ExportFormat, controller_joint_names
    from rt_drake.model.plant import make_arm_plant

    kind = ExportFormat(args.export_format)
    files = [
        export_file_name(o.name, motion, kind)
        for o in scenario.objects
        for motion in KINDS
    ]
    output_directory(args.export, "--export", files, {"scenario file": path})
    try:
        names = controller_joint_names(
            make_arm_plant(scenario), scenario.robot.joint_names
        )
    except InputError as error:
        raise InputError(f"{path}: {error}") from None
    return kind, args.export_period, names
