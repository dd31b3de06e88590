"""Scenario loading: the shipped files load; bad input gives one clear line."""

from __future__ import annotations

import pytest

from rt_drake.errors import ScenarioError
from rt_drake.model.scenario import load_scenario
from rt_drake.model.vacuum import VacuumModel


def test_shipped_scenarios_load(scenario_paths):
    stack = load_scenario(scenario_paths["stack_four_objects"])
    assert [o.name for o in stack.objects] == [
        "whetstone_box",
        "kindle_box",
        "notebook",
        "carton_box",
    ]
    assert stack.cup.points == 6 and stack.cup.friction == pytest.approx(0.3)
    assert stack.vacuum.kind is VacuumModel.FIXED
    assert stack.vacuum.attach_s == pytest.approx(1.0)
    sensor = load_scenario(scenario_paths["stack_four_objects_vacuum_sensor"])
    assert sensor.vacuum.kind is VacuumModel.FIRST_ORDER
    assert [o.name for o in sensor.objects] == [o.name for o in stack.objects]
    assert sensor.vacuum.move_force_fraction == pytest.approx(0.8)
    transport = load_scenario(scenario_paths["random_transport"])
    assert transport.random_transport.object == "notebook"


def test_approach_offsets_resolve_per_object_then_the_scenario_default(
    scenario_paths,
):
    auto = load_scenario(scenario_paths["stack_four_objects"])
    paper = load_scenario(scenario_paths["stack_four_objects_paper"])
    names = [o.name for o in paper.objects]
    assert [auto.approach_offset(n) for n in names] == [None] * 4  # "auto"
    assert [paper.approach_offset(n) for n in names] == [0.15, 0.21, 0.24, 0.26]
    assert auto.planning.approach_clearance == pytest.approx(0.02)


def _write(tmp_path, scenario_paths, old: str, new: str):
    text = scenario_paths["stack_four_objects_paper"].read_text()
    assert old in text, old
    path = tmp_path / "bad.yaml"
    path.write_text(text.replace(old, new, 1))
    return path


BAD_EDITS = [
    # (old text, new text, words the message must contain)
    (
        "  approach_offset: 0.15",
        "  aproach_offset: 0.15",
        ["bad.yaml", "objects[0].aproach_offset", "unknown key"],
    ),
    (
        "start: {translation: [0.461, -0.357, 0.109]",
        "start: {translation: [0.461, -0.357]",
        ["bad.yaml", "objects[0].start.translation", "[0.461, -0.357]"],
    ),
    (
        "start: {translation: [0.461, -0.357, 0.109]",
        "start: {translation: [0.461, -0.357, high]",
        ["bad.yaml", "objects[0].start.translation", "'high'"],
    ),
    (
        "rotation: !Rpy {deg: [0, 0, 90]}}",
        "rotation: !Rpy {deg: [0, 90]}}",
        ["bad.yaml", "deg", "[0, 90]"],
    ),
    (
        "package://rt_drake/objects/notebook.sdf",
        "package://rt_drake/objects/notbook.sdf",
        ["bad.yaml", "objects[2].model", "notbook.sdf"],
    ),
    (
        "- name: kindle_box",
        "- name: whetstone_box",
        ["bad.yaml", "objects[1].name", "duplicate", "whetstone_box"],
    ),
    (
        "  approach_offset: 0.21",
        "  approach_offset: -0.21",
        ["bad.yaml", "objects[1].approach_offset", "-0.21"],
    ),
    ("  friction: 0.3", "  friction: -0.3", ["bad.yaml", "cup", "-0.3"]),
    ("  attach_s: 1.0", "  attach_s: 1.0\n  wait_s: 2", ["bad.yaml", "vacuum.wait_s"]),
    ("  model: fixed", "  model: fast", ["bad.yaml", "vacuum.model", "'fast'"]),
    ("  attach_s: 1.0", "  attach_s: -1.0", ["bad.yaml", "vacuum.attach_s", "-1.0"]),
    (
        "  attach_s: 1.0",
        "  attach_s: 1.0\n  build_up_tau_s: 0",
        ["bad.yaml", "vacuum.build_up_tau_s", "> 0"],
    ),
    (
        "  attach_s: 1.0",
        "  attach_s: 1.0\n  part_present_fraction: 1.5",
        ["bad.yaml", "vacuum.part_present_fraction", "1.5"],
    ),
    (
        "  approach_offset: 0.21",
        "  approach_offset: high",
        ["bad.yaml", "objects[1].approach_offset", "'high'", "'auto'"],
    ),
    (
        "  approach_offset: 0.21",
        "  approach_offset: [0.21]",
        ["bad.yaml", "objects[1].approach_offset", "a number or a string"],
    ),
    (
        "  approach_offset: 0.21",
        "  approach_offset: .nan",
        ["bad.yaml", "objects[1].approach_offset", "finite"],
    ),
    (
        "vacuum:\n",
        "planning:\n  approach_clearance: 0\nvacuum:\n",
        ["bad.yaml", "planning.approach_clearance", "(0, 0.2]", "got 0"],
    ),
    (
        "vacuum:\n",
        "planning:\n  approach_offset: -1\nvacuum:\n",
        ["bad.yaml", "planning.approach_offset", ">= 0 m", "-1"],
    ),
    (
        "vacuum:\n  model: fixed  # the paper's fixed 1 s waits (Table II)",
        "timing:",
        ["bad.yaml", "'timing' was renamed 'vacuum'", "attach_s: 1.0"],
    ),
]


@pytest.mark.parametrize("old,new,words", BAD_EDITS, ids=[e[2][1] for e in BAD_EDITS])
def test_bad_scenario_gives_one_line_naming_file_key_value(
    tmp_path, scenario_paths, old, new, words
):
    path = _write(tmp_path, scenario_paths, old, new)
    with pytest.raises(ScenarioError) as info:
        load_scenario(path)
    message = str(info.value)
    assert "\n" not in message
    for word in words:
        assert word in message, (word, message)


def test_missing_file(tmp_path):
    with pytest.raises(ScenarioError, match="nope.yaml.*does not exist"):
        load_scenario(tmp_path / "nope.yaml")


def test_unknown_object_name(scenario_paths):
    scenario = load_scenario(scenario_paths["stack_four_objects"])
    with pytest.raises(ScenarioError, match="unknown object 'stapler'.*notebook"):
        scenario.object("stapler")


def test_unknown_transport_object(tmp_path, scenario_paths):
    text = (
        scenario_paths["random_transport"]
        .read_text()
        .replace("  object: notebook", "  object: stapler")
    )
    path = tmp_path / "bad.yaml"
    path.write_text(text)
    with pytest.raises(ScenarioError, match="random_transport.object.*'stapler'"):
        load_scenario(path)


def test_cup_parameters_are_read_from_the_file(tmp_path, scenario_paths):
    # CupParameters is a field of the typed schema: non-default values arrive.
    text = scenario_paths["stack_four_objects"].read_text()
    text = text.replace("  points: 6", "  points: 8").replace(
        "  friction: 0.3", "  friction: 0.45"
    )
    path = tmp_path / "cup.yaml"
    path.write_text(text)
    cup = load_scenario(path).cup
    assert (cup.points, cup.friction) == (8, pytest.approx(0.45))


def _transport(tmp_path, scenario_paths, old: str, new: str, prefix: str = ""):
    text = scenario_paths["random_transport"].read_text()
    assert old in text, old
    path = tmp_path / "bad.yaml"
    path.write_text(prefix + text.replace(old, new, 1))
    return path


ALIAS_BOMB = "".join(
    f"{c}: &{c} [{', '.join([f'*{p}'] * 9) if p else 'lol'}]\n"
    for p, c in zip(["", *"abcdefgh"], "abcdefghi", strict=True)
)

REFUSED = [
    # (old text, new text, prefix, words the message must contain)
    (
        "cup:\n",
        "cup:\n  radius: 0.02\ncup:\n",
        "",
        ["line 26", "duplicate key 'cup' (first on line 24)"],  # after jerk_limits
    ),
    ("attach_s: 1.0", "attach_s: &t 1.0", "", []),  # an anchor alone is fine
    ("detach_s: 1.0", "detach_s: *t", "t: &t 1\n", ["line", "aliases (*t)"]),
    ("objects:\n", "objects:\n", ALIAS_BOMB, ["line 2", "aliases (*a)"]),
    ("objects:\n", "objects:\n", "x: " + "[" * 50 + "]" * 50 + "\n", ["deeper"]),
    ("objects:\n", "objects:\n- null\n", "", ["objects[0]", "got null"]),
    ("home: [0.0,", "home: [.nan,", "", ["robot.home[0]", "finite", "nan"]),
    ("home: [0.0, 0.35, 1.75, 0.0, 1.04, 0.0]", "home: 5", "", ["robot.home", "list"]),
    ("points: 6", "points: six", "", ["cup.points", "integer", "'six'"]),
    ("points: 6", "points: 6.0", "", ["cup.points", "integer", "6.0"]),
    ("radius: 0.0125", "radius: 1e-300", "", ["cup", "radius", "1e-300"]),
    ("- name: notebook", "- name: 5", "", ["objects[0].name", "string", "5"]),
    (
        "goal: {translation: [0.35,",
        "goal: {translation: [.inf,",
        "",
        ["objects[0].goal.translation[0]", "inf"],
    ),
    ("deg: [0, 0, 90]", "deg: [0, .nan, 90]", "", ["objects[0].start.rotation.deg[1]"]),
    (
        "home: [0.0, 0.35, 1.75, 0.0, 1.04, 0.0]",
        "home: [0.0, 0.35, 1.75, 0.0, 1.04, 0.0]\n  velocity_limits: [1, 2]",
        "",
        ["robot.velocity_limits", "2 values", "robot.home", "6 values"],
    ),
    (
        "jerk_limits: [394.67, 336.89,",
        "jerk_limits: [394.67,",
        "",
        ["robot.jerk_limits", "5 values", "robot.home", "6 values"],
    ),
    (
        "jerk_limits: [394.67,",
        "jerk_limits: [-1.0,",
        "",
        ["robot.jerk_limits", "must be > 0", "-1.0"],
    ),
    ("lower: [0.38,", "lower: [.nan,", "", ["random_transport.start_region.lower[0]"]),
]


@pytest.mark.parametrize(
    "old,new,prefix,words", REFUSED, ids=[f"{i}" for i in range(len(REFUSED))]
)
def test_scenarios_that_would_be_misread_are_refused(
    tmp_path, scenario_paths, old, new, prefix, words
):
    path = _transport(tmp_path, scenario_paths, old, new, prefix)
    if not words:
        load_scenario(path)
        return
    with pytest.raises(ScenarioError) as info:
        load_scenario(path)
    message = str(info.value)
    assert message.startswith(f"{path}: ") and "\n" not in message
    for word in words:
        assert word in message, (word, message)


def test_empty_objects_binary_and_directories_are_refused(tmp_path, scenario_paths):
    text = scenario_paths["random_transport"].read_text()
    (tmp_path / "none.yaml").write_text(
        text[: text.index("\nobjects:")] + "\nobjects: []\n"
    )
    with pytest.raises(ScenarioError, match="'objects': a scenario needs at least one"):
        load_scenario(tmp_path / "none.yaml")
    (tmp_path / "bin.yaml").write_bytes(b"\xff\xfe" + text.encode())
    with pytest.raises(ScenarioError, match="bin.yaml: not UTF-8 text"):
        load_scenario(tmp_path / "bin.yaml")
    with pytest.raises(ScenarioError, match="is a directory"):
        load_scenario(tmp_path)
    (tmp_path / "empty.yaml").write_text("")
    with pytest.raises(ScenarioError, match="got an empty file"):
        load_scenario(tmp_path / "empty.yaml")


def test_an_object_model_with_an_invalid_mass_is_refused_at_load(
    tmp_path, scenario_paths
):
    from rt_drake.model.resources import models_dir

    sdf = (models_dir() / "objects" / "notebook.sdf").read_text()
    (tmp_path / "o.sdf").write_text(sdf.replace("<mass>0.551</mass>", "<mass>0</mass>"))
    path = _transport(
        tmp_path,
        scenario_paths,
        "package://rt_drake/objects/notebook.sdf",
        str(tmp_path / "o.sdf"),
    )
    with pytest.raises(
        ScenarioError, match="'objects\\[0\\].model'.*o.sdf.*mass must be > 0"
    ):
        load_scenario(path)
