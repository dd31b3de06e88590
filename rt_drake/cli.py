"""The ``rt-drake`` command.

Each subcommand lives in ``rt_drake.commands.<name>`` and exposes
``register(subparsers)``, which adds its parser and sets ``run`` (a callable
taking the parsed namespace and returning an exit code). Heavy imports happen
inside ``run`` so ``rt-drake --help`` stays fast.
"""

from __future__ import annotations

import argparse
import importlib
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
        importlib.import_module(f"rt_drake.commands.{name}").register(subparsers)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run ``rt-drake`` and return its exit code.

    Errors caused by input (``RtDrakeError``, ``ValueError``, a missing file)
    print one line, ``rt-drake <command>: error: <message>``, and return 2.
    """
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args.run(args) or 0)
    except (RtDrakeError, ValueError, FileNotFoundError) as error:
        message = " ".join(str(error).split())
        print(f"rt-drake {args.command}: error: {message}", file=sys.stderr)
        return EXIT_BAD_INPUT


def main_exit() -> None:
    """Console-script entry point: ``sys.exit(main())``."""
    sys.exit(main())


if __name__ == "__main__":
    main_exit()
