"""On-disk cache of exact contact wrench sets, one ``.npz`` per cup or tool.

A file is named by a hash of the cup parameters (or of a multi-cup tool's
parameters and poses, every cup's) and :data:`FORMAT_VERSION` and lives in
``$RT_DRAKE_CACHE_DIR`` (default ``~/.cache/rt_drake``). It stores ``F``,
``g``, ``vertices``, ``format_version`` and the parameters: for a cup
``parameter_names`` and ``parameters``, for a tool ``tool``, the JSON text of
:meth:`ToolParameters.as_dict` (floats written exactly). On load the stored
parameters must equal the requested ones exactly, so a file written for
another cup or tool (renamed, hash collision, older format) is never used:
it is recomputed and overwritten instead. Files are written atomically
(:mod:`rt_drake.atomic_file`): no temporary file is left behind on failure.
"""

from __future__ import annotations

import hashlib
import json
import os
import zipfile
from pathlib import Path
from typing import Any, BinaryIO

import numpy as np

from rt_drake import arguments
from rt_drake.atomic_file import write_atomically
from rt_drake.contact._cup import CupParameters
from rt_drake.contact.exact_cost import DEFAULT_MAX_MEMORY
from rt_drake.contact.tool import ToolParameters
from rt_drake.contact.tool_polytope import DEFAULT_MAX_FACETS, tool_wrench_polytope
from rt_drake.contact.wrench_polytope import (
    WrenchPolytope,
    check_polytope,
    contact_wrench_polytope,
)
from rt_drake.errors import InputError

#: Bump when the stored arrays or the enumeration change meaning.
FORMAT_VERSION = 1

#: Environment variable naming the cache directory.
CACHE_ENV = "RT_DRAKE_CACHE_DIR"


def default_cache_dir() -> Path:
    """Return ``$RT_DRAKE_CACHE_DIR`` or ``~/.cache/rt_drake``."""
    configured = os.environ.get(CACHE_ENV)
    return Path(configured) if configured else Path.home() / ".cache" / "rt_drake"


def tool_text(tool: ToolParameters) -> str:
    """Return the tool's parameters and poses as canonical JSON text."""
    return json.dumps(tool.as_dict(), sort_keys=True)


def cache_key(cup: CupParameters | ToolParameters) -> str:
    """Return a hex digest of the parameters (and poses) and the format version."""
    if isinstance(cup, ToolParameters):
        fields: dict[str, object] = {"format": FORMAT_VERSION, "tool": tool_text(cup)}
    else:
        fields = {"format": FORMAT_VERSION, "cup": cup.as_dict()}
    text = json.dumps(fields, sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:24]


def cache_path(
    cup: CupParameters | ToolParameters, directory: Path | None = None
) -> Path:
    """Return where the wrench set of ``cup`` (or of a tool) is cached."""
    arguments.instance(cup, "cup", (CupParameters, ToolParameters), where="cache_path")
    if directory is not None:
        arguments.path(directory, "directory", where="cache_path")
    directory = default_cache_dir() if directory is None else Path(directory)
    kind = "wrench_polytope"
    if isinstance(cup, ToolParameters):
        kind = "tool_wrench_polytope"
    return directory / f"{kind}_{cache_key(cup)}.npz"


def _parameters(cup: CupParameters | ToolParameters) -> dict[str, np.ndarray]:
    """Return the arrays that identify the parameters in a file."""
    if isinstance(cup, ToolParameters):
        return {"tool": np.array(tool_text(cup))}
    fields = cup.as_dict()
    return {
        "parameter_names": np.array(list(fields)),
        "parameters": np.array(list(fields.values()), dtype=float),
    }


def save_polytope(path: str | Path, polytope: WrenchPolytope, **extra: Any) -> None:
    """Write ``polytope`` (and any ``extra`` arrays) to ``path`` atomically.

    Raises:
        InputError: ``path`` cannot be written (a directory, under a file).
    """
    arguments.path(path, "path", where="save_polytope")
    arguments.instance(polytope, "polytope", WrenchPolytope, where="save_polytope")
    arrays: dict[str, Any] = {
        "F": polytope.F,
        "g": polytope.g,
        "vertices": polytope.vertices,
        "format_version": FORMAT_VERSION,
        **_parameters(polytope.cup),
        **extra,
    }

    def write(stream: BinaryIO) -> None:
        np.savez(stream, **arrays)

    write_atomically(path, write)


def _check_cup(path: Path, data: Any, cup: CupParameters) -> None:
    """Raise InputError unless ``data`` stores exactly ``cup``'s parameters."""
    fields = cup.as_dict()
    names, values = list(data["parameter_names"]), data["parameters"]
    if names != list(fields) or len(values) != len(fields):
        raise InputError(f"{path}: parameters {names}, expected {list(fields)}")
    stored = dict(zip(names, np.asarray(values, dtype=float).tolist(), strict=False))
    for name, value in fields.items():
        if stored[name] != float(value):
            raise InputError(
                f"{path}: written for cup {name} = {stored[name]:g}, not {value:g}"
            )


def _check_tool(path: Path, data: Any, tool: ToolParameters) -> None:
    """Raise InputError unless ``data`` stores exactly ``tool`` (cups, poses)."""
    stored = str(data["tool"])
    if stored != tool_text(tool):
        try:
            count = len(json.loads(stored)["cups"])
        except (ValueError, KeyError, TypeError):
            raise InputError(f"{path}: key 'tool' is not a tool description") from None
        raise InputError(
            f"{path}: written for another tool ({count} cups), not this "
            f"{len(tool.cups)}-cup tool"
        )


def load_polytope(
    path: str | Path, cup: CupParameters | ToolParameters
) -> WrenchPolytope:
    """Return the wrench set stored in ``path``, which must be ``cup``'s (or a tool's).

    Raises:
        InputError: naming the file and the reason: missing, not an ``.npz``
            of this format version, written for other parameters (which) or
            another tool, or arrays that are not a consistent polytope.
    """
    path = arguments.path(path, "path", where="load_polytope")
    arguments.instance(
        cup, "cup", (CupParameters, ToolParameters), where="load_polytope"
    )
    if not path.is_file():
        raise InputError(f"wrench polytope file '{path}' does not exist")
    try:
        with np.load(path, allow_pickle=False) as data:
            version = int(data["format_version"])
            if version != FORMAT_VERSION:
                raise InputError(
                    f"{path}: key 'format_version' is {version}, "
                    f"expected {FORMAT_VERSION}"
                )
            if isinstance(cup, ToolParameters):
                _check_tool(path, data, cup)
            else:
                _check_cup(path, data, cup)
            F, g, vertices = data["F"], data["g"], data["vertices"]
    except (OSError, zipfile.BadZipFile) as error:
        raise InputError(f"{path}: not a wrench polytope .npz: {error}") from None
    except KeyError as error:
        raise InputError(f"{path}: key {error} is missing") from None
    except InputError:
        raise
    except ValueError as error:
        raise InputError(f"{path}: not a wrench polytope .npz: {error}") from None
    polytope = WrenchPolytope(cup=cup, F=F, g=g, vertices=vertices)
    try:
        check_polytope(polytope)
    except InputError as error:
        raise InputError(f"{path}: {error}") from None
    return polytope


def cached_wrench_polytope(
    cup: CupParameters | ToolParameters,
    directory: Path | None = None,
    use_cache: bool = True,
    max_memory: float = DEFAULT_MAX_MEMORY,
    max_facets: int | None = DEFAULT_MAX_FACETS,
) -> WrenchPolytope:
    """Return the exact W_c of ``cup`` (or W_T of a tool), computed once.

    Args:
        cup: The cup model, or a multi-cup tool (then the set is about the
            tool frame's origin, in the tool frame).
        directory: Cache directory (default :func:`default_cache_dir`).
        use_cache: If False, neither read nor write the cache.
        max_memory: Bytes the computation of one cup's set may use (see
            :func:`~rt_drake.contact.contact_wrench_polytope`).
        max_facets: Most facets a tool of several cups may have (see
            :func:`~rt_drake.contact.tool_wrench_polytope`); None: no limit.

    Raises:
        InputError: a bad parameter; TooLargeError (an InputError) when the
            set is estimated or found to be too large.
    """
    where = "cached_wrench_polytope"
    arguments.instance(cup, "cup", (CupParameters, ToolParameters), where=where)
    if directory is not None:
        arguments.path(directory, "directory", where=where)
    arguments.number(max_memory, "max_memory", where=where, above=0.0)
    if max_facets is not None:
        arguments.integer(max_facets, "max_facets", where=where, low=1)
    cup.validate()
    path = cache_path(cup, directory)
    if use_cache:
        try:
            return load_polytope(path, cup)
        except InputError:  # missing, stale or corrupt: compute it again
            pass
    if isinstance(cup, ToolParameters):
        polytope = tool_wrench_polytope(cup, max_facets, max_memory)
    else:
        polytope = contact_wrench_polytope(cup, max_memory)
    if use_cache:
        save_polytope(path, polytope)
    return polytope
