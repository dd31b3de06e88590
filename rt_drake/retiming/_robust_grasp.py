"""The grasp rows of a set of objects: (row, vertex) pairs, added as they bind.

A robust grasp must hold every object of a set Q of inertial parameters
(:mod:`rt_drake.uncertainty.inertial_set`): ``F_k w(pi) <= g_k`` for every row k and
every pi in Q, at every point the stage LPs constrain. The wrench is linear
in pi, so it suffices to hold the vertices of Q; Q has many (1024 for the
notebook's set) and only a few bind anywhere. :class:`SetRows` gives the
stage LPs pairs (row k, vertex v): the vertex is an object whose wrench
coefficients are a combination of the set's parameter columns
(``samples.wrench_set``), and the pair is a row at the grid points and at
the segments' midpoints (coefficients interpolated, as for one object).
After each solve every row is evaluated at every one of those points for its
worst vertex, in closed form (:func:`._robust_rows.worst_rows`); where the
worst pair is violated it is added and the passes run again (the first
solve has no grasp rows at all: three solves in all are typical). When no
pair is violated the profile holds every object of Q at every point the LPs
constrain, and it is the profile TOPP-RA computes with every (row, vertex)
pair there (the pairs are a relaxation that turned out admissible, the
argument of :mod:`._solve`).

Between those points :meth:`SetRows.between` evaluates the worst object at
the seven sub-points of every segment; where it exceeds a limit, the worst
pair there becomes a cut of that stage (a row at that sub-point only) and
the passes run again. Cuts rather than new grid points: a grid point costs a
Drake evaluation and every pair's rows again, a cut one row.

With torque limits the torques depend on the object too (``tau = arm +
J_Coᵀ w(pi)``): the rows ``+-tau_j / tau_max_j <= 1`` are handled the same
way, at the grid points.

The robot must be able to stop anywhere: at rest (u = x = 0) the worst
object of Q must be held, and its gravity torques within limits, at every
grid point; the error names the worst object.
"""

from __future__ import annotations

import numpy as np
from toppra.constraint import LinearConstraint

from rt_drake.dynamics.wrench import PathCoefficients
from rt_drake.retiming import stage_rows as R
from rt_drake.retiming._at_rest import (
    set_grasp_at_rest,
    set_torque_at_rest,
)
from rt_drake.retiming._between import ROW_SCREEN
from rt_drake.retiming._grasp_rows import (
    ROW_TOLERANCE,
    Check,
)
from rt_drake.retiming._robust_rows import (
    vertex_weights,
    worst_rows,
)
from rt_drake.retiming._samples import PathSamples
from rt_drake.retiming._segments import Segments, subpoint_x
from rt_drake.retiming._set_pairs import (
    Cut,
    Pairs,
    cut_rows,
)
from rt_drake.retiming._set_tables import (
    Points,
    Tables,
    enforced_points,
    inside_places,
    pair_stage_rows,
    parameter_columns,
    torque_columns,
    torque_normals,
    with_subpoints,
)
from rt_drake.retiming.limits import JointLimits, ObjectSetGrasp
from rt_drake.retiming.passes import StageRows
from rt_drake.uncertainty.inertial_set import (
    SetVertex,
    set_vertex,
)

#: Rows ranked at each point by the exactness check (their worst pairs added
#: where violated).
RANKS = 1
#: Rows whose screening bound at the enforced points exceeds this are
#: looked at between grid points.
SCREEN = 1.0 - ROW_SCREEN


class SetRows:
    """Grasp (and torque) rows of a set of objects (module docstring).

    Attributes:
        grasp: The constraint (``grasp.objects`` the set).
        columns: (P, 10) the set's parameter columns.
        layout: The boxes among the columns.
        repairs: Rounds that added pairs in the current solve.
    """

    robust = True

    def __init__(self, grasp: ObjectSetGrasp, limits: JointLimits) -> None:
        self.grasp = grasp
        self.limits = limits
        self.columns, self.layout = parameter_columns(grasp.objects)
        self.normals = R.normalised_rows(grasp.F, grasp.g)
        self.repairs = 0
        self._grasp = Pairs()
        self._torque = Pairs()
        self._tables: Tables | None = None
        self._cuts: list[Cut] = []
        self._torque_normals: np.ndarray | None = None
        self._torque_directions: np.ndarray | None = None
        if limits.torque is not None:
            directions, normals = torque_normals(limits.torque)
            self._torque_directions, self._torque_normals = directions, normals

    def add(self, samples: PathSamples) -> None:
        """The worst object of the set held, and its torques, at rest."""
        assert samples.wrench_set is not None
        count = len(samples.s)
        rest = Points(np.arange(count), np.zeros(count), np.zeros(count))
        worst = worst_rows(samples.wrench_set, *rest, self.normals, self.layout)
        if np.any(worst.ratio >= 1.0):
            i = int(np.flatnonzero(worst.ratio >= 1.0)[0])
            vertex = int(worst.key[i])
            c = self._vertex_weights(vertex) @ samples.wrench_set.c[i]
            set_grasp_at_rest(samples.s[i], c, self.vertex_object(vertex), self.grasp)
        if self._torque_normals is not None:
            torque = self._torque_table(samples.torque, samples.torque_set)
            held = worst_rows(torque, *rest, self._torque_normals, self.layout)
            if np.any(held.ratio >= 1.0):
                i = int(np.flatnonzero(held.ratio >= 1.0)[0])
                set_torque_at_rest(
                    samples.s[i],
                    int(held.row[i]),
                    float(held.ratio[i]),
                    self.vertex_object(int(held.key[i])),
                    self.limits,
                )

    def begin(self) -> None:
        """Start a solve (the pairs found so far stay)."""
        self.repairs = 0

    def constraints(
        self, samples: PathSamples, segments: Segments
    ) -> list[LinearConstraint]:
        """The pairs as stage rows: grid points (interpolation) and interior."""
        tables = self._tables_for(samples, segments)
        count = len(samples.s)
        inside = inside_places(count, len(segments.ds))
        out: list[LinearConstraint] = []
        if len(self._grasp):
            rows = np.array(self._grasp.rows)
            grid, interior = self._grasp.stage_values(
                "wrench", tables.wrench, self.grasp.F, self.layout, inside, segments
            )
            out.append(pair_stage_rows(grid, self.grasp.g[rows], segments, interior))
        if len(self._torque):
            assert tables.torque is not None and self.limits.torque is not None
            assert self._torque_directions is not None
            rows = np.array(self._torque.rows)
            grid, _ = self._torque.stage_values(
                "torque",
                tables.torque,
                self._torque_directions,
                self.layout,
                None,
                segments,
            )
            bound = np.tile(self.limits.torque, 2)[rows]
            out.append(pair_stage_rows(grid, bound, segments, None))
        cuts = [cut for cut in self._cuts if cut.segments is segments]
        if cuts:
            out.append(self._cut_rows(cuts, tables, segments))
        return out

    def widen(self) -> bool:
        """Never: a relaxation that is not controllable proves the set is not."""
        return False

    def check(
        self, samples: PathSamples, segments: Segments, x: np.ndarray, u: np.ndarray
    ) -> Check:
        """Every row's worst vertex at every enforced point; add the violated.

        At each point, the worst (row, vertex) of the :data:`RANKS` rows of
        largest worst value are added where violated (the others usually
        follow them out of the way). The screen is an upper bound of each
        grasp row's largest value at the enforced points.
        """
        tables = self._tables_for(samples, segments)
        count = len(samples.s)
        points = enforced_points(segments, x, u, inside=True)
        worst = worst_rows(tables.wrench, *points, self.normals, self.layout, RANKS)
        assert worst.ranked is not None
        values, rows, keys = worst.ranked
        excess = self.grasp.g[rows] * (values - 1.0)
        violated = (rows >= 0) & (excess > ROW_TOLERANCE)
        added = self._grasp.add(rows[violated], keys[violated])
        if self._torque_normals is not None:
            assert tables.torque is not None
            grid = enforced_points(segments, x, u, inside=False)
            torque = worst_rows(tables.torque, *grid, self._torque_normals, self.layout)
            violated = torque.ratio - 1.0 > ROW_TOLERANCE
            added |= self._torque.add(torque.row[violated], torque.key[violated])
        self.repairs += int(added)
        return Check(added, worst.ratio[:count], worst.bound_max)

    def between(
        self,
        samples: PathSamples,
        segments: Segments,
        x: np.ndarray,
        u: np.ndarray,
        screen: np.ndarray,
        tolerance: float | None = None,
    ) -> tuple[np.ndarray | None, bool]:
        """The worst grasp (and torque) ratio at the sub-points (N, K), >= 0.

        The grasp rows whose screening bound at the enforced points comes
        within :data:`~._between.ROW_SCREEN` of 1; every torque row. With a
        ``tolerance``, where a segment exceeds 1 by more, the worst pair of
        each of its sub-points above 1 becomes a cut of that stage (held at
        that sub-point, coefficients interpolated as the interior rows'):
        cheaper than new grid points, which would cost a Drake evaluation and
        every pair's rows again.

        Returns:
            The ratio (None: nothing to look at), and whether cuts were added.
        """
        rows = np.flatnonzero(screen > SCREEN)
        torque = self._torque_normals is not None
        if not rows.size and not torque:
            return None, False
        tables = self._tables_for(samples, segments)
        x_sub = subpoint_x(segments, x, u)
        count = len(samples.s)
        points = Points(
            count + np.arange(x_sub.size),
            np.repeat(u, x_sub.shape[1]),
            x_sub.reshape(-1),
        )
        ratio = np.zeros(x_sub.size)
        found = []
        if rows.size:
            worst = worst_rows(
                tables.wrench, *points, self.normals[:, rows], self.layout
            )
            ratio = np.maximum(ratio, worst.ratio)
            found.append((worst, rows, False))
        if torque:
            assert tables.torque is not None and self._torque_normals is not None
            worst = worst_rows(
                tables.torque, *points, self._torque_normals, self.layout
            )
            ratio = np.maximum(ratio, worst.ratio)
            found.append((worst, np.arange(self._torque_normals.shape[1]), True))
        by_segment = ratio.reshape(x_sub.shape)
        added = False
        if tolerance is not None:
            exceeded = np.repeat(
                by_segment.max(axis=1) - 1.0 > tolerance, x_sub.shape[1]
            )
            for worst, index, is_torque in found:
                for point in np.flatnonzero(exceeded & (worst.ratio > 1.0)).tolist():
                    stage, subpoint = divmod(point, x_sub.shape[1])
                    cut = Cut(
                        segments,
                        stage,
                        subpoint,
                        int(index[worst.row[point]]),
                        int(worst.key[point]),
                        is_torque,
                    )
                    if cut not in self._cuts:
                        self._cuts.append(cut)
                        added = True
        return by_segment, added

    def torque_margin(
        self, samples: PathSamples, x: np.ndarray, u: np.ndarray
    ) -> np.ndarray | None:
        """``1 - max_j |tau_j| / tau_max_j`` over the set at the grid points."""
        if self._torque_normals is None:
            return None
        count = len(x)
        torque = self._torque_table(samples.torque, samples.torque_set)
        points = Points(np.arange(count), np.append(u, u[-1]), x)
        return (
            1.0 - worst_rows(torque, *points, self._torque_normals, self.layout).ratio
        )

    def vertex_object(self, vertex: int) -> SetVertex:
        """The point of the outer set at a vertex key (mass, centre of mass)."""
        return set_vertex(self._vertex_weights(vertex) @ self.columns)

    @property
    def torque_normals(self) -> np.ndarray | None:
        """(n, 2n) the torque rows' normals ``+-e_j / tau_max_j`` (None: no limits)."""
        return self._torque_normals

    @property
    def row_count(self) -> int:
        """(row, vertex) pairs the LPs used."""
        return len(self._grasp) + len(self._torque)

    @property
    def object_count(self) -> int:
        """Vertex objects whose rows the LPs used."""
        return len(set(self._grasp.vertices) | set(self._torque.vertices))

    def _vertex_weights(self, vertex: int) -> np.ndarray:
        """The columns' weights (P,) of a vertex."""
        return vertex_weights(self.layout, np.array([vertex]), len(self.columns))[0]

    def _tables_for(self, samples: PathSamples, segments: Segments) -> Tables:
        """The tables of this grid (built once per grid)."""
        if self._tables is None or self._tables.segments is not segments:
            assert samples.wrench_set is not None
            wrench = with_subpoints(samples.wrench_set, segments)
            torque = None
            if self._torque_normals is not None:
                assert samples.torque is not None and samples.torque_set is not None
                arm = PathCoefficients(*(v[:, None, :] for v in samples.torque))
                torque = self._torque_table(
                    PathCoefficients(*(v[:, 0] for v in with_subpoints(arm, segments))),
                    with_subpoints(samples.torque_set, segments),
                )
            self._tables = Tables(segments, wrench, torque)
        return self._tables

    def _cut_rows(
        self, cuts: list[Cut], tables: Tables, segments: Segments
    ) -> StageRows:
        """The cuts as stage rows (:func:`._set_pairs.cut_rows`)."""
        table = {False: tables.wrench}
        directions = {False: self.grasp.F}
        bounds = {False: self.grasp.g}
        if tables.torque is not None:
            assert self._torque_directions is not None
            assert self.limits.torque is not None
            table[True] = tables.torque
            directions[True] = self._torque_directions
            bounds[True] = np.tile(self.limits.torque, 2)
        return cut_rows(cuts, table, directions, bounds, self.layout, segments)

    def _torque_table(
        self, arm: PathCoefficients | None, own: PathCoefficients | None
    ) -> PathCoefficients:
        """The torque columns with the arm's torque on every box's centre."""
        assert arm is not None and own is not None
        return torque_columns(arm, own, self.layout)


__all__ = ["SCREEN", "SetRows"]
