"""Files written whole or not at all, and the check that a path can be written.

:func:`write_atomically` writes to a temporary file beside the target and
renames it over the target once complete: a reader sees the old file or the
new one, never half of one. On any failure (an exception, Ctrl-C) the
temporary file is removed, so nothing like ``.name.XXXX.tmp`` is left behind.

:func:`output_problem` says why a path cannot be written (a directory where
a file is wanted, a file on the way, a read-only directory) before any work
is done. Every writer of rt_drake (the polytope cache, trajectory files,
reports, the CLI) goes through here. Imports nothing heavy: the Drake-free
layers use it.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import BinaryIO

from rt_drake.errors import InputError


def output_problem(path: str | Path, directory: bool = False) -> str | None:
    """Return why ``path`` cannot be written as a file (or a directory), or None.

    Args:
        path: The file (or directory) to write; it need not exist, nor need
            its parent directories (they are made).
        directory: True if ``path`` is to be a directory.

    Returns:
        None if it can be written, else a phrase such as ``"it is a
        directory"`` or ``"'a/b' is not a directory"``.
    """
    path = Path(path)
    if directory:
        if path.exists() and not path.is_dir():
            return "it is a file, not a directory"
    elif path.is_dir():
        return "it is a directory, not a file"
    for parent in path.absolute().parents:
        if parent.exists():
            if not parent.is_dir():
                return f"'{_shown(parent)}' is not a directory"
            if not os.access(parent, os.W_OK | os.X_OK):
                return f"directory '{_shown(parent)}' is not writable"
            break
    return None


def write_atomically(path: str | Path, write: Callable[[BinaryIO], None]) -> Path:
    """Write ``path`` through ``write(stream)`` (binary), all or nothing.

    Makes the parent directories, writes a temporary file beside ``path``
    and renames it over ``path``; removes the temporary file on any failure.

    Raises:
        InputError: ``path`` cannot be written (see :func:`output_problem`),
            or the system refused (no space, permissions), naming the path.
    """
    path = Path(path)
    problem = output_problem(path)
    if problem is not None:
        raise InputError(f"cannot write '{path}': {problem}")
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        handle, temporary = tempfile.mkstemp(
            dir=path.parent, prefix=f".{path.name}.", suffix=".tmp"
        )
    except OSError as error:
        raise InputError(f"cannot write '{path}': {error.strerror}") from None
    try:
        with os.fdopen(handle, "wb") as stream:
            write(stream)
        os.replace(temporary, path)
    except BaseException as error:
        Path(temporary).unlink(missing_ok=True)
        if isinstance(error, OSError):
            raise InputError(f"cannot write '{path}': {error.strerror}") from None
        raise
    return path


def write_text_atomically(path: str | Path, text: str) -> Path:
    """Write ``text`` (UTF-8) to ``path`` with :func:`write_atomically`."""
    data = text.encode()

    def write(stream: BinaryIO) -> None:
        stream.write(data)

    return write_atomically(path, write)


def _shown(parent: Path) -> str:
    """``parent`` relative to the working directory when it is under it."""
    try:
        return str(parent.relative_to(Path.cwd()))
    except ValueError:
        return str(parent)


__all__ = ["output_problem", "write_atomically", "write_text_atomically"]
