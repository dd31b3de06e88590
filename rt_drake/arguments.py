"""Argument checks for the public API: one line naming the argument.

Every public function of rt_drake checks its arguments up front with these,
so bad input is refused with an :class:`~rt_drake.errors.InputError` (or the
subclass a package passes as ``error``) that reads

    is_realizable: F must be a (rows, 6) array of finite numbers, got list of shape (3,)

that is ``<where>: <name> must be <what is expected>, got <what was given>``,
instead of a ``TypeError`` or ``AttributeError`` from deep inside numpy or
Drake. Array-likes (lists, tuples) are accepted where numpy would accept them:
they are converted with ``np.asarray`` and then checked. Like
:mod:`rt_drake.errors`, this module imports numpy only, so the Drake-free
layers can use it.
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any

import numpy as np

from rt_drake.errors import InputError

#: A shape: one entry per axis, an int (that size), a str (any size >= 1,
#: named in the message, e.g. "rows"), or "..." first (any leading axes).
Shape = tuple[int | str, ...]


def describe(value: Any) -> str:
    """What a value is, in a few words: ``list of shape (3,)``, ``None``, ..."""
    if value is None:
        return "None"
    if isinstance(value, (bool, int, float, np.integer, np.floating, str)):
        text = repr(value.item() if isinstance(value, np.generic) else value)
        return f"{type(value).__name__} {text[:40]}"
    if isinstance(value, (list, tuple, np.ndarray)):
        try:
            array = np.asarray(value, dtype=float)
        except (TypeError, ValueError):
            return f"{type(value).__name__} of {len(value)} items, not a numeric array"
        text = f"{type(value).__name__} of shape {array.shape}"
        if array.ndim == 0 and not np.isfinite(array):
            text += f" with {array.item()}"
        elif not np.all(np.isfinite(array)):
            index = tuple(int(i) for i in np.argwhere(~np.isfinite(array))[0])
            text += f" with {array[index]} at {index}"
        return text
    return type(value).__name__


def fail(
    where: str, name: str, expected: str, value: Any, error: type[InputError]
) -> InputError:
    """The error ``<where>: <name> must be <expected>, got <value>``."""
    return error(f"{where}: {name} must be {expected}, got {describe(value)}")


def array(
    value: Any,
    name: str,
    shape: Shape,
    *,
    where: str,
    finite: bool = True,
    error: type[InputError] = InputError,
) -> np.ndarray:
    """Return ``value`` as a finite float array of ``shape``, or raise ``error``.

    Args:
        value: An array-like (a numpy array, nested lists or tuples).
        name: The argument's name, for the message.
        shape: The expected shape (:data:`Shape`), e.g. ``("rows", 6)``,
            ``("...", 6)``, ``(3, 3)``.
        where: The function or class that checks, for the message.
        finite: Whether NaN and inf are refused.
        error: The :class:`~rt_drake.errors.InputError` subclass to raise.
    """
    expected = f"a {_shape_text(shape)} array of {'finite ' * finite}numbers"
    if value is None or isinstance(value, (str, bytes)):
        raise fail(where, name, expected, value, error)
    try:
        result = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise fail(where, name, expected, value, error) from None
    if not _shape_matches(result.shape, shape) or (
        finite and not np.all(np.isfinite(result))
    ):
        raise fail(where, name, expected, value, error)
    return result


def number(
    value: Any,
    name: str,
    *,
    where: str,
    low: float | None = None,
    high: float | None = None,
    above: float | None = None,
    error: type[InputError] = InputError,
) -> float:
    """Return ``value`` as a finite float in range, or raise ``error``.

    ``low`` and ``high`` bound it inclusively, ``above`` strictly.
    """
    expected = "a finite number" + _range_text(low, high, above)
    if isinstance(value, bool) or not isinstance(
        value, (int, float, np.integer, np.floating)
    ):
        raise fail(where, name, expected, value, error)
    result = float(value)
    if not (
        math.isfinite(result)
        and (low is None or result >= low)
        and (high is None or result <= high)
        and (above is None or result > above)
    ):
        raise fail(where, name, expected, value, error)
    return result


def integer(
    value: Any,
    name: str,
    *,
    where: str,
    low: int | None = None,
    high: int | None = None,
    error: type[InputError] = InputError,
) -> int:
    """Return ``value`` as an int in ``[low, high]``, or raise ``error``."""
    expected = "an integer" + _range_text(low, high, None)
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise fail(where, name, expected, value, error)
    if (low is not None and value < low) or (high is not None and value > high):
        raise fail(where, name, expected, value, error)
    return int(value)


def instance(
    value: Any,
    name: str,
    types: type | tuple[type, ...],
    *,
    where: str,
    error: type[InputError] = InputError,
) -> Any:
    """Return ``value`` if it is an instance of ``types``, or raise ``error``."""
    if not isinstance(value, types):
        kinds = types if isinstance(types, tuple) else (types,)
        expected = " or ".join(_article(kind.__name__) for kind in kinds)
        raise fail(where, name, expected, value, error)
    return value


def having(
    value: Any,
    name: str,
    kind: str,
    attributes: tuple[str, ...],
    *,
    where: str,
    error: type[InputError] = InputError,
) -> Any:
    """Return ``value`` if it has ``attributes`` (duck typing), or raise ``error``.

    For a family of classes behind one protocol (the grasp constraints):
    ``kind`` names it in the message, e.g. ``"GraspConstraint"``.
    """
    if value is None or not all(hasattr(value, a) for a in attributes):
        raise fail(where, name, _article(kind), value, error)
    return value


def path(
    value: Any, name: str, *, where: str, error: type[InputError] = InputError
) -> Path:
    """Return ``value`` (a str or os.PathLike) as a Path, or raise ``error``."""
    if not isinstance(value, (str, os.PathLike)) or not str(value):
        raise fail(where, name, "a file path (str or Path)", value, error)
    return Path(value)


def _article(noun: str) -> str:
    return f"an {noun}" if noun[0] in "AEIOUaeiou" else f"a {noun}"


def _shape_text(shape: Shape) -> str:
    if len(shape) == 1:
        return f"({shape[0]},)"
    return "(" + ", ".join(str(size) for size in shape) + ")"


def _shape_matches(actual: tuple[int, ...], shape: Shape) -> bool:
    if shape[:1] == ("...",):
        tail = shape[1:]
        return len(actual) >= len(tail) and _shape_matches(
            actual[len(actual) - len(tail) :], tail
        )
    if len(actual) != len(shape):
        return False
    return all(
        size >= 1 if isinstance(want, str) else size == want
        for size, want in zip(actual, shape, strict=True)
    )


def _range_text(low: float | None, high: float | None, above: float | None) -> str:
    parts = [] if above is None else [f"> {above:g}"]
    if low is not None and high is not None:
        parts.append(f"in [{low:g}, {high:g}]")
    elif low is not None:
        parts.append(f">= {low:g}")
    elif high is not None:
        parts.append(f"<= {high:g}")
    return " " + " and ".join(parts) if parts else ""


__all__ = [
    "Shape",
    "array",
    "describe",
    "fail",
    "having",
    "instance",
    "integer",
    "number",
    "path",
]
