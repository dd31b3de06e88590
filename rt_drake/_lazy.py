"""Package attributes imported on first access (PEP 562), for light packages.

A package's ``__init__`` that re-exports names from its modules would import
every module at the package's import, and with them Drake, the simulation
and matplotlib (about 3 s of CPU per process). A process that needs one
light module of the package (a campaign worker unpickling a row's
:class:`~rt_drake.experiments.campaign.Task`, the CLI parsing its arguments)
would pay for all of them. :func:`lazy_attributes` gives the package a
``__getattr__`` that imports the defining module on first access instead.
"""

from __future__ import annotations

import importlib
import sys
from collections.abc import Callable, Iterable


def lazy_attributes(
    package: str, where: dict[str, str], public: Iterable[str]
) -> tuple[Callable[[str], object], Callable[[], list[str]]]:
    """The ``__getattr__`` and ``__dir__`` of ``package`` (its ``__name__``).

    ``where``: public name -> the module defining it; ``public``: the
    package's ``__all__``. A name is imported once, then kept in the
    package's namespace.
    """
    names = sorted(public)

    def __getattr__(name: str) -> object:
        if name not in where:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(where[name]), name)
        setattr(sys.modules[package], name, value)
        return value

    def __dir__() -> list[str]:
        return names

    return __getattr__, __dir__
