"""``rt-drake run``: the simulated cycle carries the object, and reports it."""

from __future__ import annotations

import json

import pytest

from rt_drake.cli import main
from rt_drake.simulation.visualization import (
    meshcat_command_types,
    meshcat_paths_in_html,
)

#: Whole-cycle simulations: tens of seconds (still run by CI).
pytestmark = pytest.mark.slow

#: rad; the PD + inverse-dynamics arm follows critically fast motions within this.
TRACKING_TOLERANCE = 5e-3


@pytest.fixture(scope="module")
def constrained_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("run")
    # 0.5 ms: the held object's numerical friction creep is ~0.8 mm per MOVE.
    # TOPP-RA's profiles (no jerk limits), as the assertions below expect.
    argv = ["run", "random_transport", "--out", str(out), "--time-step", "0.0005"]
    assert main([*argv, "--no-jerk-limits"]) == 0
    return out, json.loads((out / "report.json").read_text())


def test_report_has_every_field(constrained_run):
    _, report = constrained_run
    (entry,) = report["objects"]
    assert entry["name"] == "notebook"
    assert set(entry["plan_s"]) == {"approach", "reach", "move", "retime"}
    assert set(entry["exec_s"]) == {"approach", "reach", "attach", "move", "detach"}
    assert set(entry["slip"]) == {"max_translation_mm", "max_rotation_deg"}
    assert set(entry["placement_error"]) == {"translation_mm", "rotation_deg"}
    assert all(v > 0 for v in entry["plan_s"].values())
    assert all(v > 0 for v in entry["exec_s"].values())
    assert 0.0 <= entry["plan_on_critical_path_s"] <= sum(entry["plan_s"].values())
    assert entry["total_s"] == pytest.approx(
        entry["plan_on_critical_path_s"] + sum(entry["exec_s"].values())
    )
    assert entry["exec_s"]["attach"] == pytest.approx(1.0, abs=0.01)
    assert entry["guarantee"] == "the nominal object (0.551 kg)"
    assert report["plan_on_critical_path_s"] == entry["plan_on_critical_path_s"]
    assert report["pipelined_planning"] is True  # the default
    assert report["picks_per_hour"] == pytest.approx(3600.0 / report["total_s"])
    # The simulation waited for the plan on the critical path: it adds up.
    assert report["sim_time_s"] == pytest.approx(report["total_s"], abs=0.01)
    # The floor: the motion floor plus ATTACH and DETACH; no cycle beats it.
    waits = entry["exec_s"]["attach"] + entry["exec_s"]["detach"]
    motion = sum(entry["floor_segments_s"].values())
    assert entry["floor_s"] == pytest.approx(motion + waits)
    assert motion > 0.0
    assert entry["floor_ratio"] == pytest.approx(entry["total_s"] / entry["floor_s"])
    assert entry["floor_ratio"] > 1.0
    assert report["floor_ratio"] == pytest.approx(report["total_s"] / entry["floor_s"])


def test_object_lands_on_its_goal_without_slipping(constrained_run):
    _, report = constrained_run
    (entry,) = report["objects"]
    assert entry["placement_error"]["translation_mm"] < 10.0
    assert entry["placement_error"]["rotation_deg"] < 5.0
    assert entry["slip"]["max_translation_mm"] < 2.0
    assert entry["slip"]["max_rotation_deg"] < 2.0


def test_arm_tracks_the_commanded_motion(constrained_run):
    _, report = constrained_run
    assert report["max_tracking_error_rad"] < TRACKING_TOLERANCE


def test_replay_holds_the_recording(constrained_run):
    out, _ = constrained_run
    html = (out / "replay.html").read_text()
    assert meshcat_command_types(html).get("set_animation", 0) == 1
    paths = meshcat_paths_in_html(html)
    assert any("/notebook/" in p for p in paths) and any("/vs060/" in p for p in paths)
    assert "| MOVE retime |" in (out / "report.md").read_text()
    assert "| floor (joint limits, no grasp) |" in (out / "report.md").read_text()


def test_without_the_grasp_constraint_and_planned_sequentially_the_object_slips(
    tmp_path, capsys
):
    """Two options in one run (each changes a part the other does not read):
    joint limits only, so the object slips; and each motion planned when its
    phase starts, so all the planning is on the critical path."""
    # Without jerk limits: the slip and the planning are the subjects (and the
    # CPU stays low).
    argv = ["run", "random_transport", "--no-grasp-constraint", "--no-jerk-limits"]
    argv += ["--sequential-planning", "--out", str(tmp_path)]
    assert main(argv) == 0
    report = json.loads((tmp_path / "report.json").read_text())
    (entry,) = report["objects"]
    assert entry["slip"]["max_translation_mm"] > 5.0
    assert entry["guarantee"] == "none: joint limits only"
    # The shaping (on by default) needs the grasp constraint: said once.
    assert capsys.readouterr().out.count("MOVE shaping off") == 1
    assert report["pipelined_planning"] is False
    # Each motion is planned when its phase starts: the arm waits for all of it.
    assert entry["plan_on_critical_path_s"] == pytest.approx(
        sum(entry["plan_s"].values()), abs=1e-9
    )
    assert report["sim_time_s"] == pytest.approx(report["total_s"], abs=0.01)


def test_an_uncertain_object_is_moved_robustly_and_the_report_says_so(tmp_path, capsys):
    assert main(["run", "random_transport_uncertain", "--out", str(tmp_path)]) == 0
    (entry,) = json.loads((tmp_path / "report.json").read_text())["objects"]
    assert entry["guarantee"].startswith("every object of the set (mass +-20 %")
    assert entry["slip"]["max_translation_mm"] < 2.0
    assert "every object of the set" in (tmp_path / "report.md").read_text()
    assert "MOVE notebook holds every object of the set" in capsys.readouterr().out


@pytest.mark.parametrize(
    "argv,words",
    [
        (["run", "random_transport", "--speed", "0"], ["--speed", "0"]),
        (["run", "random_transport", "--time-step", "0.5"], ["--time-step", "0.5"]),
        (["run", "nowhere.yaml"], ["nowhere.yaml", "does not exist"]),
    ],
)
def test_bad_input_exits_2_with_one_line(tmp_path, capsys, argv, words):
    assert main([*argv, "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and err.startswith("rt-drake run: error:")
    for word in words:
        assert word in err
