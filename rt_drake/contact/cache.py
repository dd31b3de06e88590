"""On-disk cache of exact contact wrench sets, one ``.npz`` per cup or tool.

A file is named by a hash of the cup parameters (or of a multi-cup tool's
parameters and poses, every cup's) and :data:`FORMAT_VERSION` and lives in
``$RT_DRAKE_CACHE_DIR`` (default ``~/.cache/rt_drake``). It stores ``F``,
``g``, ``vertices``, ``format_version`` and the parameters: for a cup
``parameter_names`` and ``parameters``, for a tool ``tool``, the JSON text of
:meth:`ToolParameters.as_dict` (floats written exactly). On load the stored
parameters must equal the requested ones exactly, so a file written for
another cup or tool (renamed, hash collision, older format) is never used:
it is recomputed and overwritten instead.
"""

from __future__ import annotations

import hashlib
import json
import os
import tempfile
import zipfile
from pathlib import Path
from typing import Any

import numpy as np

from rt_drake.contact.cup import CupParameters
from rt_drake.contact.tool import ToolParameters
from rt_drake.contact.tool_polytope import tool_wrench_polytope
from rt_drake.contact.wrench_polytope import WrenchPolytope, contact_wrench_polytope

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
        fields = {"format": FORMAT_VERSION, "tool": tool_text(cup)}
    else:
        fields = {"format": FORMAT_VERSION, "cup": cup.as_dict()}
    text = json.dumps(fields, sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:24]


def cache_path(
    cup: CupParameters | ToolParameters, directory: Path | None = None
) -> Path:
    """Return where the wrench set of ``cup`` (or of a tool) is cached."""
    directory = default_cache_dir() if directory is None else Path(directory)
    kind = (
        "tool_wrench_polytope"
        if isinstance(cup, ToolParameters)
        else ("wrench_polytope")
    )
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


def save_polytope(
    path: Path, polytope: WrenchPolytope, **extra: np.ndarray | float
) -> None:
    """Write ``polytope`` (and any ``extra`` arrays) to ``path`` atomically."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    arrays: dict[str, Any] = {
        "F": polytope.F,
        "g": polytope.g,
        "vertices": polytope.vertices,
        "format_version": FORMAT_VERSION,
        **_parameters(polytope.cup),
        **extra,
    }
    with tempfile.NamedTemporaryFile(dir=path.parent, suffix=".tmp", delete=False) as f:
        np.savez(f, **arrays)
    os.replace(f.name, path)


def load_polytope(
    path: Path, cup: CupParameters | ToolParameters
) -> WrenchPolytope | None:
    """Return the wrench set stored in ``path`` if it was written for ``cup``.

    Returns None when the file is missing, unreadable, of another format
    version, or stores other parameters (or another tool).
    """
    expected = _parameters(cup)
    try:
        with np.load(path, allow_pickle=False) as data:
            if int(data["format_version"]) != FORMAT_VERSION:
                return None
            for name, value in expected.items():
                stored = data[name]
                if stored.shape != value.shape or not np.array_equal(stored, value):
                    return None
            F, g, vertices = data["F"], data["g"], data["vertices"]
    except (OSError, KeyError, ValueError, zipfile.BadZipFile):
        return None
    return WrenchPolytope(cup=cup, F=F, g=g, vertices=vertices)


def cached_wrench_polytope(
    cup: CupParameters | ToolParameters,
    directory: Path | None = None,
    use_cache: bool = True,
) -> WrenchPolytope:
    """Return the exact W_c of ``cup`` (or W_T of a tool), computed once.

    Args:
        cup: The cup model, or a multi-cup tool (then the set is about the
            tool frame's origin, in the tool frame).
        directory: Cache directory (default :func:`default_cache_dir`).
        use_cache: If False, neither read nor write the cache.
    """
    polytope = load_polytope(cache_path(cup, directory), cup) if use_cache else None
    if polytope is None:
        if isinstance(cup, ToolParameters):
            polytope = tool_wrench_polytope(cup)
        else:
            polytope = contact_wrench_polytope(cup)
        if use_cache:
            save_polytope(cache_path(cup, directory), polytope)
    return polytope
