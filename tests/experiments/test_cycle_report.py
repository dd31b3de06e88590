"""The cycle report: totals, the plan on the critical path, picks per hour, floor."""

from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path

import pytest

from rt_drake.experiments import (
    CycleReport,
    ObjectFloor,
    RunSettings,
    cycle_report,
    summary_line,
    table_markdown,
    write_report,
)
from rt_drake.simulation import ObjectRecord, PlanTimes
from rt_drake.types.phase import Phase

#: report.json of :func:`_stored_records` with :data:`_SETTINGS`, written by
#: the report before it was a dataclass (a dict, ``json.dumps(report,
#: indent=2)``, at 60ab596), with the ``on_tool`` entries added since.
STORED = Path(__file__).parent / "data" / "cycle_report_small.json"

_SETTINGS = RunSettings(
    scenario="scenarios/pick_and_place.yaml",
    grasp_constraint=True,
    speed=1.0,
    pipelined_planning=True,
    vacuum="fixed",
    time_step_s=0.001,
    sim_time_s=9.4,
    max_tracking_error_rad=0.0012,
    simulation_wall_s=12.5,
)


def _record(name, wait):
    return ObjectRecord(
        name=name,
        plan_times={
            Phase.APPROACH: PlanTimes(0.02, 0.004),
            Phase.REACH: PlanTimes(0.01),
            Phase.MOVE: PlanTimes(0.03, 0.005),
        },
        plan_wait_s={Phase.APPROACH: wait, Phase.MOVE: 0.0},
        exec_s={
            Phase.APPROACH: 0.7,
            Phase.REACH: 0.3,
            Phase.ATTACH: 1.0,
            Phase.MOVE: 1.2,
            Phase.DETACH: 1.0,
        },
    )


def _stored_records():
    """A full record and one with phases, plans and measurements missing."""
    full = ObjectRecord(
        name="notebook",
        plan_times={
            Phase.APPROACH: PlanTimes(0.02, 0.004),
            Phase.REACH: PlanTimes(0.01),
            Phase.MOVE: PlanTimes(0.03, 0.005),
        },
        plan_wait_s={Phase.APPROACH: 0.034, Phase.MOVE: 0.0},
        exec_s={
            Phase.APPROACH: 0.7,
            Phase.REACH: 0.3,
            Phase.ATTACH: 1.0,
            Phase.MOVE: 1.2,
            Phase.DETACH: 1.0,
        },
        max_slip_translation=0.0016,
        max_slip_rotation=0.01,
        max_on_tool_translation=0.0042,
        max_on_tool_rotation=0.03,
        placement_translation=0.002,
        placement_rotation=0.02,
        move_suction_force=20.0,
        guarantee="the nominal object (0.551 kg)",
    )
    partial = ObjectRecord(
        name="carton_box",
        plan_times={
            Phase.APPROACH: PlanTimes(0.025, 0.003),
            Phase.MOVE: PlanTimes(0.04),
        },
        plan_wait_s={Phase.APPROACH: 0.0},
        exec_s={Phase.APPROACH: 0.8, Phase.ATTACH: 1.0, Phase.MOVE: 1.4},
    )
    return (full, partial)


def test_report_totals_and_picks_per_hour(tmp_path):
    report = cycle_report((_record("a", 0.034), _record("b", 0.0)))
    a, b = report.objects
    assert a.plan_on_critical_path_s == pytest.approx(0.034)
    assert a.total_s == pytest.approx(4.2 + 0.034)
    assert b.total_s == pytest.approx(4.2)
    # The paper's rows stay: planning time however much of it ran ahead.
    assert (b.plan_s.approach, b.plan_s.reach, b.plan_s.move, b.plan_s.retime) == (
        pytest.approx((0.024, 0.01, 0.03, 0.005))
    )
    assert report.total_s == pytest.approx(8.434)
    assert report.plan_on_critical_path_s == pytest.approx(0.034)
    assert report.mean_cycle_s == pytest.approx(4.217)
    assert report.picks_per_hour == pytest.approx(2 * 3600 / 8.434)
    json_path, md_path = write_report(report, tmp_path)
    written = json.loads(json_path.read_text())
    assert written["picks_per_hour"] == pytest.approx(report.picks_per_hour)
    assert "plan_on_critical_path_s" in written["objects"][0]
    text = md_path.read_text()
    assert "| plan on critical path | 0.034 | 0.000 |" in text
    assert "854 picks per hour" in text
    assert "**Total (critical plan + exec.)** | 4.234 | 4.200 |" in table_markdown(
        report
    )


def test_report_json_is_the_one_the_dict_report_wrote(tmp_path):
    """Same text as the stored report.json of the dict form, NaN included."""
    report = cycle_report(_stored_records(), _SETTINGS)
    assert isinstance(report, CycleReport)
    stored = STORED.read_text()
    assert report.to_json() == stored
    json_path, _ = write_report(report, tmp_path)
    assert json_path.read_text() == stored
    # The totals are those of the stored entries, summed independently.
    data = json.loads(stored)
    for entry, obj in zip(data["objects"], report.objects, strict=True):
        assert entry["total_s"] == entry["plan_on_critical_path_s"] + sum(
            entry["exec_s"].values()
        )
        assert [entry["exec_s"][p.value] for p in obj.exec_s] == list(
            obj.exec_s.values()
        )
    assert data["total_s"] == math.fsum(e["total_s"] for e in data["objects"])
    assert data["simulation_wall_s"] == _SETTINGS.simulation_wall_s
    assert math.isnan(data["objects"][1]["move_suction_force_n"])


def test_an_empty_cycle_has_no_mean_and_no_picks():
    report = cycle_report(())
    assert math.isnan(report.mean_cycle_s) and report.picks_per_hour == 0.0
    assert json.loads(report.to_json())["objects"] == []


def test_the_floor_is_set_beside_each_object_and_the_cycle(tmp_path):
    """floor_s = the motion floor + ATTACH + DETACH as run; ratio = total / floor."""
    floors = (
        ObjectFloor("a", 0.0, 0.6, 0.2, 0.1, 0.3, 0.1),
        ObjectFloor("b", 0.1, 0.55, 0.25, 0.1, 0.4, 0.1),
    )
    report = cycle_report((_record("a", 0.034), _record("b", 0.0)), None, floors)
    data = json.loads(report.to_json())
    for entry, floor in zip(data["objects"], floors, strict=True):
        expected = 0.0
        for part in (floor.retreat_s, floor.transit_s, floor.descent_s, floor.move_s):
            expected += part
        expected += entry["exec_s"]["attach"] + entry["exec_s"]["detach"]
        assert entry["floor_s"] == pytest.approx(expected, rel=1e-12)
        assert entry["floor_ratio"] == pytest.approx(entry["total_s"] / expected)
        segments = entry["floor_segments_s"]
        assert segments["lift_s"] + segments["carry_s"] + segments["set_down_s"] == (
            pytest.approx(floor.move_s, rel=1e-12)
        )
    total_floor = sum(e["floor_s"] for e in data["objects"])
    assert data["floor_s"] == pytest.approx(total_floor, rel=1e-12)
    assert data["floor_ratio"] == pytest.approx(data["total_s"] / total_floor)
    table = table_markdown(report)
    assert "| floor (joint limits, no grasp) | 3.300 | 3.500 |" in table
    assert "floor ratio (total / floor)" in table
    assert "floor 3.400 s per object" in summary_line(report)
    # without floors the report has no floor keys (older report.json files)
    plain = json.loads(cycle_report((_record("a", 0.0),)).to_json())
    assert "floor_s" not in plain and "floor_s" not in plain["objects"][0]


def test_the_grasp_price_is_reported_where_it_was_computed():
    """Each object's price and their sum; left out where not computed."""
    priced = [
        dataclasses.replace(_record(name, 0.0), grasp_price_s=price)
        for name, price in (("a", 0.05), ("b", 0.125))
    ]
    data = json.loads(cycle_report(tuple(priced)).to_json())
    assert [o["grasp_price_s"] for o in data["objects"]] == [0.05, 0.125]
    assert data["grasp_price_s"] == pytest.approx(0.175)
    assert "| grasp price (MOVE, acc. limits) | 0.050 | 0.125 |" in table_markdown(
        cycle_report(tuple(priced))
    )
    mixed = json.loads(cycle_report((priced[0], _record("c", 0.0))).to_json())
    assert "grasp_price_s" not in mixed["objects"][1]
    assert "grasp_price_s" not in mixed
