"""rt-drake retime SCENARIO --waypoints FILE.csv --object NAME --out FILE.npz.

Retimes the clamped C2 spline through joint-space waypoints (one row per
waypoint, one column per joint, rad; # starts a comment) time-optimally
under the scenario's joint limits and, unless --no-grasp-constraint, the
grasp stability of the named object held by the scenario's cup, or by its
multi-cup tool (tool:; its set for tool.load_sharing, by default the rims'
spring split, with robot.cup_frame as the tool frame T): of every object of
its uncertainty set (and every cup of the cup's friction and suction range)
if the scenario gives one or the flags --mass-uncertainty,
--com-uncertainty, --inertia-uncertainty do (one cup only). Writes an .npz
from which anyone can re-check the result (the trajectory file format:
samples every 1 ms of t, q, qd, qdd and the cup's pose X_WC, the object's
inertia, the grasp constraint F, g, the cup, the path and its s'(s)
profile). The scenario's robot.jerk_limits, when it gives them, limit the
joint jerk too (the path acceleration is then continuous); --no-jerk-limits
drops them. --out is checked before any work (a .npz, never an input) and
written atomically.
"""

from __future__ import annotations

import argparse
import dataclasses
from pathlib import Path

import numpy as np

from rt_drake.cli._args import add_jerk_flag
from rt_drake.cli._output import output_file
from rt_drake.errors import InputError
from rt_drake.model.held import held_object_of

#: Largest number of waypoints read from a CSV.
MAX_WAYPOINTS = 100_000
#: Largest waypoint file read, bytes.
MAX_WAYPOINT_BYTES = 64 * 2**20


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``retime`` subcommand."""
    parser = subparsers.add_parser(
        "retime",
        help="retime a joint-space path time-optimally under grasp stability",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument("scenario", help="scenario YAML file (or a shipped one's name)")
    parser.add_argument(
        "--waypoints", type=Path, required=True, help="CSV of joint waypoints (rad)"
    )
    parser.add_argument("--object", required=True, help="name of the held object")
    parser.add_argument(
        "--no-grasp-constraint",
        action="store_true",
        help="joint limits only (the object is still recorded)",
    )
    parser.add_argument(
        "--mass-uncertainty",
        type=float,
        metavar="R",
        help="relative half-width of the object's mass (overrides the scenario's)",
    )
    parser.add_argument(
        "--com-uncertainty",
        type=_three_floats,
        metavar="DX,DY,DZ",
        help="half-widths (m) of its centre of mass along the object's axes",
    )
    parser.add_argument(
        "--inertia-uncertainty",
        type=float,
        metavar="R",
        help="relative half-width of each of its principal moments of inertia",
    )
    parser.add_argument(
        "--gridpoints", type=int, default=100, help="TOPP-RA grid points (default 100)"
    )
    add_jerk_flag(parser)
    parser.add_argument("--out", type=Path, required=True, help="output .npz file")
    parser.set_defaults(run=run)


def _three_floats(text: str) -> list[float]:
    """``DX,DY,DZ``: three numbers separated by commas."""
    import argparse as _argparse

    parts = text.split(",")
    try:
        values = [float(p) for p in parts]
    except ValueError:
        raise _argparse.ArgumentTypeError(
            f"expected three numbers DX,DY,DZ (m), got {text!r}"
        ) from None
    if len(values) != 3:
        raise _argparse.ArgumentTypeError(
            f"expected three numbers DX,DY,DZ (m), got {text!r}"
        )
    return values


def object_uncertainty(args: argparse.Namespace, obj):  # noqa: ANN001, ANN201
    """The object's uncertainty set: the scenario's, with the flags' widths.

    Returns None when neither gives one. Bad widths raise InputError naming
    the key and value; the CoM box must stay inside the object.
    """
    from rt_drake.model.object_geometry import object_box
    from rt_drake.types.object_uncertainty import ObjectUncertainty

    flags = {
        "mass": args.mass_uncertainty,
        "com": args.com_uncertainty,
        "inertia": args.inertia_uncertainty,
    }
    if obj.uncertainty is None and all(v is None for v in flags.values()):
        return None
    base = obj.uncertainty or ObjectUncertainty()
    fields = {
        "mass": base.mass,
        "com": list(base.com),
        "inertia": base.inertia,
        **{k: v for k, v in flags.items() if v is not None},
    }
    uncertainty = ObjectUncertainty(**fields)
    if any(uncertainty.com):
        uncertainty.check_inside(*object_box(obj.model, obj.name))
    return uncertainty


def read_waypoints(path: Path, joints: int) -> np.ndarray:
    """Read a (K, joints) waypoint CSV; InputError naming the problem."""
    if path.is_dir():
        raise InputError(f"waypoint file '{path}' is a directory")
    if not path.is_file():
        raise InputError(f"waypoint file '{path}' does not exist")
    if path.stat().st_size > MAX_WAYPOINT_BYTES:
        raise InputError(
            f"{path}: {path.stat().st_size} bytes; a waypoint file is at most "
            f"{MAX_WAYPOINT_BYTES} bytes"
        )
    try:
        text = path.read_bytes().decode("utf-8")
    except UnicodeDecodeError as error:
        raise InputError(f"{path}: not UTF-8 text (byte {error.start})") from None
    if not text.strip() or all(
        not line.strip() or line.lstrip().startswith("#") for line in text.splitlines()
    ):
        raise InputError(f"{path}: no waypoints (empty file)")
    try:
        waypoints = np.loadtxt(text.splitlines(), delimiter=",", comments="#", ndmin=2)
    except ValueError as error:
        message = " ".join(str(error).split())
        raise InputError(f"{path}: not a CSV of numbers: {message}") from None
    if len(waypoints) > MAX_WAYPOINTS:
        raise InputError(
            f"{path}: {len(waypoints)} waypoints; at most {MAX_WAYPOINTS} are read"
        )
    if waypoints.shape[1] != joints:
        raise InputError(
            f"{path}: {waypoints.shape[1]} columns but the robot has {joints} joints"
        )
    if waypoints.shape[0] < 2:
        raise InputError(f"{path}: need at least 2 waypoints, got {waypoints.shape[0]}")
    bad = np.flatnonzero(~np.all(np.isfinite(waypoints), axis=1))
    if bad.size:
        raise InputError(
            f"{path}: waypoint {bad[0] + 1} is not finite: {waypoints[bad[0]]}"
        )
    return waypoints


def run(args: argparse.Namespace) -> int:
    """Retime, write the .npz and print a summary; return 0."""
    from rt_drake.model.resources import resolve_scenario_path

    path = resolve_scenario_path(args.scenario)
    output_file(  # before the heavy imports: a quick refusal
        args.out,
        "--out",
        ".npz",
        {"scenario file": path, "waypoint file": args.waypoints},
    )

    from rt_drake import (
        CupFrame,
        CupParameters,
        GraspConstraint,
        JointLimits,
        ToolParameters,
        load_scenario,
        path_waypoints_and_knots,
        retime,
        sample_trajectory,
        save_trajectory,
    )
    from rt_drake.model.plant import make_arm_plant
    from rt_drake.retiming import RetimeResult, retime_for_ring
    from rt_drake.retiming.grid import MAX_GRIDPOINTS
    from rt_drake.simulation.move_grasp import ring_tool

    if not 2 <= args.gridpoints <= MAX_GRIDPOINTS:
        raise InputError(
            f"--gridpoints must be in [2, {MAX_GRIDPOINTS}], got {args.gridpoints}"
        )
    scenario = load_scenario(path)
    obj = scenario.object(args.object)
    plant = make_arm_plant(scenario)
    waypoints = read_waypoints(args.waypoints, plant.num_positions())
    try:
        _, knots = path_waypoints_and_knots(waypoints)
    except InputError as error:  # e.g. two equal rows: name the file
        raise InputError(f"{args.waypoints}: {error}") from None
    held = held_object_of(obj)
    obj = dataclasses.replace(obj, uncertainty=object_uncertainty(args, obj))
    uncertain = obj.uncertainty is not None and not obj.uncertainty.is_zero()
    cup_model: CupParameters | ToolParameters
    grasp: GraspConstraint | None = None
    if scenario.tool is None or uncertain:
        cup_model = scenario.single_cup("an object's uncertainty set")
        if not args.no_grasp_constraint:
            grasp = GraspConstraint.for_scenario_object(obj, cup_model)
    else:
        cup_model = scenario.tool_parameters()
        if not args.no_grasp_constraint:
            grasp = GraspConstraint.for_tool(
                held, cup_model, load_sharing=scenario.tool.load_sharing
            )
    limits = JointLimits.from_plant(plant, scenario.robot, jerk=not args.no_jerk_limits)
    cup = CupFrame.of(plant, scenario.robot.cup_frame)
    ring = None if grasp is None else ring_tool(scenario, uncertain)
    ring_words = ""
    if grasp is not None and ring is not None:  # planning.grasp_margin: ring

        def retime_with(shrunk: GraspConstraint) -> RetimeResult:
            return retime(plant, waypoints, limits, shrunk, args.gridpoints, cup=cup)

        found = retime_for_ring(retime_with, waypoints, grasp, ring, plant, cup=cup)
        result, grasp = found.result, found.grasp
        ring_words = (
            f", grasp margin {found.margin:.3f} for the bellows' ring (D "
            f"{found.load.factor:.2f}, {found.retimes} retimes)"
        )
    else:
        if grasp is not None:
            grasp = grasp.with_margin(scenario.planning.fixed_margin)
        result = retime(plant, waypoints, limits, grasp, args.gridpoints, cup=cup)
    saved = sample_trajectory(
        plant, result, held, grasp, cup_model, obj.name, waypoints, knots,
        cup_frame=cup.frame,
    )  # fmt: skip
    save_trajectory(args.out, saved)
    constraint = "joint limits only" if grasp is None else "grasp constraint"
    if isinstance(cup_model, ToolParameters):
        count = len(cup_model.cups)
        constraint += f", a tool of {count} cup{'s' if count != 1 else ''}"
    if grasp is not None and grasp.is_robust:
        constraint = (
            f"robust grasp constraint: {grasp.guarantee()}; "
            f"{result.grasp_rows} rows of {result.grasp_objects} vertex objects"
        )
    if limits.jerk is not None:
        constraint += ", jerk limits"
    constraint += ring_words
    # A binding constraint is at 0 to the LP's tolerance (about -1e-12): no "-0.000".
    margin = round(float(result.margin.min()), 3) + 0.0
    print(
        f"{obj.name}: {len(waypoints)} waypoints retimed to {result.duration:.3f} s "
        f"({constraint}, {args.gridpoints} grid points, min margin "
        f"{margin:.3f}); wrote {args.out}"
    )
    return 0
