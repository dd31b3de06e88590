"""``retime(..., jerk_start=...)``: the jerk LPs started from an earlier profile.

References: a converged profile is a fixed point of its own LPs (started
from it on the same grid, they return it, to the LPs' convergence test);
the limits by :func:`check_trajectory` at 1 kHz and the jerk from third
differences of the positions sampled at 1 kHz.
"""

from __future__ import annotations

import numpy as np
import pytest

from rt_drake.model.held import held_object_of
from rt_drake.retiming import (
    GraspConstraint,
    JointLimits,
    RetimeInputError,
    check_trajectory,
    retime,
)

HOME = np.array([0.0, 0.35, 1.75, 0.0, 1.04, 0.0])
GRID = np.linspace(0.0, 1.0, 61)


@pytest.fixture(scope="module")
def limits(plant, scenario):
    plain = JointLimits.from_plant(plant, scenario.robot)
    jerk = 20.0 * plain.acceleration
    return JointLimits(plain.velocity, plain.acceleration, jerk=jerk)


@pytest.fixture(scope="module")
def grasped_path(scenario):
    grasp = GraspConstraint.for_cup(
        held_object_of(scenario.object("carton_box")), scenario.cup
    )
    rng = np.random.default_rng(3)
    return np.cumsum(np.vstack([HOME, rng.uniform(-0.4, 0.4, (3, 6))]), axis=0), grasp


@pytest.fixture(scope="module")
def cold(plant, limits, grasped_path):
    path, grasp = grasped_path
    return retime(plant, path, limits, grasp, GRID)


def _third_difference_jerk(trajectory) -> np.ndarray:
    step = 1e-3
    count = int(trajectory.end_time() / step) + 1
    t = trajectory.start_time() + step * np.arange(count)
    q = np.array([trajectory.value(ti).ravel() for ti in t])
    return np.abs(np.diff(q, 3, axis=0)) / step**3


def test_a_converged_profile_is_a_fixed_point_of_its_lps(
    plant, limits, grasped_path, cold
):
    path, grasp = grasped_path
    warm = retime(plant, path, limits, grasp, GRID, jerk_start=cold)
    assert warm.duration == pytest.approx(cold.duration, rel=2e-3)
    assert warm.jerk_lps <= cold.jerk_lps


def test_a_warm_start_on_a_finer_grid_keeps_every_limit(
    plant, limits, grasped_path, cold
):
    path, grasp = grasped_path
    finer = np.union1d(GRID, 0.5 * (GRID[1:] + GRID[:-1]))
    warm = retime(plant, path, limits, grasp, finer, jerk_start=cold)
    assert (_third_difference_jerk(warm.trajectory) / limits.jerk).max() <= 1.0 + 1e-3
    check = check_trajectory(plant, warm.trajectory, limits, grasp)
    assert check.passed(), check.summary()


@pytest.mark.parametrize("start", ["no jerk limits", "not a result"])
def test_a_bad_start_is_named(plant, limits, grasped_path, cold, start):
    path, grasp = grasped_path
    if start == "no jerk limits":
        with pytest.raises(RetimeInputError, match="jerk_start.*limits.jerk"):
            retime(plant, path, limits.without_jerk(), grasp, GRID, jerk_start=cold)
    else:
        with pytest.raises(RetimeInputError, match="jerk_start must be a RetimeResult"):
            retime(plant, path, limits, grasp, GRID, jerk_start="profile.npz")
