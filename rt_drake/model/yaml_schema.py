"""The YAML layer of scenario files: a strict loader and a schema check.

:func:`read_yaml` parses a scenario's text with PyYAML's safe loader,
refusing, while composing (before anything expands), what would make the
file mean something other than it says or hang the loader: a key given
twice (YAML keeps the last one silently), aliases (``*name``; an alias bomb
expands exponentially) and nesting deeper than :data:`MAX_DEPTH`.
:func:`check_schema` then checks the raw data against the scenario's
dataclasses, with the key path: unknown keys, a value of the wrong type,
null where a value is needed, NaN or inf anywhere; the typed loader
(``yaml_load_typed``), whose messages name neither key nor value, sees only
text that passed. Every error is a one-line
:class:`~rt_drake.errors.ScenarioError` naming the file.
"""

import dataclasses
import math
import re
import types
import typing
from pathlib import Path
from typing import Any

import yaml
from pydrake.common.schema import Transform
from pydrake.multibody.parsing import ModelDirective

from rt_drake.errors import ScenarioError

#: Deepest nesting of YAML mappings and lists accepted.
MAX_DEPTH = 32


def read_yaml(path: Path, text: str) -> dict:
    """Parse a scenario file's text; refuse duplicates, aliases, deep nesting.

    Returns the top-level mapping (``!Tag {...}`` nodes as plain mappings).

    Raises:
        ScenarioError: naming ``path`` and the line.
    """
    try:
        raw = yaml.load(text, Loader=_StrictLoader)
    except _Refused as error:
        raise ScenarioError(f"{path}: {error}") from None
    except yaml.YAMLError as error:
        raise ScenarioError(f"{path}: not valid YAML: {error}") from None
    if not isinstance(raw, dict):
        got = "an empty file" if raw is None else type(raw).__name__
        raise ScenarioError(
            f"{path}: expected a mapping of keys at the top level, got {got}"
        )
    return raw


class _Refused(ScenarioError):
    """A YAML construct scenario files do not accept (the path added later)."""


class _StrictLoader(yaml.SafeLoader):
    """SafeLoader for scenario files.

    Keeps ``!Tag {...}`` nodes as plain mappings; refuses duplicate keys,
    aliases and nesting deeper than MAX_DEPTH, while composing (before
    anything is expanded).
    """

    _depth = 0

    def compose_node(self, parent: Any, index: Any) -> Any:
        """Compose one node, refusing aliases and deep nesting."""
        event = self.peek_event()
        if isinstance(event, yaml.AliasEvent):
            raise _Refused(
                f"line {event.start_mark.line + 1}: YAML aliases (*{event.anchor}) "
                "are not accepted in scenario files; write the value out"
            )
        if self._depth >= MAX_DEPTH:
            raise _Refused(
                f"line {event.start_mark.line + 1}: nested deeper than {MAX_DEPTH} "
                "levels"
            )
        self._depth += 1
        try:
            return super().compose_node(parent, index)
        finally:
            self._depth -= 1

    def construct_mapping(self, node: yaml.MappingNode, deep: bool = False) -> Any:
        """Construct a mapping, refusing a key that appears twice."""
        lines: dict[Any, int] = {}
        for key_node, _ in node.value:
            key = self.construct_object(key_node, deep=True)
            line = key_node.start_mark.line + 1
            try:
                duplicate = key in lines
            except TypeError:  # unhashable: SafeLoader refuses it below
                continue
            if duplicate:
                raise _Refused(
                    f"line {line}: duplicate key '{key}' (first on line "
                    f"{lines[key]}); YAML would silently keep the last value"
                )
            lines[key] = line
        return super().construct_mapping(node, deep=deep)


def _construct_tagged(loader: yaml.SafeLoader, _suffix: str, node: yaml.Node) -> Any:
    if isinstance(node, yaml.MappingNode):
        return loader.construct_mapping(node, deep=True)
    if isinstance(node, yaml.SequenceNode):
        return loader.construct_sequence(node, deep=True)
    return loader.construct_scalar(node)


_StrictLoader.add_multi_constructor("!", _construct_tagged)


def _walk(node: Any, prefix: str = ""):
    """Yield ``(key_path, key, value)`` for every mapping entry and list item."""
    if isinstance(node, dict):
        for key, value in node.items():
            child = f"{prefix}.{key}" if prefix else str(key)
            yield child, key, value
            yield from _walk(value, child)
    elif isinstance(node, list):
        for index, value in enumerate(node):
            child = f"{prefix}[{index}]"
            yield child, index, value
            yield from _walk(value, child)


def _is_number(value: Any) -> bool:
    """An int or float, or a string the typed loader reads as one (``1e-3``).

    YAML 1.1 (PyYAML) reads ``1e-3`` as a string, YAML 1.2 (the typed
    loader) as a number.
    """
    if isinstance(value, str):
        try:
            float(value)
        except ValueError:
            return False
        return "_" not in value
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _is_finite(value: Any) -> bool:
    """A number (see :func:`_is_number`) that is not NaN or inf."""
    return _is_number(value) and math.isfinite(float(value))


def _shown(value: Any) -> str:
    return "null" if value is None else repr(value)


def check_schema(path: Path, raw: dict, schema: type, prefix: str = "") -> None:
    """Check the keys of one mapping against a dataclass schema, recursively.

    Unknown keys, wrong types, null where a value is needed, and NaN or inf
    are refused here, with the key path, before the typed loader (whose
    messages name neither key nor value) sees the text.
    """
    hints = typing.get_type_hints(schema)
    names = [f.name for f in dataclasses.fields(schema) if f.metadata.get("yaml", True)]
    for key, value in raw.items():
        key_path = f"{prefix}.{key}" if prefix else str(key)
        if key not in names:
            raise ScenarioError(
                f"{path}: unknown key '{key_path}' (expected one of: "
                f"{', '.join(names)})"
            )
        _check_value(path, value, hints[key], key_path)


def _check_value(path: Path, value: Any, kind: Any, key_path: str) -> None:
    where = f"{path}: key '{key_path}'"
    if typing.get_origin(kind) in (typing.Union, types.UnionType):
        if value is None and type(None) in typing.get_args(kind):
            return
        kinds = [a for a in typing.get_args(kind) if a is not type(None)]
        if len(kinds) > 1:  # e.g. float | str: a number, or a word checked later
            if not any(_matches(value, k) for k in kinds):
                names = " or ".join(_KIND_NAMES[k] for k in kinds)
                raise ScenarioError(f"{where}: expected {names}, got {_shown(value)}")
            if _is_number(value):
                _check_number(where, value)
            return
        (kind,) = kinds
    if kind is Transform:
        _check_pose(path, value, key_path)
    elif kind is ModelDirective:  # Drake checks the directives themselves
        if not isinstance(value, dict):
            raise ScenarioError(f"{where}: expected a directive, got {_shown(value)}")
    elif dataclasses.is_dataclass(kind):
        if not isinstance(value, dict):
            raise ScenarioError(
                f"{where}: expected a mapping of keys, got {_shown(value)}"
            )
        check_schema(path, value, typing.cast(type, kind), key_path)
    elif typing.get_origin(kind) is list:
        if not isinstance(value, list):
            raise ScenarioError(f"{where}: expected a list, got {_shown(value)}")
        (item,) = typing.get_args(kind)
        for index, entry in enumerate(value):
            _check_value(path, entry, item, f"{key_path}[{index}]")
    elif typing.get_origin(kind) is dict:
        if not isinstance(value, dict):
            raise ScenarioError(f"{where}: expected a mapping, got {_shown(value)}")
        key_kind, item = typing.get_args(kind)
        for key, entry in value.items():
            if key_kind is str and not isinstance(key, str):
                raise ScenarioError(f"{where}: expected string keys, got {_shown(key)}")
            _check_value(path, entry, item, f"{key_path}.{key}")
    elif kind is float:
        _check_number(where, value)
    elif kind is int:
        if isinstance(value, bool) or not isinstance(value, int):
            raise ScenarioError(f"{where}: expected an integer, got {_shown(value)}")
    elif kind is str:
        if not isinstance(value, str):
            raise ScenarioError(f"{where}: expected a string, got {_shown(value)}")


#: How a scalar kind of a union is named in messages.
_KIND_NAMES = {float: "a number", int: "an integer", str: "a string"}


def _matches(value: Any, kind: Any) -> bool:
    """``value`` has the scalar ``kind`` (float, int or str) of a union."""
    if kind is float:
        return _is_number(value)
    if kind is int:
        return isinstance(value, int) and not isinstance(value, bool)
    if kind is str:
        return isinstance(value, str) and not _is_number(value)
    raise TypeError(f"scenario schema: unions of {kind} are not supported")


def _check_number(where: str, value: Any) -> None:
    if not _is_number(value):
        raise ScenarioError(f"{where}: expected a number, got {_shown(value)}")
    if not _is_finite(value):
        raise ScenarioError(f"{where}: must be finite, got {value}")


def _check_pose(path: Path, value: Any, key_path: str) -> None:
    """A pose: a mapping whose ``translation`` and angle lists hold 3 numbers.

    Every number in it must be finite (``!Rpy``, ``!AngleAxis``, ... tags are
    left to the typed loader).
    """
    if not isinstance(value, dict):
        raise ScenarioError(
            f"{path}: key '{key_path}': expected a pose {{translation: [x, y, z], "
            f"rotation: ...}}, got {_shown(value)}"
        )
    for child, key, entry in _walk(value, key_path):
        if key in ("translation", "deg", "rad") and not (
            isinstance(entry, list) and len(entry) == 3 and all(map(_is_number, entry))
        ):
            raise ScenarioError(
                f"{path}: key '{child}': expected 3 numbers, got {_shown(entry)}"
            )
        if _is_number(entry) and not _is_finite(entry):
            raise ScenarioError(f"{path}: key '{child}': must be finite, got {entry}")


def locate(path: Path, raw: dict, message: str) -> str:
    """Turn a ``yaml_load_typed`` error into 'file: key ...: problem'."""
    unknown = re.search(r"fields \[(.*?)\] were unknown", message)
    if unknown:
        names = [n.strip(" '\"") for n in unknown.group(1).split(",")]
        for key_path, key, _ in _walk(raw):
            if key in names:
                return f"{path}: unknown key '{key_path}'"
        return f"{path}: unknown key(s) {', '.join(names)}"
    bad_float = re.search(r"could not convert string to float: '(.*)'", message)
    if bad_float:
        for key_path, _, value in _walk(raw):
            if isinstance(value, str) and value == bad_float.group(1):
                return f"{path}: key '{key_path}': value {value!r} is not a number"
    return f"{path}: {' '.join(message.split())[:300]}"


__all__ = ["MAX_DEPTH", "check_schema", "locate", "read_yaml"]
