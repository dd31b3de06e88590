"""Robust retiming: every object of an uncertainty set held, checked independently.

Soundness is checked by another route than the retimer's (Drake's body
accelerations and Newton-Euler, :mod:`rt_drake.dynamics.newton_euler`), at 1 kHz,
for corners of the set and objects drawn from it; tightness against the
retime that holds a dense sample of the set (a lower bound of the robust
optimum). The paths are MOVE-like (lift, swing, set down; the cup near
vertical: with +-10 mm of CoM on a 12.5 mm cup, tilting much drops the
worst object even at rest).
"""

import dataclasses
import sys
from pathlib import Path

import numpy as np
import pytest

from rt_drake.contact import CupParameters, cached_wrench_polytope
from rt_drake.dynamics.cup_frame import CupFrame
from rt_drake.dynamics.newton_euler import (
    reference_object_wrench,
    reference_object_wrenches,
)
from rt_drake.retiming import (
    DEFAULT_TOLERANCE,
    GraspConstraint,
    GraspUnstableAtRestError,
    JointLimits,
    Margin,
    check_trajectory,
    retime,
)
from rt_drake.retiming._check import _sample
from rt_drake.retiming.stage_rows import (
    normalised_rows,
    wrench_ratios,
)
from rt_drake.types.object_uncertainty import ObjectUncertainty
from rt_drake.uncertainty.object_samples import (
    ObjectInertia,
    corners,
    random_objects,
)

sys.path.insert(0, str(Path(__file__).parents[2] / "benchmarks"))
from bench_retime import move_paths  # noqa: E402

SET = ObjectUncertainty(mass=0.2, com=[0.01, 0.01, 0.005], inertia=0.2)
#: Friction and suction known down to these.
UNCERTAIN_CUP = CupParameters(friction_min=0.25, suction_force_min=18.0)


@pytest.fixture(scope="module")
def paths():
    return move_paths(5)


@pytest.fixture(scope="module")
def limits(plant, scenario):
    return JointLimits.from_plant(plant, scenario.robot)


@pytest.fixture(scope="module")
def notebook(scenario):
    return dataclasses.replace(scenario.object("notebook"), uncertainty=SET)


@pytest.fixture(scope="module")
def samples(notebook):
    """Objects of the set, in the cup frame: its corners and 100 draws (bodies)."""
    model = ObjectInertia.of_model(notebook)
    X_OC = notebook.grasp.GetDeterministicValue()
    drawn = random_objects(model, SET, 100, np.random.default_rng(4))
    return [o.held(X_OC) for o in corners(model, SET) + drawn]


def _excess(plant, trajectory, objects, polytopes):
    """Worst ``max_k (F_k w - g_k) / g_k`` of every object over 1 kHz samples."""
    t0, t1 = trajectory.start_time(), trajectory.end_time()
    times = np.append(np.arange(t0, t1, 1e-3), t1)
    q, v, vdot = _sample(trajectory, times)
    wrenches = reference_object_wrenches(plant, objects, CupFrame.of(plant), q, v, vdot)
    flat = wrenches.reshape(-1, 6)
    return max(
        float(wrench_ratios(flat, normalised_rows(F, g), g, np.inf)[0].max()) - 1.0
        for F, g in polytopes
    )


def test_batched_reference_wrenches_equal_the_single_route(plant, samples, paths):
    result = retime(plant, paths[0], JointLimits.from_plant(plant))
    times = np.linspace(0.0, result.duration, 50)
    q, v, vdot = _sample(result.trajectory, times)
    cup = CupFrame.of(plant)
    batched = reference_object_wrenches(plant, samples[:3], cup, q, v, vdot)
    for held, wrenches in zip(samples[:3], batched, strict=True):
        single = reference_object_wrench(plant, held, cup, q, v, vdot)
        np.testing.assert_allclose(wrenches, single, atol=1e-12)


@pytest.mark.parametrize("index", [0, 4])
def test_robust_plan_holds_every_sampled_object(
    plant, limits, scenario, notebook, samples, paths, index
):
    robust = GraspConstraint.for_scenario_object(notebook, scenario.cup)
    assert robust.is_robust
    result = retime(plant, paths[index], limits, robust)
    polytope = cached_wrench_polytope(scenario.cup)
    excess = _excess(plant, result.trajectory, samples, [(polytope.F, polytope.g)])
    assert excess <= DEFAULT_TOLERANCE
    # The nominal plan does not: the set is much wider than its margin.
    nominal = retime(
        plant, paths[index], limits, GraspConstraint.for_cup(robust.held, scenario.cup)
    )
    assert nominal.duration < result.duration
    assert _excess(plant, nominal.trajectory, samples, [(polytope.F, polytope.g)]) > 0.1


def test_robust_plan_holds_with_the_worst_friction_and_either_suction(
    plant, limits, notebook, samples, paths
):
    robust = GraspConstraint.for_scenario_object(notebook, UNCERTAIN_CUP)
    assert robust.worst_cup and "suction down to 18 N" in robust.guarantee()
    result = retime(plant, paths[2], limits, robust)
    # The exact sets of the cups at both ends of the suction range, at the
    # lowest friction (computed apart from worst_cup_polytope's offsets).
    ends = [
        cached_wrench_polytope(
            dataclasses.replace(UNCERTAIN_CUP.worst_case(), suction_force=f)
        )
        for f in (18.0, 20.0)
    ]
    excess = _excess(plant, result.trajectory, samples, [(p.F, p.g) for p in ends])
    assert excess <= DEFAULT_TOLERANCE


def test_robust_duration_is_within_3_percent_of_a_dense_sample_lower_bound(
    plant, limits, scenario, notebook, samples, paths
):
    robust = GraspConstraint.for_scenario_object(notebook, scenario.cup)
    result = retime(plant, paths[1], limits, robust)
    stacked = GraspConstraint.for_objects(samples, scenario.cup)
    bound = retime(plant, paths[1], limits, stacked)
    assert bound.duration <= result.duration * (1 + 1e-9)
    assert result.duration <= 1.03 * bound.duration


def test_zero_width_set_gives_exactly_the_nominal_trajectory(
    plant, limits, scenario, notebook, paths
):
    known = dataclasses.replace(notebook, uncertainty=ObjectUncertainty())
    grasp = GraspConstraint.for_scenario_object(known, scenario.cup)
    also = GraspConstraint.robust(
        grasp.held,
        ObjectUncertainty(),
        scenario.cup,
        notebook.grasp.GetDeterministicValue().inverse().rotation().matrix(),
    )
    nominal = retime(
        plant, paths[3], limits, GraspConstraint.for_cup(grasp.held, scenario.cup)
    )
    for zero in (grasp, also):
        assert not zero.is_robust
        result = retime(plant, paths[3], limits, zero)
        assert result.duration == nominal.duration
        np.testing.assert_array_equal(result.gridpoints, nominal.gridpoints)
        np.testing.assert_array_equal(result.sd, nominal.sd)


def test_set_too_wide_to_hold_at_rest_names_the_worst_object(
    plant, limits, scenario, notebook, paths
):
    wide = dataclasses.replace(
        notebook, uncertainty=ObjectUncertainty(mass=0.5, com=[0.1, 0.06, 0.01])
    )
    grasp = GraspConstraint.for_scenario_object(wide, scenario.cup)
    with pytest.raises(GraspUnstableAtRestError) as error:
        retime(plant, paths[0], limits, grasp)
    message = str(error.value)
    assert "\n" not in message and "even at rest at s = " in message
    assert "worst object of the set (0.827 kg" in message
    assert "(-100.0, 60.0, 22.5) mm" in message or "100.0" in message
    assert error.value.s is not None


@pytest.mark.slow
def test_robust_torque_limits_hold_for_every_sampled_object(
    plant, scenario, notebook, samples, paths
):
    base = JointLimits.from_plant(plant, scenario.robot)
    limits = JointLimits(
        base.velocity, base.acceleration, np.array([6, 42, 27, 2.0, 1.5, 0.1])
    )
    robust = GraspConstraint.for_scenario_object(notebook, scenario.cup)
    result = retime(plant, paths[0], limits, robust)
    free = retime(plant, paths[0], base, robust)
    assert result.duration > free.duration  # the torques bind
    assert result.margins[Margin.TORQUE].min() >= -1e-6
    for held in samples[::32]:
        check = check_trajectory(
            plant,
            result.trajectory,
            limits,
            GraspConstraint.for_cup(held, scenario.cup),
        )
        assert check.margins[Margin.TORQUE].value >= -DEFAULT_TOLERANCE


def test_between_grid_points_a_set_is_held_by_cuts(
    plant, limits, scenario, notebook, samples, paths, monkeypatch
):
    """With a tiny tolerance between grid points, cuts hold the worst object."""
    from rt_drake.retiming import _solve as solve

    monkeypatch.setattr(solve, "BETWEEN_TOLERANCE", 1e-5)
    robust = GraspConstraint.for_scenario_object(notebook, scenario.cup)
    result = retime(plant, paths[2], limits, robust)
    assert result.cuts >= 1 and result.refinements == 0
    polytope = cached_wrench_polytope(scenario.cup)
    excess = _excess(plant, result.trajectory, samples, [(polytope.F, polytope.g)])
    assert excess <= DEFAULT_TOLERANCE
