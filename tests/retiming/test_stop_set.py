"""rt_drake.retiming: a protective stop that holds every object of a set.

Reference independent of the stop and of the set's rows: each object's own
grasp checked apart, at 1 kHz, with Drake's Newton-Euler wrench
(``check_trajectory`` with that object's ``GraspConstraint``); under jerk
limits, the joint jerk from finite differences of the 1 kHz samples.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from grasp_paths import BACK

from rt_drake.model.held import held_object_of
from rt_drake.retiming import (
    GraspConstraint,
    JointLimits,
    Margin,
    check_trajectory,
    protective_stop,
    retime,
)


@pytest.fixture(scope="module")
def objects(scenario):
    """The notebook, one 30 % heavier, one with its CoM 2 cm off along x."""
    nominal = held_object_of(scenario.object("notebook"))
    heavy = dataclasses.replace(nominal, mass=1.3 * nominal.mass)
    shifted = dataclasses.replace(
        nominal, p_CoScm_C=nominal.p_CoScm_C + [0.02, 0.0, 0.0]
    )
    return [nominal, heavy, shifted]


def test_a_stop_under_a_set_holds_every_object(plant, scenario, objects):
    limits = JointLimits.from_plant(plant, scenario.robot)
    assert limits.jerk is None  # the test scenario: acceleration-limited
    grasp = GraspConstraint.for_objects(objects, scenario.cup)
    assert grasp.is_robust
    move = retime(plant, BACK, limits, grasp)
    t = 0.45 * move.duration
    stop = protective_stop(plant, BACK, limits, move, t, grasp)
    assert stop.s_start < stop.s_stop and stop.duration > 0.0
    for held in objects:  # each object apart, its own grasp
        alone = GraspConstraint.for_cup(held, scenario.cup)
        check = check_trajectory(plant, stop.trajectory, limits, alone)
        assert check.passed(), check.summary()
    # The nominal object's own stop brakes harder than the heavy one holds.
    nominal = GraspConstraint.for_cup(objects[0], scenario.cup)
    own = protective_stop(plant, BACK, limits, move, t, nominal)
    heavy = GraspConstraint.for_cup(objects[1], scenario.cup)
    thrown = check_trajectory(plant, own.stop, limits, heavy)
    assert thrown.margins[Margin.GRASP].value < -1e-3
    assert own.duration <= stop.duration


def test_a_jerk_limited_stop_under_a_set_holds_every_object(plant, scenario, objects):
    """Every object's own grasp at 1 kHz, and the joint jerk from finite
    differences of the 1 kHz accelerations, over the MOVE and its stop."""
    plain = JointLimits.from_plant(plant, scenario.robot)
    limits = dataclasses.replace(plain, jerk=20.0 * plain.acceleration, torque=None)
    grasp = GraspConstraint.for_objects(objects, scenario.cup)
    move = retime(plant, BACK, limits, grasp)
    t = 0.45 * move.duration
    stop = protective_stop(plant, BACK, limits, move, t, grasp)
    assert stop.s_start < stop.s_stop < 1.0 and stop.duration > 0.0
    for order in (0, 1, 2):  # from the MOVE's own state at t
        np.testing.assert_allclose(
            stop.stop.EvalDerivative(t, order),
            move.trajectory.EvalDerivative(t, order),
            atol=1e-7,
        )
    for held in objects:  # each object apart, its own grasp
        alone = GraspConstraint.for_cup(held, scenario.cup)
        check = check_trajectory(plant, stop.trajectory, limits, alone)
        assert check.passed(), check.summary()
    times = np.append(np.arange(t - 0.05, stop.end_time, 1e-3), stop.end_time)
    vdot = stop.trajectory.sample(times, order=2)[2]
    jerk = np.diff(vdot, axis=0) / np.diff(times)[:, None]
    assert np.max(np.abs(jerk) / limits.jerk) <= 1.0 + 1e-3
    # The nominal object's own jerk-limited stop throws the heavy one.
    nominal = GraspConstraint.for_cup(objects[0], scenario.cup)
    own = protective_stop(plant, BACK, limits, move, t, nominal)
    heavy = GraspConstraint.for_cup(objects[1], scenario.cup)
    thrown = check_trajectory(plant, own.stop, limits, heavy)
    assert thrown.margins[Margin.GRASP].value < -1e-3
