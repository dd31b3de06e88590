"""The cycle report: totals, the plan on the critical path, picks per hour."""

from __future__ import annotations

import json

import pytest

from rt_drake.experiments import cycle_report, table_markdown, write_report
from rt_drake.simulation import ObjectRecord, PlanTimes
from rt_drake.types.phase import Phase


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


def test_report_totals_and_picks_per_hour(tmp_path):
    report = cycle_report((_record("a", 0.034), _record("b", 0.0)))
    a, b = report["objects"]
    assert a["plan_on_critical_path_s"] == pytest.approx(0.034)
    assert a["total_s"] == pytest.approx(4.2 + 0.034)
    assert b["total_s"] == pytest.approx(4.2)
    # The paper's rows stay: planning time however much of it ran ahead.
    assert b["plan_s"] == pytest.approx(
        {"approach": 0.024, "reach": 0.01, "move": 0.03, "retime": 0.005}
    )
    assert report["total_s"] == pytest.approx(8.434)
    assert report["plan_on_critical_path_s"] == pytest.approx(0.034)
    assert report["mean_cycle_s"] == pytest.approx(4.217)
    assert report["picks_per_hour"] == pytest.approx(2 * 3600 / 8.434)
    json_path, md_path = write_report(report, tmp_path)
    written = json.loads(json_path.read_text())
    assert written["picks_per_hour"] == pytest.approx(report["picks_per_hour"])
    assert "plan_on_critical_path_s" in written["objects"][0]
    text = md_path.read_text()
    assert "| plan on critical path | 0.034 | 0.000 |" in text
    assert "854 picks per hour" in text
    assert "**Total (critical plan + exec.)** | 4.234 | 4.200 |" in table_markdown(
        report
    )
