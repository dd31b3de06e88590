"""The ``rt-drake`` command.

Each subcommand lives in ``rt_drake.cli.<name>`` and exposes
``register(subparsers)``, which adds its parser and sets ``run`` (a callable
taking the parsed namespace and returning an exit code). Heavy imports happen
inside ``run`` so ``rt-drake --help`` stays fast.

Exit codes: 0 done; 2 bad input (argparse's usage errors, and every
:class:`~rt_drake.errors.RtDrakeError`, printed as one line
``rt-drake <command>: error: ...``); anything else is a bug in rt_drake: a
one-line notice, then Python's traceback.
"""

from __future__ import annotations

import argparse
import importlib
import logging
import sys
from collections.abc import Sequence
from typing import NoReturn

from rt_drake.errors import RtDrakeError

#: Subcommand modules, in the order ``--help`` lists them.
_COMMANDS: tuple[str, ...] = (
    "run",
    "experiment",
    "constraint",
    "plan",
    "retime",
    "export",
    "show",
)

#: Exit code for bad input (argparse uses the same).
EXIT_BAD_INPUT = 2


class _OneLineParser(argparse.ArgumentParser):
    """An ArgumentParser whose usage errors are one line (no usage dump), exit 2."""

    def error(self, message: str) -> NoReturn:
        """Print ``<prog>: error: <message>`` and exit with code 2."""
        self.exit(EXIT_BAD_INPUT, f"{self.prog}: error: {message}\n")


def build_parser() -> argparse.ArgumentParser:
    """Return the top-level parser with every subcommand registered.

    Subparsers inherit the parser class, so every level reports argument
    errors in one line.
    """
    parser = _OneLineParser(
        prog="rt-drake",
        description="Critically fast suction-cup pick-and-place on Drake.",
    )
    subparsers = parser.add_subparsers(dest="command", required=True)
    for name in _COMMANDS:
        importlib.import_module(f"rt_drake.cli._{name}").register(subparsers)
    _name_every_command(parser)
    return parser


def _name_every_command(parser: argparse.ArgumentParser) -> None:
    """Set each (sub)command's default ``prog``, the prefix of its errors.

    E.g. ``rt-drake experiment transport: error: ...``.
    """
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for subparser in action.choices.values():
                subparser.set_defaults(prog=subparser.prog)
                _name_every_command(subparser)


def main(argv: Sequence[str] | None = None) -> int:
    """Run ``rt-drake`` and return its exit code (see the module docstring)."""
    quiet_drake_info()
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exit_:  # usage errors (2), --help (0)
        return int(exit_.code or 0)
    try:
        return int(args.run(args) or 0)
    except RtDrakeError as error:
        message = " ".join(str(error).split())
        print(f"{args.prog}: error: {message}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except Exception:
        print(
            f"{args.prog}: internal error (a bug in rt-drake; please report it "
            "with the traceback below)",
            file=sys.stderr,
        )
        raise


def quiet_drake_info() -> None:
    """Show Drake's warnings and errors, not its INFO lines.

    Drake logs through the Python logger ``drake``; at INFO it announces,
    e.g., "Allocating contexts to support implicit context parallelism",
    which would precede the one error line of a refused input. A filter,
    not a level: importing pydrake resets the logger's level to INFO.
    """
    drake = logging.getLogger("drake")
    if _below_warning not in drake.filters:
        drake.addFilter(_below_warning)


def _below_warning(record: logging.LogRecord) -> bool:
    return record.levelno >= logging.WARNING


def main_exit() -> None:
    """Console-script entry point: ``sys.exit(main())``."""
    sys.exit(main())


if __name__ == "__main__":
    main_exit()
