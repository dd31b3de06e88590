"""``time_at``: when a retimed motion passes a path parameter.

On a jerk-limited retime it reads the time at a grid point (the pick's
approach pose is a knot of its path) instead of bisecting; checked against
the bisection of :meth:`~rt_drake.retiming.JerkTimedPath.time_at` and
against the configuration sampled from the trajectory at that time.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from rt_drake.model.plant import home_configuration, make_arm_plant
from rt_drake.retiming import JerkTimedPath, JointLimits, retime
from rt_drake.simulation.online_motions import time_at
from rt_drake.types.path import GeometricPath


def test_time_at_a_knot_and_between_grid_points_under_jerk_limits(scenario):
    plant = make_arm_plant(scenario)
    limits = JointLimits.from_plant(plant, scenario.robot)
    limits = dataclasses.replace(limits, jerk=20.0 * limits.acceleration)
    q_home = home_configuration(plant, scenario)
    steps = np.array([[0.0] * 6, [0.4, 0.1, -0.1, 0, 0.1, 0], [0.9, 0.2, 0, 0, 0, 0.2]])
    path = GeometricPath.from_waypoints(q_home + steps)
    result = retime(plant, path, limits, None)
    assert isinstance(result.trajectory, JerkTimedPath)
    knot = float(path.knots[1])
    assert np.min(np.abs(result.gridpoints - knot)) == 0.0
    s_between = 0.5 * (result.gridpoints[3] + result.gridpoints[4])
    for s in (knot, s_between):
        t = time_at(result, s)
        assert t == pytest.approx(result.trajectory.time_at(s), abs=1e-9)
        np.testing.assert_allclose(
            result.trajectory.value(t).ravel(), path.value(s).ravel(), atol=1e-7
        )
