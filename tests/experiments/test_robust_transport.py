"""Robust plans hold the objects the robot does not know; nominal plans do not.

Physics: the same planned MOVE, retimed for the nominal notebook and for
every notebook of its uncertainty set, played with a true notebook from the
set's hardest corners (its inertia set in the simulated plant).
"""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest
from pydrake.common.schema import Transform

from rt_drake.cli import main
from rt_drake.experiments._rollout import (
    rollout_scenario,
    simulate_move,
)
from rt_drake.model.resources import scenarios_dir
from rt_drake.model.scenario import load_scenario
from rt_drake.planning import sample_transports
from rt_drake.simulation import OnlineMotions
from rt_drake.uncertainty.object_samples import (
    ObjectInertia,
    hardest_corner,
)

#: Whole-cycle simulations: tens of seconds (still run by CI).
pytestmark = pytest.mark.slow

UNCERTAIN = scenarios_dir() / "random_transport_uncertain.yaml"


def test_nominal_plan_slips_with_a_perturbed_object_and_the_robust_plan_holds():
    scenario = load_scenario(UNCERTAIN)
    obj = scenario.object("notebook")
    ((X_start, X_goal),) = sample_transports(scenario, 1, 0)
    trial = dataclasses.replace(
        scenario,
        objects=[
            dataclasses.replace(obj, start=Transform(X_start), goal=Transform(X_goal))
        ],
    )
    motions = OnlineMotions(trial, seed=0, robust=False, optimize=False)
    carried = trial.objects[0]
    reach = motions.reach(motions.approach(motions.q_home, carried).q_end, carried)
    nominal = motions.move(reach.q_end, carried, reach)
    assert nominal.planned is not None and nominal.retimed is not None
    robust_grasp = motions.grasp_for(carried, nominal.planned.X_OC, robust=True)
    assert robust_grasp.is_robust and nominal.grasp is not None
    assert not nominal.grasp.is_robust
    robust = motions.retime_path(nominal.planned.path, robust_grasp)
    assert robust.duration > nominal.retimed.duration

    assert obj.uncertainty is not None
    true = hardest_corner(
        ObjectInertia.of_model(obj), obj.uncertainty, np.random.default_rng(0)
    )
    assert true.mass == pytest.approx(1.2 * 0.551)
    inertias = {obj.name: true.spatial_inertia()}
    world = rollout_scenario(trial, reach.q_end)
    # The nominal plan holds the nominal notebook (Table I) ...
    assert simulate_move(world, reach.q_end, nominal.trajectory).success
    # ... but not the true one, which the robust plan holds.
    assert not simulate_move(
        world, reach.q_end, nominal.trajectory, object_inertias=inertias
    ).success
    held = simulate_move(
        world, reach.q_end, robust.trajectory, object_inertias=inertias
    )
    assert held.success


def test_robust_experiment_writes_both_plans_per_trial(tmp_path):
    out = tmp_path / "robust"
    argv = ["experiment", "transport", "--scenario", str(UNCERTAIN), "--robust"]
    assert main([*argv, "--n", "1", "--out", str(out)]) == 0
    results = json.loads((out / "results.json").read_text())
    (t,) = results["trials"]
    assert set(t["true_object"]) == {"mass", "com", "inertia"}
    assert t["true_object"]["mass"] == pytest.approx(1.2 * 0.551)
    assert not t["success_nominal"] and t["success_robust"]
    assert t["duration_robust_s"] > t["duration_nominal_s"]
    assert 1.0 <= t["tightness"] <= 1.03
    assert results["summary"]["success_robust"] == 1
    assert results["cup_physics"] == "rim"  # the scenario's, named
    assert (out / "robustness.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    report = (out / "report.md").read_text()
    assert "| 0 | 0.661 |" in report and "Simulated cup: rim (cup_physics)" in report


def test_robust_experiment_needs_an_uncertainty_set(tmp_path, capsys):
    argv = ["experiment", "transport", "--robust", "--n", "1", "--out", str(tmp_path)]
    assert main(argv) == 2
    error = capsys.readouterr().err.strip()
    assert "\n" not in error and "no uncertainty set" in error


BELLOWS = scenarios_dir() / "random_transport_uncertain_bellows.yaml"
BELLOWS_5MM = scenarios_dir() / "random_transport_uncertain_bellows_5mm.yaml"


def rest_use_of_the_peel_set(path) -> float:
    """Closed form: the share of the lip's peel set the worst object uses at rest.

    Pointing down, the heaviest object with its centre of mass at a corner
    of its box (along a corner of the peel octagon) loads the lip with the
    moment ``m g d`` and pulls ``f_z = -m g``; the peel row ``|M_t| <= c r
    (P A + f_z)`` with the pull's side shrunk by the margin reads ``(|M_t|
    + c r m g) / (c r P A) <= 1 - margin``.
    """
    scenario = load_scenario(path)
    cup, (obj,) = scenario.cup, scenario.objects
    assert obj.uncertainty is not None and cup.peel_fraction is not None
    mass = ObjectInertia.of_model(obj).mass  # kg, the model's
    weight = 9.81 * (1.0 + obj.uncertainty.mass) * mass  # N, the heaviest
    d = float(np.hypot(*obj.uncertainty.com[:2]))  # m, off the cup's axis
    cr = cup.peel_fraction * cup.radius
    return (weight * d + cr * weight) / (cr * cup.suction_force)


def test_a_set_refused_at_rest_is_recorded_per_trial_and_the_run_goes_on(tmp_path):
    margin = load_scenario(BELLOWS).planning.grasp_margin
    assert rest_use_of_the_peel_set(BELLOWS) > 1.0 > 1.0 - margin
    # The narrowed set fits at rest with room for its (derived) margin.
    narrowed = load_scenario(BELLOWS_5MM).planning.grasp_margin
    assert narrowed > margin
    assert rest_use_of_the_peel_set(BELLOWS_5MM) < 1.0 - narrowed
    out = tmp_path / "refused"
    argv = ["experiment", "transport", "--robust", "--scenario", str(BELLOWS)]
    assert main([*argv, "--n", "2", "--out", str(out)]) == 0
    results = json.loads((out / "results.json").read_text())
    assert results["trials"] == []
    assert [t["index"] for t in results["not_retimed"]] == [0, 1]
    for t in results["not_retimed"]:
        assert t["not_retimed"].startswith("robust plan: object slips even at rest")
    assert results["summary"] == {"n": 0, "n_sampled": 2, "not_retimed": 2}
    report = (out / "report.md").read_text()
    assert "No trial was played." in report
    assert "path 1 not retimed, not played: robust plan" in report
    assert not (out / "robustness.png").exists()
