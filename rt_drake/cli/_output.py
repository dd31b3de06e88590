"""Output paths of the ``rt-drake`` commands, checked before any work starts.

Every command checks each path it will write as soon as its arguments are
parsed, so a bad path costs nothing (not a minute of simulation, then a
crash):

- the parent directories exist or can be made (no file on the way, writable);
- a file is wanted: the path is not a directory and ends in the right suffix;
  a directory is wanted: the path is not a file;
- it is none of the command's inputs (resolved paths compared: symlinks and
  hard links count), so an output never writes over an input.

Files are then written with :func:`rt_drake.atomic_file.write_atomically`:
whole or not at all, no temporary file left behind. Messages name the flag
and the path: ``--out 'victim.yaml' is the scenario file, an input of this
command: refusing to write over it``.
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Mapping
from pathlib import Path

from rt_drake.atomic_file import output_problem
from rt_drake.errors import InputError

#: What an input is (for messages) -> its path.
Inputs = Mapping[str, "str | Path | None"]


def output_file(
    path: str | Path, flag: str, suffix: str, inputs: Inputs | None = None
) -> Path:
    """Check a file the command will write; return it as a Path.

    Args:
        path: The file.
        flag: The flag that named it (``--out``), for messages.
        suffix: The suffix it must have (``.npz``).
        inputs: The command's input files by description (``"scenario file"``).

    Raises:
        InputError: naming the flag, the path and the problem.
    """
    path = Path(path)
    _check_not_an_input(path, flag, path, inputs or {})
    problem = output_problem(path)
    if problem is not None:
        raise InputError(f"{flag} '{path}': {problem}")
    if path.suffix != suffix:
        raise InputError(f"{flag} '{path}' must end in {suffix}")
    return path


def output_directory(
    path: str | Path,
    flag: str,
    files: Iterable[str],
    inputs: Inputs | None = None,
) -> Path:
    """Check a directory the command will write ``files`` into; return it.

    Raises:
        InputError: ``path`` is a file or under one, or one of ``files`` in
            it is a directory or one of the command's inputs.
    """
    path = Path(path)
    problem = output_problem(path, directory=True)
    if problem is not None:
        raise InputError(f"{flag} '{path}': {problem}")
    for name in files:
        target = path / name
        if target.is_dir():
            raise InputError(f"{flag} '{path}': '{target}' is a directory, not a file")
        _check_not_an_input(target, flag, path, inputs or {})
    return path


def _check_not_an_input(target: Path, flag: str, named: Path, inputs: Inputs) -> None:
    for what, source in inputs.items():
        if source is not None and _same_file(target, Path(source)):
            where = (
                f"'{named}' is"
                if target == named
                else f"'{named}': the command writes '{target}', which is"
            )
            raise InputError(
                f"{flag} {where} the {what}, an input of this command: "
                "refusing to write over it"
            )


def _same_file(a: Path, b: Path) -> bool:
    if a.exists() and b.exists():
        return os.path.samefile(a, b)
    return a.resolve() == b.resolve()


__all__ = ["output_directory", "output_file"]
