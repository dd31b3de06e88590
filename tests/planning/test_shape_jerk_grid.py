"""The jerk-limited retime's refined grid (:func:`rt_drake.shaping.jerk_grid`).

Reference: ``x = s'^2`` interpolated linearly between the profile's points
by ``numpy.interp`` at the refined grid, and its log ratios over each new
segment computed directly.
"""

from __future__ import annotations

import numpy as np
import pytest

from rt_drake.shaping import jerk_grid
from rt_drake.shaping._jerk_grid import MAX_PARTS

STEP = 0.1


def _profile() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A rest-to-rest profile on 41 points, with halving points at both ends."""
    base = np.linspace(0.0, 1.0, 41)
    halves = base[1] * 0.5 ** np.arange(1, 7)
    s = np.union1d(base, np.concatenate([halves, 1.0 - halves]))
    sd = np.sin(np.pi * s) ** 0.75 * (1.0 + 0.4 * np.cos(9.0 * s))
    sd[[0, -1]] = 0.0  # at rest
    return s, sd, base


def test_each_new_segment_moves_ln_x_by_at_most_the_step():
    s, sd, base = _profile()
    grid = jerk_grid(s, sd, base, STEP, end_halvings=0)
    inner = (grid >= base[1]) & (grid <= base[-2])
    x = np.interp(grid[inner], s, sd**2)
    change = np.abs(np.diff(np.log(x)))
    segments = np.abs(np.diff(np.log(np.interp(base[1:-1], s, sd**2))))
    assert segments.max() / STEP < MAX_PARTS  # no segment capped here
    assert change.max() <= STEP * (1.0 + 1e-9)
    assert segments.max() > 4 * STEP  # the profile does need splitting
    # Every point of the profile's grid inside the end segments is kept.
    kept = s[(s >= base[1]) & (s <= base[-2])]
    assert np.isin(kept, grid).all()


def test_the_ends_are_halved_and_the_retimers_own_points_dropped():
    s, sd, base = _profile()
    grid = jerk_grid(s, sd, base, STEP, end_halvings=3)
    assert np.all(np.diff(grid) > 0.0) and grid[0] == 0.0 and grid[-1] == 1.0
    head = grid[(grid > 0.0) & (grid < base[1])]
    tail = grid[(grid > base[-2]) & (grid < 1.0)]
    assert np.allclose(head, base[1] * np.array([1 / 8, 1 / 4, 1 / 2]))
    assert np.allclose(1.0 - tail, (1.0 - base[-2]) * np.array([1 / 2, 1 / 4, 1 / 8]))


def test_a_profile_not_at_rest_keeps_its_end_segments_whole():
    s, sd, base = _profile()
    sd = sd + 0.5  # moving at both ends
    grid = jerk_grid(s, sd, base, STEP, end_halvings=3)
    assert not ((grid > 0.0) & (grid < base[1])).any()
    assert not ((grid > base[-2]) & (grid < 1.0)).any()


@pytest.mark.parametrize(
    ("step", "sd", "match"),
    [(0.0, None, "step"), (STEP, np.ones(3), "sd")],
)
def test_bad_input_is_named(step, sd, match):
    s, profile_sd, base = _profile()
    with pytest.raises(ValueError, match=match):
        jerk_grid(s, profile_sd if sd is None else sd, base, step)
