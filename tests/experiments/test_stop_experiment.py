"""rt-drake experiment stop: a MOVE stopped mid-way in physics, both ways."""

from __future__ import annotations

import numpy as np
import pytest

from rt_drake import load_scenario
from rt_drake.cli import main
from rt_drake.errors import InputError, ScenarioError
from rt_drake.experiments import (
    run_stop_experiment,
    run_transport_experiment,
    stop_trial,
)
from rt_drake.experiments._rollout import SLIP_ROTATION, SLIP_TRANSLATION
from rt_drake.model.resources import resolve_scenario_path
from rt_drake.planning import sample_transports

#: s, per planning call (the default, 1 s, runs out on a loaded machine).
PLANNING_BUDGET_S = 30.0


@pytest.mark.slow
def test_the_grasp_aware_stop_holds_in_physics_and_the_joint_brake_leaves_the_set():
    """Transport 0 of random_transport_paper, seed 0, stopped where the
    experiment stops it, under the scenario's jerk limits (the command's
    default): the grasp-aware stop keeps the grasp set at 1 kHz and the
    object on the cup in the simulated physics (slip under the transport
    experiment's thresholds); the jerk-limited joint brake, braking harder
    than the grasp allows, leaves the set, sooner. Both keep the jerk limits
    across the instant (finite differences of the 1 kHz accelerations)."""
    scenario = load_scenario(resolve_scenario_path("random_transport_paper"))
    ((X_start, X_goal),) = sample_transports(scenario, 1, 0)
    fraction = float(np.random.default_rng(0).uniform(size=1)[0])
    name = scenario.random_transport.object
    trial = stop_trial(
        scenario, name, 0, X_start, X_goal, 0, fraction, PLANNING_BUDGET_S,
        jerk_limits=True,
    )  # fmt: skip
    assert trial["jerk_limited"]
    assert trial["jerk_margin_grasp_stop"] >= -1e-3
    assert trial["jerk_margin_joint_stop"] >= -1e-3
    assert trial["stop_at_s"] == pytest.approx(fraction * trial["move_duration_s"])
    assert trial["s_stop"] > trial["s_at_stop"] and trial["sd_at_stop"] > 0.0
    assert trial["grasp_margin_grasp_stop"] >= -1e-3
    assert trial["success_grasp_stop"]
    slip = trial["slip_grasp_stop"]
    assert slip["max_translation_mm"] < 1e3 * SLIP_TRANSLATION
    assert slip["max_rotation_deg"] < np.degrees(SLIP_ROTATION)
    assert trial["grasp_margin_joint_stop"] < 0.0
    assert 0.0 < trial["joint_stop_time_s"] < trial["stop_time_s"]
    assert trial["joint_s_stop"] <= trial["s_stop"]


def test_bad_arguments_are_refused_in_one_line():
    path = resolve_scenario_path("random_transport_paper")
    with pytest.raises(InputError, match="number of trials must be >= 1, got 0"):
        run_stop_experiment(path, n=0)
    with pytest.raises(InputError, match="worker processes must be >= 1"):
        run_stop_experiment(path, n=1, workers=0)
    with pytest.raises(ScenarioError, match="no 'random_transport' section"):
        run_stop_experiment(resolve_scenario_path("stack_four_objects"), n=1)


@pytest.mark.parametrize("run", [run_stop_experiment, run_transport_experiment])
def test_a_count_that_is_not_an_integer_is_refused_by_every_experiment(run):
    path = resolve_scenario_path("random_transport_paper")
    with pytest.raises(
        InputError, match="number of trials must be an integer, got 2.5"
    ):
        run(path, n=2.5)
    with pytest.raises(
        InputError, match="worker processes must be an integer, got 1.0"
    ):
        run(path, n=1, workers=1.0)


@pytest.mark.parametrize(
    "argv,words",
    [
        (["--n", "0"], ["--n", "must be in [1, 1000], got 0"]),
        (["--seed", "-1"], ["--seed"]),
        (["--workers", "0"], ["--workers"]),
    ],
)
def test_the_command_refuses_bad_flags(capsys, tmp_path, argv, words):
    assert main(["experiment", "stop", *argv, "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and err.startswith("rt-drake experiment stop: error:")
    for word in words:
        assert word in err, err


def test_an_out_that_is_a_file_is_refused_before_any_work(capsys, tmp_path):
    out = tmp_path / "results"
    out.write_text("keep me")
    assert main(["experiment", "stop", "--n", "1", "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and str(out) in err and "not a directory" in err
    assert out.read_text() == "keep me"
