"""Jerk limits with the grasp of a set of objects: every object held at 1 kHz.

References: each object of the set (its corners and objects drawn from it)
checked by another route than the retimer's, Drake's body accelerations and
Newton-Euler (:mod:`rt_drake.dynamics.newton_euler`), at 1 kHz; the jerk
from third differences of positions sampled at 1 kHz; every joint limit by
:func:`check_trajectory`.
"""

import dataclasses
import sys
from pathlib import Path

import numpy as np
import pytest

from rt_drake.contact import cached_wrench_polytope
from rt_drake.dynamics.cup_frame import CupFrame
from rt_drake.dynamics.newton_euler import reference_object_wrenches
from rt_drake.retiming import (
    DEFAULT_TOLERANCE,
    GraspConstraint,
    JerkTimedPath,
    JointLimits,
    check_trajectory,
    retime,
)
from rt_drake.retiming._check import _sample
from rt_drake.retiming.stage_rows import normalised_rows, wrench_ratios
from rt_drake.types.object_uncertainty import ObjectUncertainty
from rt_drake.uncertainty.object_samples import (
    ObjectInertia,
    corners,
    random_objects,
)

sys.path.insert(0, str(Path(__file__).parents[2] / "benchmarks"))
from bench_retime import move_paths  # noqa: E402

SET = ObjectUncertainty(mass=0.2, com=[0.01, 0.01, 0.005], inertia=0.2)
#: Jerk limits of the test: the acceleration limits reached in 50 ms.
PER_SECOND = 20.0


@pytest.fixture(scope="module")
def setup(plant, scenario):
    notebook = dataclasses.replace(scenario.object("notebook"), uncertainty=SET)
    plain = JointLimits.from_plant(plant, scenario.robot)
    limits = JointLimits(
        plain.velocity, plain.acceleration, jerk=PER_SECOND * plain.acceleration
    )
    robust = GraspConstraint.for_scenario_object(notebook, scenario.cup)
    assert robust.is_robust
    model = ObjectInertia.of_model(notebook)
    X_OC = notebook.grasp.GetDeterministicValue()
    drawn = random_objects(model, SET, 20, np.random.default_rng(5))
    objects = [o.held(X_OC) for o in corners(model, SET) + drawn]
    return limits, robust, objects


def _worst_excess(plant, trajectory, objects, cup) -> float:
    """Largest ``(F_k w - g_k) / g_k`` over the objects and 1 kHz samples."""
    t0, t1 = trajectory.start_time(), trajectory.end_time()
    times = np.append(np.arange(t0, t1, 1e-3), t1)
    q, v, vdot = _sample(trajectory, times)
    wrenches = reference_object_wrenches(plant, objects, CupFrame.of(plant), q, v, vdot)
    polytope = cached_wrench_polytope(cup)
    rows = normalised_rows(polytope.F, polytope.g)
    ratio = wrench_ratios(wrenches.reshape(-1, 6), rows, polytope.g, np.inf)[0]
    return float(ratio.max()) - 1.0


def test_a_jerk_limited_robust_plan_holds_every_object_and_the_jerk(
    plant, scenario, setup
):
    limits, robust, objects = setup
    path = move_paths(1)[0]
    result = retime(plant, path, limits, robust)
    trajectory = result.trajectory
    assert isinstance(trajectory, JerkTimedPath)
    assert result.grasp_rows > 0  # the set's rows entered the LPs
    # Every object of the set held, by Newton-Euler at 1 kHz; the grasp binds.
    excess = _worst_excess(plant, trajectory, objects, scenario.cup)
    assert -0.05 < excess <= DEFAULT_TOLERANCE
    # The jerk from third differences of 1 kHz positions, and every joint limit.
    step = 1e-3
    t = step * np.arange(int(trajectory.end_time() / step) + 1)
    q = trajectory.sample(t, order=0)[0]
    jerk = np.abs(np.diff(q, 3, axis=0)) / step**3 / limits.jerk
    assert jerk.max() <= 1.0 + 1e-3
    assert check_trajectory(plant, trajectory, limits).passed()
    # The nominal object's jerk-limited plan is faster and drops some objects.
    nominal = retime(
        plant, path, limits, GraspConstraint.for_cup(robust.held, scenario.cup)
    )
    assert nominal.duration < result.duration
    assert _worst_excess(plant, nominal.trajectory, objects, scenario.cup) > 0.05
