"""The ``optimized`` and ``robust`` variants in the physics, on the smallest campaign.

One object (the notebook, with an uncertainty set file), one cup (the
paper's), one trial, the ``constrained``, ``optimized`` and ``robust``
variants: three rows, run with the local executor as a user runs it. The
rows are checked against what is computed here apart from the campaign.
``optimized``:

- the optimised path joins the same grasp to the same goal as the spline
  path of the ``constrained`` row (its fingerprint and end waypoints);
- its stored duration equals, within 1 %, a fresh retime of the stored
  waypoints under the exact grasp constraint on 2000 uniform points (the
  campaign's retime uses the optimiser's 400-point adaptive grid; measured:
  1.1022 s stored, 1.1097 s on 1000 uniform points, 1.1000 s on 2000,
  1.0948 s on 4000; the same path without the grasp constraint: 0.874 s);
- the stored ratio and spline duration equal those of the ``constrained``
  row (an SQL join), and the report's numbers the SQL aggregation.

``robust``: its duration is at least that of the same spline path retimed
to hold only the set's corner objects, stacked
(:meth:`~rt_drake.retiming.GraspConstraint.for_objects`, another route than
the robust retime's), and at most a few percent above it; the robust MOVE
holds the true object in the physics; its price and the report's numbers
equal an SQL aggregation of the rows.

About a minute on 2 busy cores (planning three times, the optimisation, the
robust retime, four physics rollouts), so marked slow.
"""

from __future__ import annotations

import json
import sqlite3
from pathlib import Path

import numpy as np
import pytest

from rt_drake.cli import main
from rt_drake.experiments.campaign import RowKey, Variant, load_campaign
from rt_drake.planning import GeometricPath
from rt_drake.retiming import GraspConstraint
from rt_drake.simulation import OnlineMotions
from rt_drake.uncertainty.object_samples import (
    ObjectInertia,
    corners,
)

pytestmark = pytest.mark.slow

CAMPAIGN = """\
scenario: random_transport
objects:
- model: package://rt_drake/objects/notebook.sdf
  uncertainty: notebook_set.yaml
cups:
- name: paper
trials: 1
seed: 0
variants: [constrained, optimized, robust]
"""
#: The set of ``scenarios/random_transport_uncertain.yaml``'s notebook.
UNCERTAINTY = "mass: 0.2\ncom: [0.01, 0.01, 0.005]\ninertia: 0.2\n"


@pytest.fixture(scope="module")
def campaign_run(tmp_path_factory) -> tuple[Path, Path]:
    out = tmp_path_factory.mktemp("optimized")
    path, db = out / "campaign.yaml", out / "campaign.db"
    path.write_text(CAMPAIGN)
    (out / "notebook_set.yaml").write_text(UNCERTAINTY)
    argv = ["experiment", "campaign", str(path), "--out", str(db), "--workers", "1"]
    assert main(argv) == 0
    return path, db


def _row(db: Path, variant: str) -> sqlite3.Row:
    with sqlite3.connect(db) as sql:
        sql.row_factory = sqlite3.Row
        (row,) = sql.execute(
            "SELECT * FROM rollouts WHERE variant = ?", (variant,)
        ).fetchall()
    return row


def test_optimized_row_is_a_fresh_retime_of_its_stored_path(campaign_run):
    path, db = campaign_run
    spline_row, row = _row(db, "constrained"), _row(db, "optimized")
    assert row["status"] == spline_row["status"] == "ok"
    detail = json.loads(row["detail"])
    assert detail["path_sha256"] == json.loads(spline_row["detail"])["path_sha256"]
    assert detail["optimize_cpu_s"] > 0.0 and detail["optimize_wall_s"] > 0.0
    # never slower than the spline path on the optimiser's own grid
    assert row["duration_s"] <= detail["spline_same_grid_s"] * (1 + 1e-9)

    # The same grasp, goal and grasp constraint, planned again here; the
    # stored path retimed on a uniform grid twenty times the default.
    combination = load_campaign(path).combination(
        RowKey("notebook", "paper", 0, 0, Variant.OPTIMIZED)
    )
    motions = OnlineMotions(
        combination.scenario,
        grasp_constraint=True,
        seed=combination.planner_seed,
        gridpoints=2000,
        robust=False,  # the nominal notebook (its set is the robust row's)
        optimize=False,  # the spline MOVE the optimised row started from
    )
    (obj,) = combination.scenario.objects
    approach = motions.approach(motions.q_home, obj)
    reach = motions.reach(approach.q_end, obj)
    spline = motions.move(reach.q_end, obj, reach)
    assert spline.planned is not None and spline.grasp is not None
    waypoints = np.array(detail["waypoints_optimized"])
    np.testing.assert_allclose(waypoints[0], spline.planned.path.waypoints[0])
    np.testing.assert_allclose(waypoints[-1], spline.planned.path.waypoints[-1])
    fresh = motions.retime_path(GeometricPath.from_waypoints(waypoints), spline.grasp)
    assert row["duration_s"] == pytest.approx(fresh.duration, rel=1e-2)

    # held means under 5 mm and 3 deg of slip (the rollout's criterion)
    held = row["slip_translation_mm"] < 5.0 and row["slip_rotation_deg"] < 3.0
    assert bool(row["success"]) == held


def test_ratio_and_report_equal_the_sql_aggregation(campaign_run, tmp_path):
    _, db = campaign_run
    with sqlite3.connect(db) as sql:
        ((ratio, spline, d_c, held),) = sql.execute(
            "SELECT o.duration_s / c.duration_s,"
            " json_extract(o.detail, '$.spline_duration_s'), c.duration_s, o.success"
            " FROM rollouts o JOIN rollouts c USING (object, cup, seed, trial)"
            " WHERE o.variant = 'optimized' AND c.variant = 'constrained'"
        ).fetchall()
    detail = json.loads(_row(db, "optimized")["detail"])
    assert spline == pytest.approx(d_c, rel=1e-12)
    assert detail["ratio_to_spline"] == pytest.approx(ratio, rel=1e-12)
    assert main(["experiment", "report", str(db), "--out", str(tmp_path)]) == 0
    summary = json.loads((tmp_path / "summary.json").read_text())
    for optimized in (summary["optimized"], summary["groups"][0]["optimized"]):
        assert optimized["ran"] == 1 and optimized["held"] == held
        assert optimized["ratio_median"] == pytest.approx(ratio, rel=1e-12)
    table = (tmp_path / "summary.md").read_text()
    assert f"| {held}/1 | {ratio:.3f} |" in table


def test_robust_row_against_a_stacked_retime_of_the_set_corners(campaign_run):
    path, db = campaign_run
    spline_row, row = _row(db, "constrained"), _row(db, "robust")
    assert row["status"] == "ok", row["error"]
    detail = json.loads(row["detail"])
    assert detail["path_sha256"] == json.loads(spline_row["detail"])["path_sha256"]
    assert detail["nominal_duration_s"] == pytest.approx(
        spline_row["duration_s"], rel=1e-12
    )
    assert row["success"] == 1  # the robust MOVE holds the true object

    combination = load_campaign(path).combination(
        RowKey("notebook", "paper", 0, 0, Variant.ROBUST)
    )
    motions = OnlineMotions(
        combination.scenario,
        seed=combination.planner_seed,
        robust=False,
        optimize=False,  # the robust row plays the spline MOVE
    )
    (obj,) = combination.scenario.objects
    assert obj.uncertainty is not None
    approach = motions.approach(motions.q_home, obj)
    reach = motions.reach(approach.q_end, obj)
    spline = motions.move(reach.q_end, obj, reach)
    assert spline.planned is not None
    X_OC = spline.planned.X_OC
    held = [o.held(X_OC) for o in corners(ObjectInertia.of_model(obj), obj.uncertainty)]
    bound = motions.retime_path(
        spline.planned.path,
        GraspConstraint.for_objects(held, combination.scenario.cup),
    )
    tightness = row["duration_s"] / bound.duration
    assert 1.0 - 1e-9 <= tightness <= 1.05, tightness


def test_robust_price_and_report_equal_the_sql_aggregation(campaign_run, tmp_path):
    _, db = campaign_run
    with sqlite3.connect(db) as sql:
        ((price, held, nominal_held),) = sql.execute(
            "SELECT r.duration_s / c.duration_s, r.success,"
            " json_extract(r.detail, '$.nominal_on_true.success')"
            " FROM rollouts r JOIN rollouts c USING (object, cup, seed, trial)"
            " WHERE r.variant = 'robust' AND c.variant = 'constrained'"
        ).fetchall()
    assert json.loads(_row(db, "robust")["detail"])["price"] == pytest.approx(
        price, rel=1e-12
    )
    assert main(["experiment", "report", str(db), "--out", str(tmp_path)]) == 0
    summary = json.loads((tmp_path / "summary.json").read_text())
    for robust in (summary["robust"], summary["groups"][0]["robust"]):
        assert (robust["ran"], robust["held"]) == (1, held)
        assert robust["nominal_held"] == nominal_held
        assert robust["price_median"] == pytest.approx(price, rel=1e-12)
    table = (tmp_path / "summary.md").read_text()
    assert f"| {held}/1 ({nominal_held}) | {price:.3f} |" in table
