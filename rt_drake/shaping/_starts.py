"""Warm starts of the search: via-point offsets that worked on other transports.

A long search (1500 paths) on each transport of a learning set found via
points that shorten its MOVE; :func:`warm_start_library` keeps them as offsets
of the cup pose from the spline path's corners (:func:`~._family.corners`), in
the transport's frame T (unit vectors in W):

- ``x_T``: horizontal, from the cup at the grasp towards the cup at the place;
- ``z_T``: up (against gravity); ``y_T = z_T x x_T``.

Entry k of a start holds, for via point k, ``(dp_T (m, 3), w_T (rad, 3))``:
the via point's cup pose is the corner's, ``p' = p + T dp_T`` and ``R' =
exp([T w_T]x) R`` (both in W), and its configuration is found by Newton's
method from the corner's (:meth:`~.kinematics.CupChain.solve_pose`). A
start is kept when Newton converges.

Each start carries the features of the transport it was learned on
(:func:`features`); :func:`start_parameters` picks the ``count`` nearest to
the new transport's. The search evaluates them with ``x = 0`` in its first
batch and starts CMA-ES at the best.

Learned with ``tools/learn_starts.py`` on seed 3 of the shipped
random_transport and random_transport_paper scenarios (never on the seeds
the benchmarks report); see BENCHMARKS.md.
"""

from __future__ import annotations

import functools
from importlib import resources

import numpy as np

from rt_drake.shaping._family import PathFamily
from rt_drake.shaping.cup_chain import CupChain
from rt_drake.types.path import GeometricPath

#: Scales of the features (m, m, m, m, rad): differences of this size count 1.
FEATURE_SCALE = np.array([0.1, 0.1, 0.1, 0.1, 0.5])
#: The warm starts, package data beside this module.
LIBRARY_FILE = "data/warm_starts.npz"
#: rad + m: largest pose error of a start's via points after Newton's method.
POSE_TOLERANCE = 1e-6


def transport_frame(chain: CupChain, path: GeometricPath) -> np.ndarray:
    """T (3, 3), columns x_T, y_T, z_T in W (module docstring)."""
    _, p = chain.cup_pose(np.asarray(path.waypoints)[[0, -1]])
    up = -chain.gravity_W / np.linalg.norm(chain.gravity_W)
    x = (p[1] - p[0]) - ((p[1] - p[0]) @ up) * up
    if np.linalg.norm(x) < 1e-6:  # a vertical move: any horizontal direction
        x = np.cross(up, [0.0, 1.0, 0.0] if abs(up[1]) < 0.9 else [1.0, 0.0, 0.0])
    x /= np.linalg.norm(x)
    return np.column_stack([x, np.cross(up, x), up])


def features(chain: CupChain, path: GeometricPath, corners: np.ndarray) -> np.ndarray:
    """What a transport looks like (5,): the keys of the library.

    ``(d_xy, dz, h_1, h_K, |dyaw|)``: horizontal and vertical displacement of
    the cup from grasp to place (m), the heights of the first corner above
    the grasp and of the last above the place (m), and the cup's turn about
    the vertical (rad, in [0, pi]).
    """
    ends = np.asarray(path.waypoints)[[0, -1]]
    R, p = chain.cup_pose(np.vstack([ends, corners[[0, -1]]]))
    up = -chain.gravity_W / np.linalg.norm(chain.gravity_W)
    d = p[1] - p[0]
    height = d @ up
    turn = R[0].T @ R[1]
    yaw = abs(np.arctan2(turn[1, 0] - turn[0, 1], turn[0, 0] + turn[1, 1]))
    return np.array(
        [
            np.linalg.norm(d - height * up),
            height,
            (p[2] - p[0]) @ up,
            (p[3] - p[1]) @ up,
            yaw,
        ]
    )


def _exp(w: np.ndarray) -> np.ndarray:
    """Rotation matrices (..., 3, 3) of rotation vectors w (..., 3) (rad)."""
    angle = np.linalg.norm(w, axis=-1)[..., None, None]
    K = np.zeros((*w.shape[:-1], 3, 3))
    K[..., 0, 1], K[..., 0, 2] = -w[..., 2], w[..., 1]
    K[..., 1, 0], K[..., 1, 2] = w[..., 2], -w[..., 0]
    K[..., 2, 0], K[..., 2, 1] = -w[..., 1], w[..., 0]
    safe = np.where(angle > 1e-12, angle, 1.0)
    sin = np.where(angle > 1e-12, np.sin(safe) / safe, 1.0)
    cos = np.where(angle > 1e-12, (1.0 - np.cos(safe)) / safe**2, 0.5)
    return np.eye(3) + sin * K + cos * K @ K


def offset_parameters(
    family: PathFamily, path: GeometricPath, offsets: np.ndarray
) -> np.ndarray:
    """Parameters x (S', K n) of the via points at cup-pose ``offsets`` (S, K, 6).

    Offsets ``(dp_T, w_T)`` from the family's reference via points in the
    transport frame of ``path`` (module docstring); the starts whose Newton
    solve does not converge are left out.
    """
    chain = family.chain
    reference = family.reference
    T = transport_frame(chain, path)
    R0, p0 = chain.cup_pose(reference)
    p1 = p0 + offsets[..., :3] @ T.T
    R1 = _exp(offsets[..., 3:] @ T.T) @ R0
    v, error = chain.solve_pose(R1, p1, reference, iterations=10)
    ok = np.all(error < POSE_TOLERANCE, axis=1)
    x = (v[ok] - reference) / family.scale
    return x.reshape(len(x), family.dim)


@functools.cache
def warm_start_library() -> tuple[np.ndarray, np.ndarray]:
    """The learned warm starts: ``(offsets (S, K, 6), features (S, 5))``, read-only.

    Per start, the via points' cup-pose offsets ``(dp_T (m), w_T (rad))`` from
    the spline path's corners in the transport frame, and the features of the
    transport it was learned on (:func:`features`). Package data
    ``rt_drake/shaping/data/warm_starts.npz``, written by
    ``tools/learn_starts.py``.
    """
    source = resources.files("rt_drake.shaping").joinpath(LIBRARY_FILE)
    with resources.as_file(source) as path, np.load(path) as data:
        offsets = np.array(data["offsets"], dtype=float)
        keys = np.array(data["features"], dtype=float)
    for array in (offsets, keys):
        array.setflags(write=False)
    return offsets, keys


def start_parameters(family: PathFamily, path: GeometricPath, count: int) -> np.ndarray:
    """Parameters x (S, K n) of the ``count`` library starts nearest this transport.

    Empty if the family's via points are not the library's (K = 2).
    """
    offsets, keys = warm_start_library()
    reference = family.reference
    if count <= 0 or not len(offsets) or reference.shape[0] != offsets.shape[1]:
        return np.zeros((0, family.dim))
    distance = np.linalg.norm(
        (keys - features(family.chain, path, reference)) / FEATURE_SCALE, axis=1
    )
    return offset_parameters(family, path, offsets[np.argsort(distance)[:count]])


__all__ = [
    "FEATURE_SCALE",
    "features",
    "offset_parameters",
    "start_parameters",
    "transport_frame",
]
