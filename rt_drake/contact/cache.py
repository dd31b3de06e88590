"""On-disk cache of exact contact wrench sets, one ``.npz`` per cup.

A file is named by a hash of the cup parameters and :data:`FORMAT_VERSION`
and lives in ``$RT_DRAKE_CACHE_DIR`` (default ``~/.cache/rt_drake``). It
stores ``F``, ``g``, ``vertices``, ``parameter_names``, ``parameters`` and
``format_version``; on load the stored parameters must equal the requested
ones exactly, so a file written for another cup (renamed, hash collision,
older format) is never used: it is recomputed and overwritten instead.
Files are written atomically (:mod:`rt_drake.atomic_file`): no temporary
file is left behind on failure.
"""

from __future__ import annotations

import hashlib
import json
import os
import zipfile
from pathlib import Path
from typing import Any, BinaryIO

import numpy as np

from rt_drake.atomic_file import write_atomically
from rt_drake.contact.cup import CupParameters
from rt_drake.contact.exact_cost import DEFAULT_MAX_MEMORY
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


def cache_key(cup: CupParameters) -> str:
    """Return a hex digest of the cup parameters and the format version."""
    text = json.dumps({"format": FORMAT_VERSION, "cup": cup.as_dict()}, sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:24]


def cache_path(cup: CupParameters, directory: Path | None = None) -> Path:
    """Return where the wrench set of ``cup`` is cached."""
    directory = default_cache_dir() if directory is None else Path(directory)
    return directory / f"wrench_polytope_{cache_key(cup)}.npz"


def save_polytope(path: str | Path, polytope: WrenchPolytope, **extra: Any) -> None:
    """Write ``polytope`` (and any ``extra`` arrays) to ``path`` atomically.

    Raises:
        InputError: ``path`` cannot be written (a directory, under a file).
    """
    fields = polytope.cup.as_dict()

    def write(stream: BinaryIO) -> None:
        np.savez(
            stream,
            F=polytope.F,
            g=polytope.g,
            vertices=polytope.vertices,
            parameter_names=np.array(list(fields)),
            parameters=np.array(list(fields.values()), dtype=float),
            format_version=FORMAT_VERSION,
            **extra,
        )

    write_atomically(path, write)


def load_polytope(path: str | Path, cup: CupParameters) -> WrenchPolytope:
    """Return the wrench set stored in ``path``, which must be ``cup``'s.

    Raises:
        InputError: naming the file and the reason: missing, not an ``.npz``
            of this format version, written for other parameters (which),
            or arrays that are not a consistent polytope.
    """
    path = Path(path)
    if not path.is_file():
        raise InputError(f"wrench polytope file '{path}' does not exist")
    fields = cup.as_dict()
    try:
        with np.load(path, allow_pickle=False) as data:
            version = int(data["format_version"])
            names, values = list(data["parameter_names"]), data["parameters"]
            F, g, vertices = data["F"], data["g"], data["vertices"]
    except (OSError, ValueError, zipfile.BadZipFile) as error:
        raise InputError(f"{path}: not a wrench polytope .npz: {error}") from None
    except KeyError as error:
        raise InputError(f"{path}: key {error} is missing") from None
    if version != FORMAT_VERSION:
        raise InputError(
            f"{path}: key 'format_version' is {version}, expected {FORMAT_VERSION}"
        )
    stored = dict(zip(names, np.asarray(values, dtype=float).tolist(), strict=False))
    if names != list(fields) or len(values) != len(fields):
        raise InputError(f"{path}: parameters {names}, expected {list(fields)}")
    for name, value in fields.items():
        if stored[name] != float(value):
            raise InputError(
                f"{path}: written for cup {name} = {stored[name]:g}, not {value:g}"
            )
    polytope = WrenchPolytope(cup=cup, F=F, g=g, vertices=vertices)
    try:
        check_polytope(polytope)
    except InputError as error:
        raise InputError(f"{path}: {error}") from None
    return polytope


def cached_wrench_polytope(
    cup: CupParameters,
    directory: Path | None = None,
    use_cache: bool = True,
    max_memory: float = DEFAULT_MAX_MEMORY,
) -> WrenchPolytope:
    """Return the exact W_c of ``cup``, computed once per parameter set.

    Args:
        cup: The cup model.
        directory: Cache directory (default :func:`default_cache_dir`).
        use_cache: If False, neither read nor write the cache.
        max_memory: Bytes the computation may use (see
            :func:`~rt_drake.contact.contact_wrench_polytope`).
    """
    cup.validate()
    if not use_cache:
        return contact_wrench_polytope(cup, max_memory)
    path = cache_path(cup, directory)
    try:
        return load_polytope(path, cup)
    except InputError:  # missing, stale or corrupt: compute it again
        pass
    polytope = contact_wrench_polytope(cup, max_memory)
    save_polytope(path, polytope)
    return polytope
