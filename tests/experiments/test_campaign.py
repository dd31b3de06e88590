"""Campaigns without physics: the file, the registry, the database, the report.

The physics runs (local and Ray executors, kill and resume) are in
test_campaign_run.py.
"""

from __future__ import annotations

import io
import json
import math
import random
import re
import sqlite3
import statistics
import sys

import pytest
from campaign_helpers import write_campaign, write_tool_campaign

from rt_drake.cli import main
from rt_drake.experiments.campaign import (
    VARIANTS,
    CampaignError,
    CampaignMismatchError,
    Outcome,
    RowKey,
    RowResult,
    Status,
    Variant,
    load_campaign,
    write_campaign_report,
)
from rt_drake.experiments.campaign._campaign_progress import Progress
from rt_drake.experiments.campaign._store import ResultStore
from rt_drake.model.resources import scenarios_dir

SHIPPED = scenarios_dir() / "campaigns" / "two_objects_two_cups.yaml"


def test_shipped_campaign_loads_with_its_rows_and_grasps():
    campaign = load_campaign(SHIPPED)
    assert [o.name for o in campaign.objects] == ["notebook", "kindle_box"]
    assert [c.name for c in campaign.cups] == ["paper", "small"]
    assert campaign.cups[1].parameters.suction_force == 4.0
    assert campaign.cups[1].parameters.points == 6  # default: the paper's cup
    keys = campaign.row_keys()
    assert len(keys) == len(set(keys)) == 2 * 2 * 2 * 3
    # Boxes are gripped at the centre of their top face (notebook 25 mm
    # thick, kindle box 28 mm), cup +z pointing down into the box.
    grasp = {o.name: o.X_OC for o in campaign.objects}
    assert grasp["notebook"].translation() == pytest.approx([0, 0, 0.0125])
    assert grasp["kindle_box"].translation() == pytest.approx([0, 0, 0.014])
    assert grasp["kindle_box"].rotation().matrix()[:, 2] == pytest.approx([0, 0, -1])


def test_trials_are_paired_and_objects_lie_where_the_base_object_would():
    campaign = load_campaign(SHIPPED)
    notebook = campaign.combination(
        RowKey("notebook", "paper", 0, 1, Variant.SPEED_SWEEP)
    )
    kindle = campaign.combination(
        RowKey("kindle_box", "small", 0, 1, Variant.CONSTRAINED)
    )
    (n,), (k,) = notebook.scenario.objects, kindle.scenario.objects
    X_n, X_k = n.start.GetDeterministicValue(), k.start.GetDeterministicValue()
    # Same pose, the kindle box's centre 1.5 mm higher (half of 28 - 25 mm).
    assert X_k.translation() - X_n.translation() == pytest.approx([0, 0, 0.0015])
    assert X_k.rotation().matrix() == pytest.approx(X_n.rotation().matrix())
    assert kindle.scenario.cup == campaign.cups[1].parameters
    assert notebook.planner_seed == kindle.planner_seed == 1


def test_content_hash_follows_content_not_formatting(tmp_path):
    base = load_campaign(write_campaign(tmp_path / "a.yaml"))
    again = load_campaign(write_campaign(tmp_path / "b.yaml"))
    (tmp_path / "c.yaml").write_text(
        "# a comment\n" + (tmp_path / "a.yaml").read_text().replace(": ", ":  ")
    )
    assert base.content_hash == again.content_hash
    assert load_campaign(tmp_path / "c.yaml").content_hash == base.content_hash
    more = load_campaign(write_campaign(tmp_path / "d.yaml", trials=3))
    assert more.content_hash != base.content_hash


def test_every_variant_has_a_function_and_unknown_ones_list_the_known():
    assert set(VARIANTS) == set(Variant)
    with pytest.raises(CampaignError) as error:
        Variant.parse("sturdy")
    assert str(error.value) == (
        "unknown variant 'sturdy' "
        "(known: constrained, unconstrained, speed_sweep, optimized, robust)"
    )


BAD_EDITS = [
    # (old text, new text, words the one-line message must contain)
    ("trials: 2", "trails: 2", ["bad.yaml", "unknown key 'trails'"]),
    ("  radius: 0.010", "  radus: 0.010", ["bad.yaml", "cups[1].radus"]),
    ("trials: 2", "trials: two", ["bad.yaml", "'trials'", "'two'"]),
    ("trials: 2", "trials: 0", ["bad.yaml", "'trials'", "got 0"]),
    ("[constrained]", "[constrained, sturdy]", ["variants[1]", "sturdy", "known:"]),
    (
        "notebook.sdf\n",
        "notebook.sdf\n  uncertainty: nowhere.yaml\n",
        ["objects[0].uncertainty", "no such file", "nowhere.yaml"],
    ),
    ("  radius: 0.010", "  points: 2", ["bad.yaml", "cups[1]", "points", "2"]),
    ("- name: small", "- name: paper", ["cups[1].name", "duplicate", "paper"]),
    ("notebook.sdf", "notbook.sdf", ["objects[0].model", "notbook.sdf"]),
    ("random_transport", "stack_four_objects", ["'scenario'", "random_transport"]),
    ("random_transport", "nowhere", ["'scenario'", "nowhere"]),
    ("seed: 0", "seed: 0\nseed: 1", ["bad.yaml", "duplicate key 'seed'"]),
    ("  radius: 0.010", "  radius: .nan", ["bad.yaml", "cups[1].radius", "finite"]),
]


BAD_SETS = [
    # (uncertainty file, words the one-line message must contain)
    ("mass: 1.5\n", ["objects[0].uncertainty", "set.yaml", "mass", "1.5"]),
    ("mas: 0.2\n", ["objects[0].uncertainty", "set.yaml", "unknown key 'mas'"]),
    ("com: [0.5, 0, 0]\n", ["objects[0].uncertainty", "com[0]", "outside"]),
    ("inertia: .nan\n", ["objects[0].uncertainty", "inertia", "finite"]),
]


@pytest.mark.parametrize("text,words", BAD_SETS)
def test_bad_uncertainty_file_is_one_line_naming_it(tmp_path, text, words):
    (tmp_path / "set.yaml").write_text(text)
    good = write_campaign(tmp_path / "good.yaml").read_text()
    path = tmp_path / "bad.yaml"
    path.write_text(
        good.replace("notebook.sdf\n", "notebook.sdf\n  uncertainty: set.yaml\n")
    )
    _assert_refused(path, words)


def test_uncertainty_file_reaches_the_robust_row_only(tmp_path):
    (tmp_path / "set.yaml").write_text("mass: 0.2\ncom: [0.01, 0.01, 0.005]\n")
    good = write_campaign(tmp_path / "good.yaml", variants="[constrained, robust]")
    text = good.read_text()
    path = tmp_path / "set_campaign.yaml"
    path.write_text(
        text.replace("notebook.sdf\n", "notebook.sdf\n  uncertainty: set.yaml\n")
    )
    campaign = load_campaign(path)
    assert campaign.content_hash != load_campaign(good).content_hash
    key = RowKey("notebook", "paper", 0, 0, Variant.ROBUST)
    (obj,) = campaign.combination(key).scenario.objects
    assert obj.uncertainty is not None
    assert (obj.uncertainty.mass, obj.uncertainty.com) == (0.2, [0.01, 0.01, 0.005])


@pytest.mark.parametrize("old,new,words", BAD_EDITS)
def test_bad_campaign_is_one_line_naming_file_key_value(tmp_path, old, new, words):
    text = write_campaign(tmp_path / "good.yaml").read_text()
    assert old in text, old
    path = tmp_path / "bad.yaml"
    path.write_text(text.replace(old, new, 1))
    _assert_refused(path, words)


def test_a_tool_entry_names_its_rows_and_sets_the_trial_scenarios_tool(tmp_path):
    campaign = load_campaign(write_tool_campaign(tmp_path / "tool.yaml"))
    assert [(c.name, c.tool is None) for c in campaign.cups] == [
        ("weak", True),
        ("weak_pair", False),
    ]
    assert [k.cup for k in campaign.row_keys()] == ["weak", "weak_pair"]
    single, pair = (
        campaign.combination(RowKey("kindle_box", cup, 0, 0, Variant.CONSTRAINED))
        for cup in ("weak", "weak_pair")
    )
    assert single.scenario.tool is None
    assert single.scenario.cup.suction_force == 1.8
    tool = pair.scenario.tool_parameters()
    assert [m.p_TC.tolist() for m in tool.cups] == [[0.04, 0, 0], [-0.04, 0, 0]]
    assert [(m.cup.points, m.cup.suction_force) for m in tool.cups] == [(4, 1.8)] * 2
    # Moving one cup of the tool is another campaign.
    text = (tmp_path / "tool.yaml").read_text()
    (tmp_path / "moved.yaml").write_text(text.replace("[0.04,", "[0.05,", 1))
    moved = load_campaign(tmp_path / "moved.yaml")
    assert moved.content_hash != campaign.content_hash


def test_a_cup_entry_replaces_the_base_scenarios_tool(tmp_path):
    path = write_campaign(tmp_path / "c.yaml").read_text()
    (tmp_path / "c.yaml").write_text(
        path.replace("random_transport", "carton_two_cups").replace(
            "notebook.sdf", "carton_box.sdf"
        )
    )
    campaign = load_campaign(tmp_path / "c.yaml")
    assert campaign.scenario.tool is not None  # the base: a two-cup tool
    key = RowKey("carton_box", "small", 0, 0, Variant.CONSTRAINED)
    scenario = campaign.combination(key).scenario
    assert scenario.tool is None and scenario.cup.suction_force == 4.0
    assert len(scenario.tool_parameters().cups) == 1


BAD_TOOL_EDITS = [
    # (old text, new text, words the one-line message must contain)
    (
        "[0.04, 0.0, 0.0]}, points: 4",
        "[0.04, 0.0, 0.0]}, points: 2",
        ["tool.yaml", "cups[1].tool.cups[0].points", "got 2"],
    ),
    (
        "[0.04, 0.0, 0.0]}, points: 4",
        "[0.04, 0.0, 0.0]}, pionts: 4",
        ["tool.yaml", "unknown key 'cups[1].tool.cups[0].pionts'"],
    ),
    (
        "[0.04, 0.0, 0.0]}",
        "[0.04, 0.0]}",
        ["tool.yaml", "cups[1].tool.cups[0].pose.translation", "[0.04, 0.0]"],
    ),
    (
        "[0.04, 0.0, 0.0]}, points: 4",
        "[0.04, 0.0, 0.0]}, friction: .nan, points: 4",
        ["tool.yaml", "cups[1].tool.cups[0].friction", "nan"],
    ),
    (
        "  tool:\n",
        "  radius: 0.01\n  tool:\n",
        ["tool.yaml", "cups[1].radius", "a tool entry takes", "0.01"],
    ),
    ("- name: weak_pair\n  tool:", "- tool:", ["cups[1].name", "a tool needs a name"]),
    ("name: weak_pair", "name: weak", ["cups[1].name", "duplicate", "weak"]),
    ("    cups:\n", "    cup:\n", ["unknown key 'cups[1].tool.cup'"]),
    (
        re.compile(r"  tool:\n(    .*\n)+"),
        "  tool: {cups: []}\n",
        ["tool.yaml", "cups[1].tool.cups", "at least one cup"],
    ),
]


@pytest.mark.parametrize("old,new,words", BAD_TOOL_EDITS)
def test_bad_tool_entry_is_one_line_naming_file_key_value(tmp_path, old, new, words):
    text = write_tool_campaign(tmp_path / "good.yaml").read_text()
    path = tmp_path / "tool.yaml"
    if isinstance(old, re.Pattern):
        bad = old.sub(new, text, count=1)
    else:
        bad = text.replace(old, new, 1)
    assert bad != text, old
    path.write_text(bad)
    _assert_refused(path, words)


def _outcome(key: RowKey, result: RowResult) -> Outcome:
    return Outcome(key, result, 1.0, 0.5, worker="test:1", code_version="test")


def test_store_keeps_one_row_per_combination_and_refuses_another_campaign(tmp_path):
    campaign = load_campaign(write_campaign(tmp_path / "c.yaml"))
    key = campaign.row_keys()[0]
    db = tmp_path / "c.db"
    with ResultStore(db, campaign) as store:
        store.add(_outcome(key, RowResult(Status.OK, duration_s=1.0, success=True)))
        store.add(_outcome(key, RowResult(Status.OK, duration_s=2.0, success=False)))
        store.add(
            _outcome(campaign.row_keys()[1], RowResult.failed(Status.CRASHED, "x"))
        )
        assert store.finished() == set(campaign.row_keys()[:2])
        assert store.forget(Status.ERROR, Status.CRASHED) == 1
    with sqlite3.connect(db) as connection:
        assert connection.execute("PRAGMA journal_mode").fetchone() == ("wal",)
        rows = connection.execute("SELECT duration_s, success FROM rollouts").fetchall()
    assert rows == [(1.0, 1)]  # the first one stays
    other = load_campaign(write_campaign(tmp_path / "d.yaml", trials=3))
    with pytest.raises(CampaignMismatchError) as error:
        ResultStore(db, other)
    assert "c.yaml" in str(error.value) and "d.yaml" in str(error.value)


def test_cli_refuses_to_mix_campaigns_in_one_database(tmp_path, capsys):
    first = load_campaign(write_campaign(tmp_path / "c.yaml"))
    ResultStore(tmp_path / "c.db", first).close()
    other = write_campaign(tmp_path / "d.yaml", trials=3)
    argv = ["experiment", "campaign", str(other), "--out", str(tmp_path / "c.db")]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1
    assert err.startswith("rt-drake experiment campaign: error:")
    assert "another campaign" in err and first.content_hash[:12] in err


def test_ray_executor_without_ray_says_how_to_install_it(tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "ray", None)  # import ray -> ImportError
    path = write_campaign(tmp_path / "c.yaml")
    argv = ["experiment", "campaign", str(path), "--out", str(tmp_path / "c.db")]
    assert main([*argv, "--executor", "ray"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1
    assert 'pip install "rt-drake[ray]"' in err
    assert not (tmp_path / "c.db").exists()


def test_plain_progress_lines_count_done_failures_and_eta():
    stream = io.StringIO()
    progress = Progress(total=4, done=1, failed=1, stream=stream, interval=0.0)
    progress.advance(failed=False)
    progress.advance(failed=True)
    lines = stream.getvalue().splitlines()
    assert lines[0].startswith("campaign: 2/4 rows (50%), 1 failed")
    assert lines[1].startswith("campaign: 3/4 rows (75%), 2 failed")
    assert "rows/min" in lines[1] and "ETA" in lines[1]


def _synthetic(campaign, seed: int = 0) -> list[Outcome]:
    """Random results for every row: some infeasible, crashed, never slipping."""
    rng = random.Random(seed)
    outcomes = []
    for key in campaign.row_keys():
        roll = rng.random()
        if roll < 0.1:
            result = RowResult.failed(Status.INFEASIBLE, "GraspUnstableAtRestError: x")
        elif roll < 0.15:
            result = RowResult.failed(Status.CRASHED, "WorkerCrashed: y")
        else:
            critical = rng.choice([None, 1.1, 1.2, 1.3, 1.6])
            detail = {}
            if key.variant is Variant.OPTIMIZED:
                detail = {
                    "ratio_to_spline": rng.uniform(0.7, 1.0),
                    "optimize_cpu_s": rng.uniform(0.1, 0.5),
                }
            if key.variant is Variant.ROBUST:
                detail = {
                    "price": rng.uniform(1.0, 1.5),
                    "nominal_on_true": {"success": rng.random() < 0.5},
                }
            result = RowResult(
                Status.OK,
                duration_s=rng.uniform(0.8, 1.6),
                speed=1.0,
                success=rng.random() < 0.7,
                critical_speed=critical if key.variant is Variant.SPEED_SWEEP else None,
                detail=detail,
            )
        outcomes.append(_outcome(key, result))
    return outcomes


def test_report_numbers_equal_an_independent_sql_aggregation(tmp_path):
    campaign = load_campaign(
        write_campaign(
            tmp_path / "c.yaml",
            trials=6,
            variants="[constrained, unconstrained, speed_sweep, optimized, robust]",
        )
    )
    db = tmp_path / "c.db"
    with ResultStore(db, campaign) as store:
        for outcome in _synthetic(campaign):
            store.add(outcome)
    written = write_campaign_report(db, tmp_path / "report")
    assert {p.name for p in written} >= {"summary.md", "success_rates.png"}
    summary = json.loads((tmp_path / "report" / "summary.json").read_text())
    groups = {(g["object"], g["cup"]): g for g in summary["groups"]}
    with sqlite3.connect(db) as sql:
        assert (
            summary["rows"]
            == sql.execute("SELECT COUNT(*) FROM rollouts").fetchone()[0]
        )
        by_status = dict(
            sql.execute("SELECT status, COUNT(*) FROM rollouts GROUP BY status")
        )
        assert summary["status"] == {s.value: by_status.get(s.value, 0) for s in Status}
        assert list(summary["status"]) == ["ok", "infeasible", "error", "crashed"]
        counts = sql.execute(
            "SELECT object, cup, variant, COUNT(*),"
            " SUM(status = 'ok'), SUM(CASE WHEN status = 'ok' THEN success END),"
            " SUM(status = 'infeasible'), SUM(status IN ('error', 'crashed'))"
            " FROM rollouts GROUP BY object, cup, variant"
        ).fetchall()
        for obj, cup, variant, rows, ran, held, infeasible, failed in counts:
            got = groups[(obj, cup)]["variants"][variant]
            assert (got["rows"], got["ran"], got["held"]) == (rows, ran, held or 0)
            assert (got["infeasible"], got["failed"]) == (infeasible, failed)
            assert got["success_rate"] == (held / ran if ran else None)
        extension = sql.execute(
            "SELECT c.object, c.cup, COUNT(*),"
            " AVG(100.0 * (c.duration_s - u.duration_s) / c.duration_s),"
            " MIN(100.0 * (c.duration_s - u.duration_s) / c.duration_s)"
            " FROM rollouts c JOIN rollouts u USING (object, cup, seed, trial)"
            " WHERE c.variant = 'constrained' AND u.variant = 'unconstrained'"
            " AND c.status = 'ok' AND u.status = 'ok' GROUP BY c.object, c.cup"
        ).fetchall()
        assert len(extension) == len(groups)
        for obj, cup, n, mean, low in extension:
            got = groups[(obj, cup)]["time_extension_pct"]
            assert got["n"] == n
            assert got["mean"] == pytest.approx(mean, rel=1e-12)
            assert got["min"] == pytest.approx(low, rel=1e-12)
        for (obj, cup), group in groups.items():
            critical = [
                value
                for (value,) in sql.execute(
                    "SELECT critical_speed FROM rollouts WHERE object = ? AND cup = ?"
                    " AND variant = 'speed_sweep' AND status = 'ok'",
                    (obj, cup),
                )
            ]
            slipped = [c for c in critical if c is not None]
            got = group["critical_speed"]
            assert got["n"] == len(slipped)
            assert got["held_through_sweep"] == len(critical) - len(slipped)
            if slipped:
                assert got["median"] == statistics.median(slipped)
                assert got["min"] == min(slipped)
        _check_optimized(sql, summary, groups)
        _check_robust(sql, summary, groups)
    table = (tmp_path / "report" / "summary.md").read_text()
    for (obj, cup), group in groups.items():
        held = group["variants"]["constrained"]
        assert f"| {obj} | {cup} | {held['held']}/{held['ran']} |" in table
        optimized = group["variants"]["optimized"]
        ratio = group["optimized"]["ratio_median"]
        assert f" {optimized['held']}/{optimized['ran']} | {ratio:.3f} |" in table
        robust = group["robust"]
        assert (
            f" {robust['held']}/{robust['ran']} ({robust['nominal_held']}) | "
            f"{robust['price_median']:.3f} |"
        ) in table
    assert not math.isnan(summary["groups"][0]["time_extension_pct"]["mean"])


def _check_optimized(sql: sqlite3.Connection, summary: dict, groups: dict) -> None:
    """The optimized numbers against the rows' JSON detail, read by SQLite."""
    query = (
        "SELECT object, cup, success, json_extract(detail, '$.ratio_to_spline'),"
        " json_extract(detail, '$.optimize_cpu_s') FROM rollouts"
        " WHERE variant = 'optimized' AND status = 'ok'"
    )
    rows = sql.execute(query).fetchall()
    assert rows and summary["optimized"]["ran"] == len(rows)
    assert summary["optimized"]["held"] == sum(r[2] for r in rows)
    assert summary["optimized"]["ratio_median"] == statistics.median(r[3] for r in rows)
    for (obj, cup), group in groups.items():
        mine = [r for r in rows if r[:2] == (obj, cup)]
        got = group["optimized"]
        assert (got["ran"], got["held"]) == (len(mine), sum(r[2] for r in mine))
        assert got["ratio_median"] == statistics.median(r[3] for r in mine)
        assert got["ratio_min"] == min(r[3] for r in mine)
        assert got["optimize_cpu_s_median"] == statistics.median(r[4] for r in mine)


def _check_robust(sql: sqlite3.Connection, summary: dict, groups: dict) -> None:
    """The robust numbers against the rows' JSON detail, read by SQLite."""
    rows = sql.execute(
        "SELECT object, cup, success, json_extract(detail, '$.price'),"
        " json_extract(detail, '$.nominal_on_true.success') FROM rollouts"
        " WHERE variant = 'robust' AND status = 'ok'"
    ).fetchall()
    assert rows and summary["robust"]["ran"] == len(rows)
    assert summary["robust"]["held"] == sum(r[2] for r in rows)
    assert summary["robust"]["nominal_held"] == sum(r[4] for r in rows)
    assert summary["robust"]["price_median"] == statistics.median(r[3] for r in rows)
    for (obj, cup), group in groups.items():
        mine = [r for r in rows if r[:2] == (obj, cup)]
        got = group["robust"]
        assert (got["ran"], got["held"]) == (len(mine), sum(r[2] for r in mine))
        assert got["nominal_held"] == sum(r[4] for r in mine)
        assert got["price_median"] == statistics.median(r[3] for r in mine)
        assert got["price_max"] == max(r[3] for r in mine)


@pytest.mark.parametrize(
    "argv,words",
    [
        (["campaign", "{campaign}", "--out", "{text}"], ["not.db", "not a campaign"]),
        (["report", "{missing}", "--out", "{tmp}"], ["missing.db", "does not exist"]),
        (["report", "{text}", "--out", "{tmp}"], ["not.db", "not a campaign"]),
        (
            ["campaign", "{campaign}", "--out", "{tmp}/c.db", "--ray-address", "auto"],
            ["Ray address", "ray executor"],
        ),
        (
            ["campaign", "{campaign}", "--out", "{tmp}/c.db", "--workers", "1000"],
            ["--workers", "[1, 64]", "1000"],
        ),
    ],
)
def test_bad_database_or_flags_exit_2_with_one_line(tmp_path, capsys, argv, words):
    (tmp_path / "not.db").write_text("a text file, not SQLite\n" * 100)
    names = {
        "campaign": write_campaign(tmp_path / "c.yaml"),
        "text": tmp_path / "not.db",
        "missing": tmp_path / "missing.db",
        "tmp": tmp_path,
    }
    assert main(["experiment", *(a.format(**names) for a in argv)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and ": error: " in err
    for word in words:
        assert word in err, (word, err)


def test_without_variants_the_campaign_runs_table_one_comparisons(tmp_path):
    """No ``variants`` key: constrained, unconstrained and the speed sweep only."""
    campaign = load_campaign(write_campaign(tmp_path / "c.yaml", variants=None))
    assert [variant.value for variant in campaign.variants] == [
        "constrained",
        "unconstrained",
        "speed_sweep",
    ]


def _assert_refused(path, words) -> None:
    """Loading ``path`` raises a one-line CampaignError holding every word."""
    with pytest.raises(CampaignError) as error:
        load_campaign(path)
    message = str(error.value)
    assert "\n" not in message
    for word in words:
        assert word in message, (word, message)
