"""The package root is the public API; errors share one base class."""

from __future__ import annotations

import importlib
import inspect
import pickle
import pkgutil
import subprocess
import sys
from importlib.metadata import version

import rt_drake
from rt_drake.errors import RtDrakeError


def test_every_public_name_resolves_to_its_defining_module():
    for name in rt_drake.__all__:
        assert getattr(rt_drake, name) is not None, name
    assert rt_drake.retime is importlib.import_module("rt_drake.retiming").retime
    assert set(rt_drake.__all__) == set(dir(rt_drake))


def test_the_version_is_written_once():
    assert rt_drake.__version__ == version("rt-drake")


def test_importing_the_package_the_contact_layer_or_a_campaign_task_loads_no_drake():
    """Nor does unpickling a campaign row's Task, as a worker does first."""
    from rt_drake.experiments.campaign import RowKey, Task, Variant

    task = Task("c.yaml", "hash", RowKey("box", "cup", 0, 1, Variant.CONSTRAINED))
    code = (
        "import pickle, sys, rt_drake, rt_drake.contact\n"
        "from rt_drake.contact import cached_wrench_polytope\n"
        f"task = pickle.loads(bytes.fromhex({pickle.dumps(task).hex()!r}))\n"
        "print(task.key.object, any(m.startswith('pydrake') for m in sys.modules))"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    )
    assert out.stdout.strip() == "box False"


def test_every_exception_rt_drake_defines_derives_from_the_base():
    found = []
    for info in pkgutil.walk_packages(rt_drake.__path__, "rt_drake."):
        module = importlib.import_module(info.name)
        for _, cls in inspect.getmembers(module, inspect.isclass):
            if issubclass(cls, BaseException) and cls.__module__ == info.name:
                found.append(cls)
                assert issubclass(cls, RtDrakeError), cls
    names = {cls.__name__ for cls in found}
    assert {
        "ScenarioError",
        "RetimeInputError",
        "PlanningError",
        "CycleTimeout",
    } <= names


def test_cli_reports_a_bug_as_an_internal_error_with_its_traceback(monkeypatch, capsys):
    import pytest

    from rt_drake import cli
    from rt_drake.cli import _show as show

    def broken(args):
        raise ZeroDivisionError("a bug")

    monkeypatch.setattr(show, "run", broken)
    with pytest.raises(ZeroDivisionError):
        cli.main(["show", "stack_four_objects"])
    err = capsys.readouterr().err
    assert err.startswith("rt-drake show: internal error")


def test_a_lazy_name_is_not_shadowed_by_a_submodule_of_the_same_name():
    """Importing every submodule leaves each public name its object.

    The import system sets ``package.x`` to the submodule ``package.x`` when
    it loads it, over a lazy name ``x`` (``rt_drake.experiments.cycle_report``
    was both); so no lazily loaded package may have a public name that is
    also a submodule's.
    """
    for package in (rt_drake, rt_drake.contact, "rt_drake.experiments"):
        module = (
            importlib.import_module(package) if isinstance(package, str) else package
        )
        for info in pkgutil.walk_packages(module.__path__, f"{module.__name__}."):
            importlib.import_module(info.name)
        for name in module.__all__:
            value = getattr(module, name)
            assert not inspect.ismodule(value), f"{module.__name__}.{name}"
