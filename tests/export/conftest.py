"""A retimed trajectory and its .npz file, shared by the export tests."""

from __future__ import annotations

import numpy as np
import pytest

from rt_drake import (
    CupParameters,
    HeldObject,
    JointLimits,
    retime,
    sample_trajectory,
    save_trajectory,
)

HOME = np.array([0.0, 0.35, 1.75, 0.0, 1.04, 0.0])
WAYPOINTS = np.array(
    [
        HOME,
        HOME + [-0.4, 0.1, -0.2, 0.0, 0.1, -0.5],
        HOME + [-1.2, -0.1, 0.2, 0, -0.1, -0.8],
    ]
)


@pytest.fixture(scope="module")
def retimed(scenario, plant):
    """A joint-limited retime of a three-waypoint path (about 0.6 s)."""
    limits = JointLimits.from_plant(plant, scenario.robot)
    return retime(plant, WAYPOINTS, limits)


@pytest.fixture(scope="module")
def saved(plant, retimed):
    """The retimed motion sampled every 1 ms by ``sample_trajectory``.

    The reference of the export tests: it samples the retimer's own
    trajectory, while an export rebuilds the motion from the file's path and
    profile, and samples on its own grid.
    """
    from rt_drake.types.path import path_waypoints_and_knots

    _, knots = path_waypoints_and_knots(WAYPOINTS)
    held = HeldObject(mass=1.0, p_CoScm_C=np.zeros(3), I_Scm_C=np.eye(3) * 1e-3)
    return sample_trajectory(
        plant, retimed, held, None, CupParameters(points=4), "box", WAYPOINTS, knots
    )


@pytest.fixture()
def npz(tmp_path, saved):
    """``saved`` written to a file."""
    return save_trajectory(tmp_path / "move.npz", saved)
