"""The (row, vertex) pairs of a set of objects, as rows of the stage LPs.

A pair is a row k of a constraint (a grasp row ``F_k w <= g_k``, or a
joint-torque row) for one vertex v of the set's parameter set (a key of
:mod:`._robust_rows`): an object whose coefficients are a combination of the
set's parameter columns. :class:`Pairs` keeps the pairs found so far and
their values ``n_k . (a, b, c)_v`` on the current grid (computed once per
pair and grid: a new round of the retimer computes only its new pairs');
:class:`Cut` holds a pair at one sub-point of one segment.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from rt_drake.dynamics.wrench import PathCoefficients
from rt_drake.retiming._robust_rows import (
    Layout,
    vertex_weights,
)
from rt_drake.retiming._segments import (
    SUBPOINTS,
    Segments,
)
from rt_drake.retiming.passes import StageRows


class Cut(NamedTuple):
    """A pair held at one sub-point of one segment (a cut of that stage's LP).

    Attributes:
        segments: The grid it was made for.
        stage: The segment i.
        subpoint: k, the sub-point theta = (k + 1) / (K + 1).
        row: The grasp row (or torque row, if ``torque``).
        vertex: The vertex key.
        torque: Whether it is a torque row.
    """

    segments: Segments
    stage: int
    subpoint: int
    row: int
    vertex: int
    torque: bool


class Pairs:
    """(row, vertex) pairs in the order found, with their stage-row values.

    ``values[name]`` keeps ``n_k . (a, b, c)_v`` of the pairs found so far on
    the grid they were computed for, so a new round computes only the new
    pairs'.
    """

    def __init__(self) -> None:
        self.rows: list[int] = []
        self.vertices: list[int] = []
        self._known: set[tuple[int, int]] = set()
        self.values: dict[str, tuple[Segments, list[np.ndarray]]] = {}

    def add(self, rows: np.ndarray, vertices: np.ndarray) -> bool:
        """Add the new pairs; whether there was one."""
        added = False
        for pair in zip(rows.tolist(), vertices.tolist(), strict=True):
            if pair not in self._known:
                self._known.add(pair)
                self.rows.append(pair[0])
                self.vertices.append(pair[1])
                added = True
        return added

    def __len__(self) -> int:
        return len(self.rows)

    def stage_values(
        self,
        name: str,
        table: PathCoefficients,
        directions: np.ndarray,
        layout: Layout,
        inside: np.ndarray | None,
        segments: Segments,
    ) -> tuple[tuple[np.ndarray, ...], tuple[np.ndarray, ...] | None]:
        """``n_k . (a, b, c)_v`` of every pair (row k, vertex v), (places, p).

        At the grid points and at the ``inside`` places of the tables
        (:mod:`._set_tables`); cached per name and grid, so that only new
        pairs are computed.

        Args:
            name: Which values (the cache's key, with the grid).
            table: The set's columns' coefficients (each (G + K N, P, D)).
            directions: (R, D) the rows ``n_k`` (unscaled).
            layout: The boxes among the P columns.
            inside: (N, I) places inside the segments, or None.
            segments: The grid.
        """
        count = len(segments.s)
        places = np.arange(count)
        if inside is not None:
            places = np.concatenate([places, inside.reshape(-1)])
        cached = self.values.get(name)
        if cached is None or cached[0] is not segments:
            cached = (segments, [np.zeros((len(places), 0))] * 3)
        done = cached[1][0].shape[1]
        if done < len(self):
            rows = np.array(self.rows[done:])
            vertices, which = np.unique(self.vertices[done:], return_inverse=True)
            weights = vertex_weights(layout, vertices, table[0].shape[1])
            new = []
            for part in table:
                chosen = part[places]  # (M, P, D)
                places_count, columns, dims = chosen.shape
                flat = chosen.transpose(1, 0, 2).reshape(columns, -1)
                per_vertex = (weights @ flat).reshape(len(vertices), places_count, dims)
                new.append(np.einsum("pmd,pd->mp", per_vertex[which], directions[rows]))
            cached = (
                segments,
                [np.hstack([old, v]) for old, v in zip(cached[1], new, strict=True)],
            )
            self.values[name] = cached
        values = cached[1]
        grid = tuple(v[:count] for v in values)
        interior = None if inside is None else tuple(v[count:] for v in values)
        return grid, interior


def cut_rows(
    cuts: list[Cut],
    tables: dict[bool, PathCoefficients],
    directions: dict[bool, np.ndarray],
    bounds: dict[bool, np.ndarray],
    layout: Layout,
    segments: Segments,
) -> StageRows:
    """Each cut as a row of its own stage (inactive in the others).

    Args:
        cuts: The cuts of this grid.
        tables: The set's coefficient tables, by ``cut.torque``.
        directions: (R, D) the rows, by ``cut.torque``.
        bounds: (R,) their bounds, by ``cut.torque``.
        layout: The boxes among the columns.
        segments: The grid.
    """
    count = len(segments.s)
    stages = len(segments.ds)
    A = np.zeros((stages, len(cuts)))
    B = np.zeros((stages, len(cuts)))
    C = np.full((stages, len(cuts)), -1.0)
    columns = tables[False].a.shape[1]
    weights = vertex_weights(layout, np.array([cut.vertex for cut in cuts]), columns)
    for j, cut in enumerate(cuts):
        place = count + SUBPOINTS * cut.stage + cut.subpoint
        table = tables[cut.torque]
        direction = directions[cut.torque][cut.row]
        bound = bounds[cut.torque][cut.row]
        a, b, c = (float(weights[j] @ v[place] @ direction) for v in table)
        A[cut.stage, j] = a + segments.step[cut.stage, cut.subpoint] * b
        B[cut.stage, j] = b
        C[cut.stage, j] = c - bound
    return StageRows(A, B, C)


__all__ = ["Cut", "Pairs", "cut_rows"]
