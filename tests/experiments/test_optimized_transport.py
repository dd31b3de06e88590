"""``rt-drake experiment transport --optimize``: the optimised MOVE next to Table I."""

from __future__ import annotations

import json

import pytest

from rt_drake.cli import main
from rt_drake.experiments import optimized_summary, summarize, transport_table

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
KEYS = (
    "duration_optimized_s",
    "success_optimized",
    "optimize_wall_s",
    "critical_speed_factor_optimized",
)


def trial(index: int, spline: float, same_grid: float, optimized: float) -> dict:
    return {
        "index": index,
        "duration_unconstrained_s": 1.0,
        "duration_constrained_s": spline,
        "time_extension_pct": 10.0,
        "success_unconstrained": False,
        "success_constrained": True,
        "critical_speed_factor": 1.1,
        "duration_optimized_s": optimized,
        "duration_spline_same_grid_s": same_grid,
        "success_optimized": True,
        "optimize_wall_s": 0.2,
        "optimize_cpu_s": 0.1,
        "critical_speed_factor_optimized": 1.2,
        "improved": optimized < same_grid,
    }


def test_summary_gives_the_median_ratios_against_both_spline_durations():
    trials = [trial(0, 1.3, 1.2, 0.9), trial(1, 1.2, 1.1, 1.1), trial(2, 1.4, 1.3, 1.0)]
    summary = summarize(trials)
    assert summary["ratio_median"] == pytest.approx(1.0 / 1.4)
    assert summary["ratio_same_grid_median"] == pytest.approx(1.0 / 1.3)
    assert summary["improved"] == 2 and summary["success_optimized"] == 3
    assert summary["critical_speed_factor_optimized_min"] == 1.2
    line = optimized_summary(summary)
    assert "0.714" in line and "0.769" in line and "\n" not in line
    table = transport_table({"optimize": True, "trials": trials})
    assert "optimized (s)" in table.splitlines()[0]
    assert "| 0.900 | ok | 0.692 | 1.2x |" in table
    assert "optimized" not in transport_table({"trials": trials})


@pytest.mark.slow
def test_optimized_move_holds_in_physics_and_is_reported(tmp_path):
    argv = ["experiment", "transport", "--n", "1", "--seed", "2", "--optimize"]
    argv.append("--no-jerk-limits")  # the optimiser's MOVE is acceleration-limited
    assert main([*argv, "--out", str(tmp_path)]) == 0
    results = json.loads((tmp_path / "results.json").read_text())
    (t,) = results["trials"]
    for key in KEYS:
        assert key in t, key
    assert t["success_optimized"]
    critical = t["critical_speed_factor_optimized"]
    assert critical is None or critical > 1.0
    assert t["duration_optimized_s"] <= t["duration_spline_same_grid_s"]
    assert "ratio_median" in results["summary"]
    data = (tmp_path / "optimized.png").read_bytes()
    assert data.startswith(PNG_MAGIC) and len(data) > 10_000
    assert (tmp_path / "optimized_replay.html").stat().st_size > 100_000
    assert "optimized (s)" in (tmp_path / "report.md").read_text()
