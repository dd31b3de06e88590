"""Where the rows of a set of objects are evaluated, on one grid.

For a set of objects (:mod:`._robust_grasp`) the wrench coefficients of its P
parameter columns are known at the grid points (``samples.wrench_set``,
each (G, P, D)). :class:`Tables` extends them to the K sub-points of every
segment (interpolated within the path's cubic pieces,
:meth:`._between.Segments.interpolate`), once per grid: row ``G + K i + k``
is sub-point k of segment i. :class:`Points` names places of the tables
with the (u, x) of the motion there; :func:`enforced_points` gives the
points the stage LPs enforce; :func:`pair_stage_rows` writes (row, vertex)
pairs as rows of the stage LPs.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from rt_drake.dynamics.wrench import PathCoefficients
from rt_drake.retiming._robust_rows import Layout
from rt_drake.retiming._segments import (
    MIDDLE,
    SUBPOINTS,
    Segments,
)
from rt_drake.retiming.passes import StageRows
from rt_drake.uncertainty.inertial_set import ObjectSet

#: Sub-points (indices k of theta = (k + 1) / (K + 1)) where pairs are rows
#: of the stage LPs and where the exactness check looks, besides the grid
#: points: the midpoints, as for one object.
INSIDE = np.array([MIDDLE])


def parameter_columns(objects: ObjectSet) -> tuple[np.ndarray, Layout]:
    """The P parameter columns of a set (P, 10) and where each box's are."""
    columns: list[np.ndarray] = []
    layout = []
    for box in objects.boxes:
        unit = len(columns)
        columns += [box.unit, *box.com]
        center = len(columns)
        columns += [box.center, *box.inertia]
        layout.append([unit, unit + 1, center, center, center + 1, len(columns)])
    masses = np.array([box.mass for box in objects.boxes], dtype=float)
    return np.array(columns), Layout(np.array(layout, dtype=np.int64), masses)


def torque_normals(torque: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The torque limits as rows of a set: directions (2n, n) and normals (n, 2n).

    Row ``r < n`` is ``+tau_r``, row ``n + j`` is ``-tau_j``: the rows
    ``d_r . tau <= tau_max_j``, or ``n_r . tau <= 1`` with the normals
    ``n_r = d_r / tau_max_j`` (``tau_max``: (n,) N m, > 0).
    """
    n = len(torque)
    directions = np.vstack([np.eye(n), -np.eye(n)])
    return directions, directions.T / np.tile(torque, 2)


def torque_columns(
    arm: PathCoefficients, own: PathCoefficients, layout: Layout
) -> PathCoefficients:
    """The set's torque columns with the arm's torque on every box's centre.

    ``tau(pi) = arm + sum_p theta_p own_p`` (joint torques, N m, each
    coefficient of ``u``, ``x`` and 1): a vertex's weights sum its box's
    centre column once, so adding the arm's torque (each (G, n)) to every
    centre column (``own`` each (G, P, n)) gives the whole torque as the
    vertex's combination of columns.
    """
    centres = layout.columns[:, 3]
    out = []
    for part, mine in zip(arm, own, strict=True):
        table = np.array(mine, dtype=float)
        table[:, centres, :] += part[:, None, :]
        out.append(table)
    return PathCoefficients(*out)


class Tables(NamedTuple):
    """The set's columns' coefficients on one grid, each (G + K N, P, D).

    Rows 0..G-1 are the grid points, then the K sub-points of each segment
    (``G + K i + k``); the torques include the arm's (on the centre columns).
    """

    segments: Segments
    wrench: PathCoefficients
    torque: PathCoefficients | None


class Points(NamedTuple):
    """Points of the tables: place (row of the tables), u and x at each."""

    place: np.ndarray
    u: np.ndarray
    x: np.ndarray


def with_subpoints(
    coefficients: PathCoefficients, segments: Segments
) -> PathCoefficients:
    """The coefficients at the grid points, then at every sub-point.

    Each (G + K N, P, D); the sub-points' interpolated
    (:meth:`._between.Segments.interpolate`).
    """
    out = []
    for values in coefficients:
        count, columns, dims = values.shape
        inside = segments.interpolate(values.reshape(count, -1))
        out.append(np.concatenate([values, inside.reshape(-1, columns, dims)]))
    return PathCoefficients(*out)


def inside_places(count: int, stages: int) -> np.ndarray:
    """(N, I) table rows of the interior points of every segment."""
    return count + SUBPOINTS * np.arange(stages)[:, None] + INSIDE


def enforced_points(
    segments: Segments, x: np.ndarray, u: np.ndarray, inside: bool
) -> Points:
    """The points the stage LPs enforced, as places of the tables.

    As :func:`._grasp_rows._enforced_wrenches`: ``s_i`` at ``(u_i, x_i)`` (the
    end point with the last u), then ``s_{i+1}`` at ``(u_i, x_i + 2 ds_i
    u_i)``; with ``inside``, then the :data:`INSIDE` sub-points of every
    segment at ``(u_i, x_i + 2 theta ds_i u_i)``.
    """
    count = len(x)
    stages = count - 1
    place = [np.arange(count), np.arange(1, count)]
    u_at = [np.append(u, u[-1]), u]
    x_at = [x, x[:-1] + 2.0 * segments.ds * u]
    if inside:
        place.append(inside_places(count, stages).ravel())
        u_at.append(np.repeat(u, len(INSIDE)))
        steps = segments.step[:, INSIDE]
        x_at.append((x[:-1, None] + steps * u[:, None]).reshape(-1))
    return Points(np.concatenate(place), np.concatenate(u_at), np.concatenate(x_at))


def pair_stage_rows(
    grid: tuple[np.ndarray, ...],
    bound: np.ndarray,
    segments: Segments,
    inside: tuple[np.ndarray, ...] | None,
) -> StageRows:
    """Pairs as stage rows: ``alpha u + beta x + gamma - bound <= 0``.

    Stage i gets each pair at ``s_i`` and at ``s_{i+1}`` with ``x_{i+1} = x
    + 2 ds_i u`` (the interpolation discretization, as
    :func:`.seidel.project`), and, with ``inside``, at theta = 1/4, 1/2, 3/4
    of its segment with ``x = x_i + 2 theta ds_i u`` (as the joint limits'
    :func:`._between.interior_rows`).

    Args:
        grid: alpha, beta, gamma (G, p) at the grid points.
        bound: (p,) the pairs' bounds.
        segments: The grid's segments.
        inside: alpha, beta, gamma (N I, p) inside the segments, or None.
    """
    alpha, beta, gamma = grid
    step = 2.0 * segments.ds[:, None]
    A = [alpha[:-1], alpha[1:] + step * beta[1:]]
    B = [beta[:-1], beta[1:]]
    C = [gamma[:-1] - bound, gamma[1:] - bound]
    if inside is not None:
        count = len(segments.ds)
        a, b, c = (v.reshape(count, len(INSIDE), -1) for v in inside)
        steps = segments.step[:, INSIDE, None]
        for j in range(len(INSIDE)):
            A.append(a[:, j] + steps[:, j] * b[:, j])
            B.append(b[:, j])
            C.append(c[:, j] - bound)
    return StageRows(np.hstack(A), np.hstack(B), np.hstack(C))


__all__ = [
    "INSIDE",
    "Points",
    "Tables",
    "enforced_points",
    "inside_places",
    "pair_stage_rows",
    "parameter_columns",
    "torque_columns",
    "torque_normals",
    "with_subpoints",
]
