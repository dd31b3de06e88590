"""Warm starts of the MOVE optimiser: offsets in the transport frame, by Drake's FK."""

from __future__ import annotations

import numpy as np
import pytest

from rt_drake import CupFrame, GeometricPath
from rt_drake.shaping._family import PathFamily
from rt_drake.shaping._starts import (
    offset_parameters,
    start_parameters,
    transport_frame,
    warm_start_library,
)
from rt_drake.shaping.cup_chain import CupChain


@pytest.fixture(scope="module")
def family(scenario, plant):
    chain = CupChain(plant, CupFrame.of(plant))
    home = np.array(scenario.robot.home)
    place = home + np.array([1.2, 0.1, -0.1, 0.0, 0.1, 0.3])
    reference = np.array([home + [0.3, -0.1, 0, 0, 0, 0], place - [0.3, 0, 0, 0, 0, 0]])
    return PathFamily(chain, home, place, reference, 0.03, 2, np.full(6, 0.1))


def path_of(family: PathFamily) -> GeometricPath:
    return GeometricPath.from_waypoints(family.waypoints(np.zeros(family.dim))[0])


def cup_poses(plant, q):
    frame = CupFrame.of(plant).frame
    context = plant.CreateDefaultContext()
    out = []
    for qk in q:
        plant.SetPositions(context, qk)
        out.append(frame.CalcPoseInWorld(context))
    return out


def test_transport_frame_is_right_handed_with_z_up_and_x_towards_the_place(
    family, plant
):
    path = path_of(family)
    T = transport_frame(family.chain, path)
    np.testing.assert_allclose(T.T @ T, np.eye(3), atol=1e-12)
    assert np.linalg.det(T) == pytest.approx(1.0)
    np.testing.assert_allclose(T[:, 2], [0.0, 0.0, 1.0], atol=1e-12)
    start, goal = cup_poses(plant, path.waypoints[[0, -1]])
    d = goal.translation() - start.translation()
    d[2] = 0.0
    np.testing.assert_allclose(T[:, 0], d / np.linalg.norm(d), atol=1e-12)


def test_zero_offsets_are_the_reference(family):
    x = offset_parameters(family, path_of(family), np.zeros((1, 2, 6)))
    np.testing.assert_allclose(x, 0.0, atol=1e-8)


def test_an_offset_moves_the_via_points_cup_by_that_much(family, plant):
    path = path_of(family)
    T = transport_frame(family.chain, path)
    offsets = np.zeros((1, 2, 6))
    offsets[0, 0, :3] = [0.02, -0.01, 0.05]  # m, in T
    offsets[0, 1, 5] = 0.2  # rad about z_T (up)
    x = offset_parameters(family, path, offsets)
    via = family.via(x)[0]
    before = cup_poses(plant, family.reference)
    after = cup_poses(plant, via)
    np.testing.assert_allclose(
        after[0].translation() - before[0].translation(),
        T @ offsets[0, 0, :3],
        atol=1e-9,
    )
    turn = after[1].rotation().multiply(before[1].rotation().inverse())
    np.testing.assert_allclose(turn.ToAngleAxis().angle(), 0.2, atol=1e-9)
    np.testing.assert_allclose(turn.ToAngleAxis().axis(), [0, 0, 1], atol=1e-9)
    np.testing.assert_allclose(
        after[1].translation(), before[1].translation(), atol=1e-9
    )


def test_library_starts_are_at_most_the_count_asked(family):
    offsets, keys = warm_start_library()
    assert offsets.shape[1:] == (2, 6) and keys.shape == (len(offsets), 5)
    x = start_parameters(family, path_of(family), 5)
    assert x.shape[1] == family.dim and len(x) <= min(5, len(offsets))
    assert start_parameters(family, path_of(family), 0).shape == (0, family.dim)
