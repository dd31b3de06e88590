"""rt-drake export TRAJ.npz --period SECONDS --out FILE: a controller's file.

Samples a trajectory file (written by rt-drake retime) every --period
seconds on a fixed grid from its start, and writes a ROS 2 bag (MCAP) of one
trajectory_msgs/msg/JointTrajectory (its points: positions, velocities,
accelerations, time_from_start), which Foxglove and ros2 bag read and a
joint_trajectory_controller takes, or a CSV (t, q_*, qd_*, qdd_*, one row
per sample). The end is padded with rest samples (the last pose, zero
velocity and acceleration) up to the next multiple of the period: the grid
is never cut short. The format follows --out's suffix (.mcap or .csv)
unless --format names it. Joint names: --joint-names, or those of the
--scenario's robot, renamed by its robot.joint_names. --out is checked
before any work (never an input) and written atomically.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from rt_drake.cli._args import positive_float


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``export`` subcommand."""
    parser = subparsers.add_parser(
        "export",
        help="write a trajectory as a ROS 2 bag (MCAP) or CSV at a controller's period",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument("trajectory", type=Path, help="trajectory .npz file")
    parser.add_argument(
        "--format",
        choices=("mcap", "csv"),
        help="file format (default: --out's suffix)",
    )
    parser.add_argument(
        "--period",
        type=positive_float,
        required=True,
        metavar="SECONDS",
        help="the controller's period, e.g. 0.008 (b-CAP slave mode) or 0.002 "
        "(UR RTDE at 500 Hz)",
    )
    parser.add_argument("--out", type=Path, required=True, help="output file")
    parser.add_argument(
        "--scenario",
        metavar="SCENARIO",
        help="scenario whose robot names the joints (and its robot.joint_names)",
    )
    parser.add_argument(
        "--joint-names",
        type=_names,
        metavar="A,B,...",
        help="the controller's joint names, one per joint (overrides the scenario's)",
    )
    parser.add_argument(
        "--topic",
        help="the bag's topic (default /joint_trajectory_controller/joint_trajectory)",
    )
    parser.set_defaults(run=run)


def _names(text: str) -> list[str]:
    """``A,B,...``: names separated by commas (spaces around them dropped)."""
    return [name.strip() for name in text.split(",")]


def run(args: argparse.Namespace) -> int:
    """Export the trajectory and print a summary; return 0."""
    from rt_drake.cli._output import output_file
    from rt_drake.errors import InputError
    from rt_drake.export import DEFAULT_TOPIC, ExportFormat, export_format
    from rt_drake.model.resources import resolve_scenario_path

    suffix = args.out.suffix.lstrip(".")
    kind = export_format(args.format or suffix, "--format (or --out's suffix)")
    scenario_path = (
        None if args.scenario is None else resolve_scenario_path(args.scenario)
    )
    output_file(
        args.out,
        "--out",
        kind.suffix,
        {"trajectory file": args.trajectory, "scenario file": scenario_path},
    )
    if args.joint_names is None and scenario_path is None:
        raise InputError(
            "give --scenario (its robot's joint names) or --joint-names A,B,..."
        )

    from rt_drake.export import export_trajectory
    from rt_drake.retiming import load_trajectory

    saved = load_trajectory(args.trajectory)
    names = args.joint_names
    if names is None and scenario_path is not None:
        names = scenario_joint_names(scenario_path)
    written = export_trajectory(
        args.trajectory,
        args.out,
        format=kind,
        period=args.period,
        joint_names=names,
        topic=args.topic or DEFAULT_TOPIC,
    )
    what = "ROS 2 bag" if kind is ExportFormat.MCAP else "CSV"
    print(
        f"{args.trajectory}: {saved.duration:.3f} s every {args.period:g} s "
        f"({', '.join(names)}); wrote {what} {written}"
    )
    return 0


def scenario_joint_names(path: Path) -> list[str]:
    """The controller's joint names of a scenario's robot (its map applied)."""
    from rt_drake.errors import InputError
    from rt_drake.export import controller_joint_names
    from rt_drake.model.plant import make_arm_plant
    from rt_drake.model.scenario import load_scenario

    scenario = load_scenario(path)
    try:
        return controller_joint_names(
            make_arm_plant(scenario), scenario.robot.joint_names
        )
    except InputError as error:
        raise InputError(f"{path}: {error}") from None
