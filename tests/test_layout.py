"""The package's layout rules that import-linter does not check.

import-linter (``lint-imports`` in CI, contracts in pyproject.toml) keeps the
layer order, the absence of import circles and the privacy of ``_x.py``
modules. This test keeps the rest of the layout: one name per module.
"""

from __future__ import annotations

import collections
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1] / "rt_drake"


def module_names() -> dict[str, list[str]]:
    """Module name (leading underscore dropped) -> the files that use it."""
    names: dict[str, list[str]] = collections.defaultdict(list)
    for path in sorted(PACKAGE.rglob("*.py")):
        if path.name in {"__init__.py", "__main__.py"}:
            continue
        names[path.stem.lstrip("_")].append(str(path.relative_to(PACKAGE)))
    return names


def test_no_module_name_is_used_twice():
    names = module_names()
    assert len(names) > 100  # the walk found the package
    twice = {name: files for name, files in names.items() if len(files) > 1}
    assert not twice, f"module names used twice: {twice}"


def test_the_root_holds_only_the_public_face_and_the_foundation():
    root = sorted(p.name for p in PACKAGE.glob("*.py"))
    assert root == [
        "__init__.py",
        "_lazy.py",
        "_version.py",
        "arguments.py",
        "atomic_file.py",
        "errors.py",
    ]
