"""``rt-drake experiment``: the constraint keeps objects on; without it they slip."""

from __future__ import annotations

import json

import pytest

from rt_drake.cli import main
from rt_drake.experiments import SPEED_FACTORS, summarize

#: Whole-cycle simulations: tens of seconds (still run by CI).
pytestmark = pytest.mark.slow

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def _slipped(step: dict) -> bool:
    """A sweep step slipped: the object moved 5 mm or turned 3 deg on the cup."""
    return step["max_translation_mm"] >= 5.0 or step["max_rotation_deg"] >= 3.0


@pytest.fixture(scope="module")
def transport(tmp_path_factory):
    out = tmp_path_factory.mktemp("transport")
    # Table I's spline-versus-spline comparison (test_optimized_transport.py
    # plays the shaped MOVE beside it). One trial: on seed 0 its unconstrained
    # MOVE slips and the sweep reaches the first slipping factor; how the
    # summary counts several trials is checked on copies of it below.
    argv = ["experiment", "transport", "--n", "1", "--seed", "0", "--no-optimize"]
    assert main([*argv, "--out", str(out)]) == 0
    return out, json.loads((out / "results.json").read_text())


def test_every_constrained_path_holds_and_some_unconstrained_slips(transport):
    _, results = transport
    trials = results["trials"]
    assert len(trials) == 1
    assert all(t["success_constrained"] for t in trials)
    assert not any(t["success_unconstrained"] for t in trials)
    for t in trials:
        slip = t["slip_constrained"]
        assert slip["max_translation_mm"] < 5.0 and slip["max_rotation_deg"] < 3.0


def test_constraint_costs_time_and_the_trajectory_is_safe_but_near_critical(transport):
    _, results = transport
    for t in results["trials"]:
        assert t["duration_constrained_s"] >= t["duration_unconstrained_s"]
        expected = (
            100
            * (t["duration_constrained_s"] - t["duration_unconstrained_s"])
            / t["duration_constrained_s"]
        )
        assert t["time_extension_pct"] == pytest.approx(expected)
        sweep = t["speed_sweep"]
        assert sweep[0]["factor"] == 1.0 and sweep[0]["success"]
        # The sweep plays the factors in order, skipping none, and judges
        # each by its measured slip (5 mm, 3 deg).
        factors = [s["factor"] for s in sweep]
        assert factors == list(SPEED_FACTORS[: len(sweep)])
        for s in sweep:
            assert s["success"] == (not _slipped(s)), s
        # Critically fast: played a little faster, the object slips. The
        # critical factor is the FIRST that slips: every earlier one held.
        critical = t["critical_speed_factor"]
        assert critical is not None and 1.0 < critical <= 1.4
        first_slip = next(s["factor"] for s in sweep if _slipped(s))
        assert critical == first_slip
        at = factors.index(critical)
        assert not any(_slipped(s) for s in sweep[:at])
        assert _slipped(sweep[at])


def test_summary_counts_what_the_trials_show(transport):
    _, results = transport
    summary, trials = results["summary"], results["trials"]
    assert summary["success_constrained"] == sum(
        t["success_constrained"] for t in trials
    )
    assert summary["success_unconstrained"] == sum(
        t["success_unconstrained"] for t in trials
    )
    assert summary["critical_speed_factors"] == [
        t["critical_speed_factor"] for t in trials
    ]
    # Over several trials: the played one and two altered copies of it.
    (played,) = trials
    held = {**played, "success_unconstrained": True, "critical_speed_factor": 1.4}
    lost = {**played, "success_constrained": False, "critical_speed_factor": None}
    several = summarize([played, held, lost], not_retimed=2)
    assert several["n"] == 3 and several["n_sampled"] == 5
    assert several["success_constrained"] == 2
    assert several["success_unconstrained"] == 1
    assert several["critical_speed_factors"] == [
        played["critical_speed_factor"],
        1.4,
        None,
    ]


def test_report_table_and_plots_are_written(transport):
    out, results = transport
    report = (out / "report.md").read_text()
    for t in results["trials"]:
        row = f"| {t['index']} | {t['duration_unconstrained_s']:.3f} |"
        assert row in report
        assert f"{t['duration_constrained_s']:.3f}" in report
    for name in ("sd_profiles.png", "grasp_margin.png", "durations.png"):
        data = (out / name).read_bytes()
        assert data.startswith(PNG_MAGIC) and len(data) > 10_000, name


@pytest.mark.parametrize(
    "argv,words",
    [
        (["--n", "0"], ["--n", "0"]),
        (["--workers", "0"], ["--workers", "0"]),
        (["--object", "stapler"], ["stapler"]),
        (["--scenario", "stack_four_objects"], ["random_transport"]),
    ],
)
def test_bad_input_exits_2_with_one_line(tmp_path, capsys, argv, words):
    assert main(["experiment", "transport", *argv, "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1
    assert err.startswith("rt-drake experiment transport: error:")
    for word in words:
        assert word in err


def test_cycle_experiment_writes_the_breakdown(tmp_path):
    # The one-object scenario keeps the test short; the default is the
    # four-object stack of Table II.
    # Without jerk limits: the breakdown is the subject here, and the
    # jerk-limited retimes cost CPU (the transport fixture above has them).
    argv = [
        "experiment",
        "cycle",
        "--scenario",
        "random_transport",
        "--no-jerk-limits",
        "--out",
        str(tmp_path),
    ]
    assert main(argv) == 0
    (entry,) = json.loads((tmp_path / "report.json").read_text())["objects"]
    assert entry["name"] == "notebook" and entry["exec_s"]["move"] > 0
    assert "| MOVE retime |" in (tmp_path / "report.md").read_text()
    assert (tmp_path / "replay.html").stat().st_size > 100_000
