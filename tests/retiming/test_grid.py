"""The retimer's initial grid: knots, pieces and the joint-space step bound."""

from __future__ import annotations

import numpy as np
import pytest
from pydrake.trajectories import CompositeTrajectory, PiecewisePolynomial

from rt_drake.retiming import JointLimits, RetimeInputError, retime
from rt_drake.retiming._joint_path import as_joint_path
from rt_drake.retiming.grid import (
    MAX_JOINT_STEP,
    MIN_PIECE_SEGMENTS,
    bound_steps,
    initial_grid,
)


def _steps(path, s: np.ndarray) -> np.ndarray:
    return np.linalg.norm(np.diff(path(s), axis=0), axis=1)


def test_steps_are_bounded_in_joint_space_on_a_long_coarse_path():
    """A 6-joint path of about 7 rad on 8 requested points: every step of the
    bounded grid is at most MAX_JOINT_STEP, measured on a 20x finer sampling
    of each segment (so a step's arc, not only its chord, is bounded up to
    the curvature inside a segment), and the grid keeps the knots."""
    waypoints = np.array(
        [[0, 0, 0, 0, 0, 0], [2, -1, 1, 0.5, 0, 1], [0.5, 0.5, -1, 2, 1, -1.0]]
    )
    path = as_joint_path(waypoints)
    s = bound_steps(initial_grid(8, path.breaks), path)
    assert np.all(np.isin(path.breaks, s))
    assert np.all(np.diff(s) > 0) and s[0] == 0.0 and s[-1] == 1.0
    fine = np.concatenate(
        [np.linspace(a, b, 21)[:-1] for a, b in zip(s[:-1], s[1:], strict=True)]
        + [[1.0]]
    )
    arcs = np.add.reduceat(_steps(path, fine), np.arange(0, fine.size - 1, 20))
    assert arcs.max() <= MAX_JOINT_STEP * 1.01, arcs.max()
    # At least the path's length over the bound, and not twice as many.
    length = _steps(path, np.linspace(0.0, 1.0, 5001)).sum()
    assert length / MAX_JOINT_STEP <= s.size <= 2.0 * length / MAX_JOINT_STEP


def test_a_fine_grid_on_a_short_path_is_unchanged():
    waypoints = np.array([[0.0] * 6, [0.3, -0.2, 0.1, 0.0, 0.2, 0.4]])
    path = as_joint_path(waypoints)
    s = initial_grid(100, path.breaks)
    assert _steps(path, s).max() < MAX_JOINT_STEP
    np.testing.assert_array_equal(bound_steps(s, path), s)
    assert len(s) - 1 >= MIN_PIECE_SEGMENTS


def test_a_path_too_long_for_the_grid_is_refused():
    """Joint 1 swung between -90 and +90 rad 40 times (7200 rad): steps of
    0.05 rad would need 144 000 points, beyond the grid's 100 000."""
    waypoints = np.zeros((41, 6))
    waypoints[:, 0] = 90.0 * (-1.0) ** np.arange(41)
    path = as_joint_path(waypoints)
    with pytest.raises(RetimeInputError, match=r"rad long in joint space"):
        bound_steps(initial_grid(100, path.breaks), path)


def test_a_path_that_jumps_is_refused_not_split_forever(plant):
    """Two cubic pieces 0.3 rad apart per joint at s = 0.5 (a Drake
    CompositeTrajectory): no number of grid points makes that step short, so
    the retimer names the jump instead of splitting it until it hangs."""
    first = PiecewisePolynomial.CubicShapePreserving(
        [0.0, 0.5], np.array([[0.0] * 6, [0.2] * 6]).T, True
    )
    second = PiecewisePolynomial.CubicShapePreserving(
        [0.5, 1.0], np.array([[0.5] * 6, [0.7] * 6]).T, True
    )
    path = CompositeTrajectory([first, second])
    limits = JointLimits(np.full(6, 2.0), np.full(6, 10.0))
    with pytest.raises(RetimeInputError, match=r"jumps by 0.735 rad at s = 0.5000"):
        retime(plant, path, limits)
