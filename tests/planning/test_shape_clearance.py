"""The search's clearance estimate (rt_drake.shaping._clearance) against brute force.

A cup body of three spheres is swept along a curved motion (translation
and a turn about a fixed axis) past three boxes. The reference is the
sphere-box signed distance in closed form, ``|max(|p_B| - h, 0)| +
min(max_k (|p_B|_k - h_k), 0) - r``, written here in numpy, at 40 poses
between consecutive samples of the motion:

- :meth:`ClearanceModel.swept` bounds it from below on every segment;
- with ``floor``, every bound below the floor is the same bit for bit as
  without it, and every other bound stays above the floor (so the search's
  penalties, which read only the bounds below its threshold, do not change).
"""

from __future__ import annotations

import numpy as np
import pytest

from rt_drake.shaping._clearance import ClearanceModel

SPHERES = [
    (np.array([0.0, 0.0, 0.0]), 0.03),
    (np.array([0.0, 0.0, -0.08]), 0.05),
    (np.array([0.04, 0.0, -0.12]), 0.02),
]
CUTOFF = 0.07
SAMPLES = 64
BETWEEN = 40


def rotation(axis: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """Rotation matrices (..., 3, 3) about a unit axis by angles (...) (rad)."""
    K = np.array(
        [[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]]
    )
    a = np.asarray(angle)[..., None, None]
    return np.eye(3) + np.sin(a) * K + (1 - np.cos(a)) * K @ K


def boxes() -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    tilted = rotation(np.array([0.0, 0.0, 1.0]), np.array(0.4))
    return [
        (np.eye(3), np.array([0.3, 0.12, 0.0]), np.array([0.05, 0.01, 0.2])),
        (tilted, np.array([0.55, -0.1, -0.1]), np.array([0.1, 0.02, 0.15])),
        (np.eye(3), np.array([0.4, 0.0, -0.35]), np.array([0.5, 0.5, 0.05])),
    ]


def motion(t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Cup poses (R_WC (T, 3, 3), p_WC (T, 3)) at times t in [0, 1]."""
    axis = np.array([1.0, 2.0, 2.0]) / 3.0
    p = np.column_stack([0.8 * t, 0.1 * np.sin(3 * t), -0.1 * t**2])
    return rotation(axis, 1.5 * t), p


def brute_force(R_WC: np.ndarray, p_WC: np.ndarray) -> np.ndarray:
    """The sphere-box clearance (m) at each pose, closed form."""
    centres = np.einsum("tij,kj->tki", R_WC, np.array([c for c, _ in SPHERES]))
    centres += p_WC[:, None, :]
    radii = np.array([r for _, r in SPHERES])
    best = np.full(len(p_WC), np.inf)
    for R_WB, p_WB, half in boxes():
        local = np.abs((centres - p_WB) @ R_WB) - half
        outside = np.linalg.norm(np.maximum(local, 0.0), axis=-1)
        inside = np.minimum(local.max(axis=-1), 0.0)
        best = np.minimum(best, (outside + inside - radii).min(axis=-1))
    return best


@pytest.fixture(scope="module")
def model() -> ClearanceModel:
    return ClearanceModel.of_shapes(None, SPHERES, boxes())


def test_swept_bounds_the_clearance_between_samples(model):
    t = np.linspace(0.0, 1.0, SAMPLES)
    bound = model.swept(*motion(t), CUTOFF)
    dense = np.linspace(t[:-1], t[1:], BETWEEN).T  # (segments, BETWEEN)
    truth = brute_force(*motion(dense.ravel())).reshape(dense.shape).min(axis=1)
    assert truth.min() < 0.0 < CUTOFF < truth.max()  # touches, and is far
    assert np.all(bound <= np.minimum(truth, CUTOFF) + 1e-6)
    # and is not vacuous: within the motion's half step of the truth
    assert np.all(bound >= np.minimum(truth, CUTOFF) - 0.05)


@pytest.mark.parametrize("floor", [-0.01, 0.0, 0.01, 0.03])
def test_floor_keeps_every_bound_below_it(model, floor):
    R_WC, p_WC = motion(np.linspace(0.0, 1.0, SAMPLES))
    plain = model.swept(R_WC, p_WC, CUTOFF)
    capped = model.swept(R_WC, p_WC, CUTOFF, floor=floor)
    below = plain < floor
    assert below.any() and not below.all()
    assert np.array_equal(capped[below], plain[below])
    assert np.all(capped[~below] > floor)
