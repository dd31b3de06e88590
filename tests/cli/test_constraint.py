"""``rt-drake constraint``: writes F, g, vertices; bad input exits 2 in one line."""

from __future__ import annotations

import argparse

import numpy as np
import pytest

import rt_drake.cli as cli
from rt_drake.cli import _constraint as constraint
from rt_drake.contact import CupParameters, contact_wrench_polytope


@pytest.fixture(autouse=True)
def _cache_in_tmp(tmp_path, monkeypatch):
    monkeypatch.setenv("RT_DRAKE_CACHE_DIR", str(tmp_path / "cache"))


@pytest.fixture
def main(monkeypatch):
    """``rt_drake.cli.main`` with the constraint command registered."""
    if "constraint" not in cli._COMMANDS:
        monkeypatch.setattr(cli, "_COMMANDS", (*cli._COMMANDS, "constraint"))
    return cli.main


def test_register_adds_the_subcommand():
    parser = argparse.ArgumentParser(prog="rt-drake")
    constraint.register(parser.add_subparsers(dest="command"))
    args = parser.parse_args(["constraint", "--points", "4", "--out", "x.npz"])
    assert args.run is constraint.run and args.points == 4 and args.radius is None


def test_writes_the_exact_set_and_its_parameters(tmp_path, capsys, main):
    out = tmp_path / "out" / "cup.npz"
    argv = ["constraint", "--points", "4", "--friction", "0.5", "--out", str(out)]
    assert main(argv) == 0
    cup = CupParameters(points=4, friction=0.5)
    expected = contact_wrench_polytope(cup)
    with np.load(out) as data:
        np.testing.assert_allclose(data["F"], expected.F)
        np.testing.assert_allclose(data["g"], expected.g)
        assert data["vertices"].shape == expected.vertices.shape
        assert list(data["parameter_names"]) == list(cup.as_dict())
        np.testing.assert_array_equal(data["parameters"], list(cup.as_dict().values()))
    printed = capsys.readouterr().out
    assert f"{len(expected.F)} rows" in printed and str(out) in printed


def test_approximate_writes_the_smaller_inner_set(tmp_path, capsys, main):
    out = tmp_path / "approx.npz"
    argv = ["constraint", "--approximate", "12", "--samples", "300", "--out", str(out)]
    assert main(argv) == 0
    exact = contact_wrench_polytope(CupParameters())
    with np.load(out) as data:
        assert len(data["vertices"]) <= 12
        assert np.all(exact.contains(data["vertices"]))
        assert int(data["exact_rows"]) == len(exact.F)
        assert 0 < int(data["covered"]) <= int(data["samples"])
    assert "approximation:" in capsys.readouterr().out


def test_scenario_cup_with_a_flag_overriding_it(tmp_path, main):
    pytest.importorskip("pydrake")
    out = tmp_path / "cup.npz"
    argv = ["constraint", "--scenario", "stack_four_objects", "--friction", "0.6"]
    assert main([*argv, "--out", str(out)]) == 0
    with np.load(out) as data:
        names = list(data["parameter_names"])
        assert data["parameters"][names.index("friction")] == 0.6


@pytest.mark.parametrize(
    "flags,words",
    [
        (["--radius", "-0.01"], ["radius", "-0.01"]),
        (["--points", "2"], ["points", "2"]),
        (["--friction", "nan"], ["friction", "nan"]),
        (["--max-normal-force", "0"], ["max_normal_force", "0"]),
        (["--approximate", "3"], ["--approximate", "3"]),
        (["--scenario", "no_such_scenario.yaml"], ["no_such_scenario.yaml"]),
    ],
)
def test_bad_input_exits_2_with_one_line(tmp_path, capsys, main, flags, words):
    assert main(["constraint", *flags, "--out", str(tmp_path / "x.npz")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1
    assert err.startswith("rt-drake constraint: error:")
    for word in words:
        assert word in err
    assert not (tmp_path / "x.npz").exists()


def test_out_must_be_an_npz_file(tmp_path, capsys, main):
    assert main(["constraint", "--out", str(tmp_path / "x.txt")]) == 2
    assert ".npz" in capsys.readouterr().err
