"""Argument types of the ``rt-drake`` subcommands: each rejects a bad value.

argparse calls a type with the flag's text; a ``ValueError`` or
``argparse.ArgumentTypeError`` becomes the one-line usage error
``rt-drake <command>: error: argument --flag: <message>`` with exit code 2.
Every number must be finite (``nan``, ``inf`` are refused); ranges are
closed unless a bound is marked open.
"""

from __future__ import annotations

import argparse
import math
from collections.abc import Callable


def positive_int(text: str) -> int:
    """An integer >= 1."""
    return int_in(1)(text)


def nonnegative_int(text: str) -> int:
    """An integer >= 0 (e.g. a random seed)."""
    return int_in(0)(text)


def finite_float(text: str) -> float:
    """Any finite number."""
    return _parse(text, float, "a number")


def positive_float(text: str) -> float:
    """A finite number > 0."""
    return float_in(0.0, math.inf, low_open=True)(text)


def nonnegative_float(text: str) -> float:
    """A finite number >= 0."""
    return float_in(0.0, math.inf)(text)


def int_in(low: int, high: int | None = None) -> Callable[[str], int]:
    """The type of an integer in ``[low, high]`` (no upper bound if None)."""

    def parse(text: str) -> int:
        value = _parse(text, int, "an integer")
        if value < low or (high is not None and value > high):
            bounds = f">= {low}" if high is None else f"in [{low}, {high}]"
            raise argparse.ArgumentTypeError(f"must be {bounds}, got {text}")
        return value

    parse.__name__ = "integer"  # argparse names the type in some messages
    return parse


def float_in(low: float, high: float, low_open: bool = False) -> Callable[[str], float]:
    """The type of a finite number in ``[low, high]`` (``(low, high]`` if open)."""

    def parse(text: str) -> float:
        value = _parse(text, float, "a number")
        if value < low or (low_open and value == low) or value > high:
            if math.isinf(high):
                bounds = f"> {low:g}" if low_open else f">= {low:g}"
            else:
                bounds = f"{'(' if low_open else '['}{low:g}, {high:g}]"
                bounds = f"in {bounds}"
            raise argparse.ArgumentTypeError(f"must be {bounds}, got {text}")
        return value

    parse.__name__ = "number"
    return parse


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


def add_cup_physics_flag(parser: argparse.ArgumentParser) -> None:
    """``--cup-physics rim|bellows`` (default: the scenario's ``cup_physics``)."""
    parser.add_argument(
        "--cup-physics",
        choices=("rim", "bellows"),
        default=None,
        help="the simulated cup: rim (rigid points at the planner's model) or "
        "bellows (a compliant cup from models/cups, independent of the planner; "
        "default: the scenario's cup_physics.kind)",
    )


def add_jerk_flag(parser: argparse.ArgumentParser) -> None:
    """``--no-jerk-limits``: ignore the scenario's ``robot.jerk_limits``."""
    parser.add_argument(
        "--no-jerk-limits",
        action="store_true",
        help="ignore the scenario's robot.jerk_limits (the acceleration may jump)",
    )


__all__ = [
    "add_cup_physics_flag",
    "add_jerk_flag",
    "add_optimize_flag",
    "finite_float",
    "float_in",
    "int_in",
    "nonnegative_float",
    "nonnegative_int",
    "positive_float",
    "positive_int",
]
