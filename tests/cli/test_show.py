"""``rt-drake show``: writes the scene as HTML; bad input exits 2 in one line."""

from __future__ import annotations

import pytest

from rt_drake.cli import main
from rt_drake.simulation.visualization import meshcat_paths_in_html


def test_show_writes_html_with_the_scene(tmp_path, capsys):
    out = tmp_path / "scene.html"
    assert main(["show", "stack_four_objects", "--html", str(out)]) == 0
    paths = meshcat_paths_in_html(out.read_text())
    # The robot, the tool, the cell, the bin and every object are drawn.
    for model in (
        "vs060",
        "suction_tool",
        "cell",
        "bin",
        "whetstone_box",
        "carton_box",
    ):
        assert any(f"/drake/visual/{model}/" in p for p in paths), model


def test_empty_page_has_no_scene():
    # The check above can fail: a page without commands has no paths.
    assert meshcat_paths_in_html("<html><body></body></html>") == set()


@pytest.mark.parametrize(
    "argv,words",
    [
        (
            ["show", "no_such_scenario.yaml", "--html", "x.html"],
            ["no_such_scenario.yaml", "does not exist"],
        ),
    ],
)
def test_bad_input_exits_2_with_one_line(tmp_path, capsys, argv, words):
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and err.startswith("rt-drake show: error:")
    for word in words:
        assert word in err


def test_bad_scenario_key_exits_2(tmp_path, capsys, scenario_paths):
    bad = tmp_path / "bad.yaml"
    bad.write_text(
        scenario_paths["stack_four_objects"].read_text().replace("  home:", "  hom:")
    )
    assert main(["show", str(bad), "--html", str(tmp_path / "x.html")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "robot.hom" in err and "bad.yaml" in err


@pytest.mark.parametrize(
    "argv,words",
    [
        (["constraint", "--radius", "abc", "--out", "x.npz"], ["--radius", "'abc'"]),
        (["experiment", "transport", "--n", "x", "--out", "d"], ["--n", "'x'"]),
        (["nosuch"], ["'nosuch'"]),
    ],
)
def test_malformed_arguments_exit_2_with_one_line(capsys, argv, words):
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "error:" in err
    for word in words:
        assert word in err
