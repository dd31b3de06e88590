"""Argument types of the ``rt-drake`` subcommands: each rejects a bad value.

argparse calls a type with the flag's text; a ``ValueError`` or
``argparse.ArgumentTypeError`` becomes the one-line usage error
``rt-drake <command>: error: argument --flag: <message>`` with exit code 2.
"""

from __future__ import annotations

import argparse
import math


def positive_int(text: str) -> int:
    """An integer >= 1."""
    value = _parse(text, int, "an integer")
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be >= 1, got {text}")
    return value


def _parse(text: str, kind: type, what: str):  # noqa: ANN202
    try:
        value = kind(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not {what}") from None
    if isinstance(value, float) and not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"must be finite, got {text}")
    return value


def add_optimize_flag(parser: argparse.ArgumentParser, what: str) -> None:
    """``--optimize`` / ``--no-optimize`` (default: the scenario's ``planning``)."""
    parser.add_argument(
        "--optimize",
        action=argparse.BooleanOptionalAction,
        default=None,
        help=f"{what} (default: the scenario's planning.optimize_move)",
    )


__all__ = ["add_optimize_flag", "positive_int"]
