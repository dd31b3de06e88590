"""On-disk cache of exact contact wrench sets, one ``.npz`` per cup.

A file is named by a hash of the cup parameters and :data:`FORMAT_VERSION`
and lives in ``$RT_DRAKE_CACHE_DIR`` (default ``~/.cache/rt_drake``). It
stores ``F``, ``g``, ``vertices``, ``parameter_names``, ``parameters`` and
``format_version``; on load the stored parameters must equal the requested
ones exactly, so a file written for another cup (renamed, hash collision,
older format) is never used: it is recomputed and overwritten instead.
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
from rt_drake.contact.wrench_polytope import WrenchPolytope, contact_wrench_polytope

#: Bump when the stored arrays or the enumeration change meaning.
FORMAT_VERSION = 1

#: Environment variable naming the cache directory.
CACHE_ENV = "RT_DRAKE_CACHE_DIR"


def default_cache_dir() -> Path:
    """Return ``$RT_DRAKE_CACHE_DIR`` or ``~/.cache/rt_drake``."""
    configured = os.environ.get(CACHE_ENV)
    return Path(configured) if configured else Path.home() / ".cache" / "rt_drake"


def cache_key(cup: CupParameters) -> str:
    """Return a hex digest of the cup parameters and the format version."""
    text = json.dumps({"format": FORMAT_VERSION, "cup": cup.as_dict()}, sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:24]


def cache_path(cup: CupParameters, directory: Path | None = None) -> Path:
    """Return where the wrench set of ``cup`` is cached."""
    directory = default_cache_dir() if directory is None else Path(directory)
    return directory / f"wrench_polytope_{cache_key(cup)}.npz"


def save_polytope(path: Path, polytope: WrenchPolytope, **extra: Any) -> None:
    """Write ``polytope`` (and any ``extra`` arrays) to ``path`` atomically."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fields = polytope.cup.as_dict()
    with tempfile.NamedTemporaryFile(dir=path.parent, suffix=".tmp", delete=False) as f:
        np.savez(
            f,
            F=polytope.F,
            g=polytope.g,
            vertices=polytope.vertices,
            parameter_names=np.array(list(fields)),
            parameters=np.array(list(fields.values()), dtype=float),
            format_version=FORMAT_VERSION,
            **extra,
        )
    os.replace(f.name, path)


def load_polytope(path: Path, cup: CupParameters) -> WrenchPolytope | None:
    """Return the wrench set stored in ``path`` if it was written for ``cup``.

    Returns None when the file is missing, unreadable, of another format
    version, or stores other parameters.
    """
    fields = cup.as_dict()
    try:
        with np.load(path, allow_pickle=False) as data:
            if int(data["format_version"]) != FORMAT_VERSION:
                return None
            if list(data["parameter_names"]) != list(fields) or not np.array_equal(
                data["parameters"], np.array(list(fields.values()), dtype=float)
            ):
                return None
            F, g, vertices = data["F"], data["g"], data["vertices"]
    except (OSError, KeyError, ValueError, zipfile.BadZipFile):
        return None
    return WrenchPolytope(cup=cup, F=F, g=g, vertices=vertices)


def cached_wrench_polytope(
    cup: CupParameters, directory: Path | None = None, use_cache: bool = True
) -> WrenchPolytope:
    """Return the exact W_c of ``cup``, computed once per parameter set.

    Args:
        cup: The cup model.
        directory: Cache directory (default :func:`default_cache_dir`).
        use_cache: If False, neither read nor write the cache.
    """
    if not use_cache:
        return contact_wrench_polytope(cup)
    path = cache_path(cup, directory)
    polytope = load_polytope(path, cup)
    if polytope is None:
        polytope = contact_wrench_polytope(cup)
        save_polytope(path, polytope)
    return polytope
