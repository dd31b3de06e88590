"""Jerk limits, the grasp of a set of objects and torque limits together.

References, each independent of the retimer's rows: the joint torques of
every object by Drake's inverse dynamics of a plant with the object as a
body welded at the cup frame (its mass, centre of mass and inertia set in
the context: no regressor, no object wrench), at 1 kHz; the grasp by
Newton-Euler (:mod:`rt_drake.dynamics.newton_euler`) at 1 kHz; the jerk by
third differences of the 1 kHz positions. The objects: every corner of
the uncertainty box that is a body, and objects drawn inside it.

The case: a short lift under torque limits tight on joints 2 and 3 (their
gravity load plus a little), so that the set's torques bind; a set mostly
in mass (+-30 %), whose torques differ most.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from torque_reference import TorqueReference

from rt_drake.contact import cached_wrench_polytope
from rt_drake.dynamics.cup_frame import CupFrame
from rt_drake.dynamics.newton_euler import reference_object_wrenches
from rt_drake.retiming import (
    DEFAULT_TOLERANCE,
    GraspConstraint,
    JerkTimedPath,
    JointLimits,
    Margin,
    check_trajectory,
    protective_stop,
    retime,
)
from rt_drake.retiming._check import _sample
from rt_drake.retiming.stage_rows import normalised_rows, wrench_ratios
from rt_drake.types.object_uncertainty import ObjectUncertainty
from rt_drake.types.path import GeometricPath
from rt_drake.uncertainty.object_samples import (
    ObjectInertia,
    corners,
    random_objects,
)

SET = ObjectUncertainty(mass=0.3, com=[0.002, 0.002, 0.001], inertia=0.1)
#: Torque limits of the test, as fractions of the plant's: joints 2 and 3
#: a little above their gravity load with the heaviest object.
TORQUE_SCALE = np.array([1.0, 0.33, 0.34, 1.0, 1.0, 1.0])
#: The lift (rad from home): joints 2, 3 and 5 keep the cup pointing down.
LIFT = np.array([0.2, -0.3, -0.3, 0.0, 0.55, 0.1])
GRIDPOINTS = 30
STEP = 1e-3


def _states(trajectory, start: float | None = None):
    """q, v, vdot at 1 kHz from ``start`` (default: the start) to the end."""
    t0 = trajectory.start_time() if start is None else start
    t1 = trajectory.end_time()
    times = np.append(np.arange(t0, t1, STEP), t1)
    return _sample(trajectory, times)


def _torque_ratio(reference, objects, trajectory, limit, start=None) -> np.ndarray:
    """(K,) each object's largest ``|tau_j| / tau_max_j`` at 1 kHz."""
    tau = reference.torques(objects, *_states(trajectory, start))
    return np.max(np.abs(tau) / limit, axis=(1, 2))


def _grasp_excess(plant, trajectory, objects, cup, start=None) -> float:
    """Largest ``(F_k w - g_k) / g_k`` over the objects at 1 kHz."""
    wrenches = reference_object_wrenches(
        plant, objects, CupFrame.of(plant), *_states(trajectory, start)
    )
    polytope = cached_wrench_polytope(cup)
    rows = normalised_rows(polytope.F, polytope.g)
    ratio = wrench_ratios(wrenches.reshape(-1, 6), rows, polytope.g, np.inf)[0]
    return float(ratio.max()) - 1.0


def _jerk_ratio(trajectory, jerk: np.ndarray, start: float | None = None) -> float:
    """Largest ``|q'''_j| / J_j`` from third differences of 1 kHz positions."""
    t0 = trajectory.start_time() if start is None else start
    t = t0 + STEP * np.arange(int((trajectory.end_time() - t0) / STEP) + 1)
    q = _sample(trajectory, t)[0]
    return float(np.max(np.abs(np.diff(q, 3, axis=0)) / STEP**3 / jerk))


@pytest.fixture(scope="module")
def case(plant, scenario):
    notebook = dataclasses.replace(scenario.object("notebook"), uncertainty=SET)
    plain = JointLimits.from_plant(plant, scenario.robot, torque=True)
    assert plain.torque is not None
    limits = dataclasses.replace(
        plain, jerk=20.0 * plain.acceleration, torque=TORQUE_SCALE * plain.torque
    )
    robust = GraspConstraint.for_scenario_object(notebook, scenario.cup)
    assert robust.is_robust
    home = np.asarray(scenario.robot.home, dtype=float)
    path = GeometricPath.from_waypoints(np.array([home, home + LIFT]))
    model = ObjectInertia.of_model(notebook)
    X_OC = notebook.grasp.GetDeterministicValue()
    drawn = random_objects(model, SET, 4, np.random.default_rng(7))
    objects = [o.held(X_OC) for o in corners(model, SET) + drawn]
    result = retime(plant, path, limits, robust, GRIDPOINTS)
    reference = TorqueReference(scenario)
    return limits, robust, path, objects, result, reference


def test_the_retime_holds_every_objects_torques_grasp_and_jerk(plant, scenario, case):
    limits, _, _, objects, result, reference = case
    trajectory = result.trajectory
    assert isinstance(trajectory, JerkTimedPath)
    # Every object's torques by Drake's inverse dynamics; the set's bind.
    ratio = _torque_ratio(reference, objects, trajectory, limits.torque)
    assert ratio.max() <= 1.0 + DEFAULT_TOLERANCE
    assert ratio.max() > 0.99
    assert abs(float(result.margins[Margin.TORQUE].min())) < 1e-6
    # Every object held (Newton-Euler), the jerk and the other joint limits.
    excess = _grasp_excess(plant, trajectory, objects, scenario.cup)
    assert excess <= DEFAULT_TOLERANCE
    assert _jerk_ratio(trajectory, limits.jerk) <= 1.0 + DEFAULT_TOLERANCE
    joints = dataclasses.replace(limits, torque=None)
    assert check_trajectory(plant, trajectory, joints).passed()


def test_the_nominal_objects_retime_is_faster_and_overloads_a_corner(
    plant, scenario, case
):
    limits, robust, path, objects, result, reference = case
    nominal = GraspConstraint.for_cup(robust.held, scenario.cup)
    own = retime(plant, path, limits, nominal, GRIDPOINTS)
    assert own.duration < result.duration
    # Some heavy corner overloads a joint (the heavy half is enough to show it).
    heavy = [o for o in objects if o.mass > 1.25 * robust.held.mass]
    assert heavy
    ratio = _torque_ratio(reference, heavy, own.trajectory, limits.torque)
    assert ratio.max() > 1.0 + 5.0 * DEFAULT_TOLERANCE
    # Without torque limits the set's retime is faster still: torques bind.
    free = retime(
        plant, path, dataclasses.replace(limits, torque=None), robust, GRIDPOINTS
    )
    assert free.duration < result.duration


def test_the_stop_ends_at_rest_within_every_limit_for_every_object(
    plant, scenario, case
):
    limits, robust, path, objects, result, reference = case
    t = 0.5 * result.duration
    stop = protective_stop(plant, path, limits, result, t, robust)
    assert stop.grasp_aware and stop.duration > 0.0
    trajectory = stop.trajectory
    end = trajectory.end_time()
    np.testing.assert_allclose(
        trajectory.EvalDerivative(end, 1).ravel(), 0.0, atol=1e-9
    )
    ratio = _torque_ratio(reference, objects, trajectory, limits.torque, t)
    assert ratio.max() <= 1.0 + DEFAULT_TOLERANCE
    excess = _grasp_excess(plant, trajectory, objects, scenario.cup, t)
    assert excess <= DEFAULT_TOLERANCE
    assert _jerk_ratio(trajectory, limits.jerk, t - 3 * STEP) <= 1.0 + DEFAULT_TOLERANCE
