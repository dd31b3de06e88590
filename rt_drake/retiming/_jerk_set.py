"""The grasp of a set of objects in the jerk-limited retimer's LPs.

For a set of objects (:mod:`rt_drake.uncertainty.inertial_set`), the object
wrench at a point is ``w = sum_p theta_p (a_p u + b_p x + c_p)``: linear in
the set's parameter columns p (``PathSamples.wrench_set``), each object a
weight vector theta. Row r of the grasp, ``n_r w <= 1`` (``n_r = F_r /
g_r``), holds for every object of the set iff it holds for the worst
vertex of the set, which :func:`._robust_rows.worst_rows` finds in closed
form at each point (with its key).

The LPs take the set's rows as (point, row, vertex) triples, each the
linear row ``alpha u + beta x <= 1 - gamma`` with ``alpha = n_r . sum_p
theta_vp a_p`` (and beta, gamma likewise from b, c): exact at its point for
that vertex. Triples are added where the worst vertex of a row is near or
over the limit (:class:`SetPairs`), and once in, stay in; the LPs' profile
is then checked against the whole set at every dense point.

With torque limits the joint torques depend on the object too: ``tau = arm
+ sum_p theta_p (a_p u + b_p x + c_p)`` (the arm's own torque on every box's
centre column, :func:`._set_tables.torque_columns`), so the rows
``+-tau_j / tau_max_j <= 1`` are a second set of rows of the same form
(``normals`` (n, 2n), one per joint and sign): their worst vertex per
(point, joint, sign) comes from the same closed form, and they enter the
LPs as (point, row, vertex) triples of another :class:`SetPairs`.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from rt_drake.dynamics.wrench import PathCoefficients
from rt_drake.retiming._jerk_rows import Band, Rows, key
from rt_drake.retiming._robust_rows import Layout, Worst, vertex_weights, worst_rows

#: Rows ranked per point when looking for the set's worst (row, vertex).
RANKS = 3


class SetGrasp(NamedTuple):
    """The grasp of a set of objects: its rows and the set's boxes.

    Attributes:
        normals: (6, R) the rows ``n_r = F_r / g_r`` (``n_r w <= 1``).
        layout: The set's boxes among its parameter columns.
        torque: With torque limits, (n, 2n) the torque rows' normals
            ``+-e_j / tau_max_j`` (1/(N m), :func:`._set_tables.torque_normals`);
            else None.
    """

    normals: np.ndarray
    layout: Layout
    torque: np.ndarray | None = None


class SetPairs:
    """The (point, row, vertex) triples of a set of objects in the LPs.

    Args:
        table: The set's columns at the P dense points, a, b, c each (P, C,
            D): the wrench's (D = 6) or the joint torques' (D = n).
        normals: (D, R) the rows ``n_r`` (``n_r w <= 1``).
        layout: The set's boxes among the C columns.
        ranks: Rows ranked per point by :meth:`worst` (all R: every row's
            worst vertex).
    """

    def __init__(
        self,
        table: PathCoefficients,
        normals: np.ndarray,
        layout: Layout,
        ranks: int = RANKS,
    ) -> None:
        self.table = table
        self.normals = normals
        self.layout = layout
        self.ranks = ranks
        self._ids: dict[tuple[int, int], int] = {}
        self._triples: set[tuple[int, int, int]] = set()
        self.point = np.zeros(0, dtype=np.int64)
        self.row = np.zeros(0, dtype=np.int64)
        self.vertex = np.zeros(0, dtype=np.int64)

    def worst(self, x: np.ndarray, u: np.ndarray) -> Worst:
        """The worst (row, vertex) pairs at every dense point, at (x, u) there."""
        index = np.arange(len(x))
        return worst_rows(
            self.table, index, u, x, self.normals, self.layout, self.ranks
        )  # fmt: skip

    def add(self, worst: Worst, chosen: np.ndarray) -> None:
        """The ranked pairs of ``worst`` where ``chosen`` ((P, RANKS) bool)."""
        assert worst.ranked is not None
        _, rows, vertices = worst.ranked
        points, ranks = np.nonzero(chosen & (rows >= 0))
        new = []
        for p, r, v in zip(
            points.tolist(),
            rows[points, ranks].tolist(),
            vertices[points, ranks].tolist(),
            strict=True,
        ):
            if (p, r, v) not in self._triples:
                self._triples.add((p, r, v))
                new.append((p, r, v))
        if new:
            added = np.array(new, dtype=np.int64)
            self.point = np.concatenate([self.point, added[:, 0]])
            self.row = np.concatenate([self.row, added[:, 1]])
            self.vertex = np.concatenate([self.vertex, added[:, 2]])

    def __len__(self) -> int:
        return len(self.point)

    def rows(self, band: Band, at: np.ndarray, kind: int) -> Rows:
        """The triples at the points ``at`` as LP rows (module docstring).

        ``band``: x, u of all dense points; ``kind``: the rows' key kind
        (the key's column names the (row, vertex) pair).
        """
        chosen = np.flatnonzero(np.isin(self.point, at))
        point, row, vertex = (v[chosen] for v in (self.point, self.row, self.vertex))
        weights = vertex_weights(self.layout, vertex, self.table.a.shape[1])
        normal = self.normals[:, row].T  # (T, 6)

        def along(m: np.ndarray) -> np.ndarray:
            return np.einsum("tc,tcd,td->t", weights, m[point], normal)

        alpha, beta, gamma = (along(m) for m in self.table)
        pair = np.array(
            [
                self._ids.setdefault((r, v), len(self._ids))
                for r, v in zip(row.tolist(), vertex.tolist(), strict=True)
            ],
            dtype=np.int64,
        )
        return Rows(
            band.cols[point],
            alpha[:, None] * band.U[point] + beta[:, None] * band.X[point],
            1.0 - gamma,
            key(kind, point, pair),
        )


__all__ = ["RANKS", "SetGrasp", "SetPairs"]
