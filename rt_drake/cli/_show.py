"""rt-drake show SCENARIO [--html FILE] [--wait]: the cell in Meshcat.

Builds the scenario's plant (robot at home, objects at their start poses, or
at their goals with --goals), publishes it to Drake's Meshcat and, with
--html, writes a self-contained HTML file of the scene that opens offline
in a browser. --html is checked before anything is built (an .html, never
the scenario file) and written atomically.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from rt_drake.cli._output import output_file


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``show`` subcommand."""
    parser = subparsers.add_parser(
        "show",
        help="show a scenario's cell in Meshcat; optionally save it as HTML",
        description=__doc__,
    )
    parser.add_argument(
        "scenario",
        help="scenario YAML file, or the name of a shipped one (stack_four_objects)",
    )
    parser.add_argument(
        "--html", type=Path, help="write the scene as a standalone HTML file"
    )
    parser.add_argument(
        "--goals", action="store_true", help="show the objects at their goal poses"
    )
    parser.add_argument(
        "--wait",
        action="store_true",
        help="keep serving Meshcat until Ctrl-C (the default without --html)",
    )
    parser.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    """Show the scene; return 0."""
    from pydrake.geometry import StartMeshcat

    from rt_drake.atomic_file import write_text_atomically
    from rt_drake.model.resources import resolve_scenario_path
    from rt_drake.model.scenario import load_scenario
    from rt_drake.simulation.visualization import publish_scene

    path = resolve_scenario_path(args.scenario)
    if args.html is not None:
        output_file(args.html, "--html", ".html", {"scenario file": path})
    scenario = load_scenario(path)
    meshcat = StartMeshcat()
    publish_scene(scenario, meshcat, at_goals=args.goals)
    print(f"Meshcat: {meshcat.web_url()}")
    if args.html is not None:
        write_text_atomically(args.html, meshcat.StaticHtml())
        print(f"wrote {args.html}")
    if args.wait or args.html is None:
        print("serving until Ctrl-C")
        try:
            while True:
                time.sleep(1.0)
        except KeyboardInterrupt:
            pass
    return 0
