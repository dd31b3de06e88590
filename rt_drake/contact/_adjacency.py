"""Facets of a Minkowski sum by walking from facet to adjacent facet.

``W = offset + P_1 + ... + P_m``, each summand of dimension <= 3. The
enumeration of :mod:`rt_drake.contact._minkowski` tries every combination of
summand faces: about ``C(m, d - 1) 8^(d - 1)`` candidates in dimension d,
too many beyond about 10 summands (two suction cups: 12 rim pyramids, 31
million; it did not finish in 10 minutes for two 5-point cups). This walk
costs an amount per facet of W instead (output-sensitive):

1. One facet: the first candidate of the enumeration that is a facet.
2. For each facet found, its ridges (:class:`rt_drake.contact._ridges.SumFaces`)
   and, across each ridge, the neighbouring facet (gift wrapping); each new
   facet, identified by its vertex incidence, is walked from in turn. The
   facet graph of a polytope is connected, so all facets are found.
3. The vertices are those of the facets walked from.

Hard facets. A facet whose ridges would need more than :data:`HARD_LIMIT`
combinations or candidate vertices is recorded but not walked from (for
suction cups: the "tipping" facets, whose normals have no tangential part
and whose faces hold a friction polygon of nearly every rim point). That
loses nothing when the hard facets' normals span at most d - 2 dimensions
(see :func:`walk_facets`); otherwise the walk runs again with no limit.

Symmetry: given a permutation of all summand vertices induced by an
orthogonal map that permutes the summands, only one facet of W per orbit is
walked from, and the orbits are completed at the end.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence

import numpy as np

from rt_drake.contact._minkowski import (
    MinkowskiSum,
    _candidate_normals,
    _groups,
    _incidence,
    assemble_sum,
    minkowski_sum,
    prepare_sum,
)
from rt_drake.contact._ridges import SumFaces
from rt_drake.contact._summand import (
    Summand,
    vertex_permutation,
)
from rt_drake.errors import TooLargeError

#: A facet whose ridges would need more combinations or candidate vertices
#: than this is "hard": the walk does not cross its ridges (see
#: :func:`walk_facets` for why that is sound, and when it is not done).
HARD_LIMIT = 2_000

#: Facets whose neighbours are computed together.
_BATCH = 256


class TooManyFacetsError(TooLargeError):
    """The exact sum has more facets than the caller allows.

    Attributes:
        found: Facets found when the walk stopped (a lower bound).
        seconds: Time the walk had taken.
    """

    def __init__(self, limit: int, found: int, seconds: float) -> None:
        super().__init__(
            f"the exact set has more than {limit} facets ({found} found in "
            f"{seconds:.0f} s); use an inner approximation instead"
        )
        self.found, self.seconds = found, seconds


def _keys(rows: np.ndarray) -> list[bytes]:
    """Return one hashable key per incidence row."""
    return [row.tobytes() for row in np.packbits(rows, axis=1)]


def _walk(
    walk: SumFaces,
    first: tuple[np.ndarray, np.ndarray],
    maps: list[np.ndarray],
    limit: float,
    max_facets: int | None = None,
) -> tuple[list[np.ndarray], list[bool], list[np.ndarray]]:
    """Return one facet row per symmetry orbit, and vertices of the sum.

    Args:
        walk: The summands.
        first: One facet: its unit normal and row.
        maps: Column maps of the symmetry (:func:`_orbit`).
        limit: Size above which a facet is hard.
        max_facets: Raise :class:`TooManyFacetsError` beyond this many facets
            (counting symmetric images).

    Returns:
        The facets' rows (P,), whether each is hard (its ridges were not
        crossed, see :meth:`SumFaces.enumerated_facets`), and arrays (C, m) of
        vertices of the sum as indices into all points (of the facets walked
        from).
    """
    d = walk.points.shape[1]
    everything = np.ones(len(walk.points), dtype=bool)
    flag = np.zeros((0, d))
    found: list[np.ndarray] = []
    hard: list[bool] = []
    tuples: list[np.ndarray] = []
    seen: set[bytes] = set()
    queue: list[tuple[np.ndarray, int]] = []
    start = time.perf_counter()

    def visit(normals: np.ndarray, rows: np.ndarray) -> None:
        for normal, row in zip(normals, rows, strict=True):
            images = _keys(np.array([row[m] for m in maps]))
            if seen.isdisjoint(images):
                seen.update(images)
                queue.append((normal, len(found)))
                found.append(row)
                hard.append(False)
        if max_facets is not None and len(seen) > max_facets:
            raise TooManyFacetsError(max_facets, len(seen), time.perf_counter() - start)

    visit(first[0][None], first[1][None])
    while queue:
        work, queue[:] = queue[:_BATCH], queue[_BATCH:]
        facets, ridges, rows = [], [], []
        for u, index in work:
            product = walk.product_facets(u, found[index], flag)
            if product is None:
                product = walk.enumerated_facets(u, found[index], flag, limit)
            if product is None:
                hard[index] = True
                continue
            facets.append(np.repeat(u[None], len(product[0]), axis=0))
            ridges.append(product[0])
            rows.append(product[1])
            tuples.append(product[2])
        if not facets:
            continue
        guesses = walk.neighbours(
            everything, np.vstack(facets), np.vstack(ridges), np.vstack(rows)
        )
        tight = walk.tight(guesses, everything)
        new, fresh = [], set()
        for k, key in enumerate(_keys(tight)):
            if key not in seen and key not in fresh:
                new.append(k)
                fresh.add(key)
        if new:
            normals = walk.planes(tight[new], flag, everything)
            visit(normals, walk.tight(normals, everything))
    return found, hard, tuples


def _orbit(permutation: np.ndarray | None, count: int) -> list[np.ndarray]:
    """Return the column maps of an incidence row's images under the symmetry.

    ``row[..., maps[k]]`` is the row's image under the k-th power of the map
    sending vertex j to ``permutation[j]``; ``maps[0]`` is the identity.
    """
    maps = [np.arange(count)]
    if permutation is None:
        return maps
    inverse = np.argsort(permutation)
    while len(maps) <= count:
        image = maps[-1][inverse]
        if np.array_equal(image, maps[0]):
            return maps
        maps.append(image)
    raise ValueError("the symmetry's vertex map is not a permutation")


def walk_facets(
    parts: Sequence[Summand],
    atol: float,
    permutation: np.ndarray | None = None,
    max_facets: int | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Return every facet normal (rows, d) and the vertices (count, m) of the sum.

    Hard facets (see :meth:`SumFaces.enumerated_facets`) are found as neighbours
    but not walked across. That loses nothing when their normals span at most
    d - 2 dimensions (a subspace S): the facet graph is the vertex graph of
    the polar polytope, and the polar's vertices off a linear subspace of
    codimension >= 2 stay connected (for any two of them, some hyperplane
    through S has both strictly on one side, and the vertices strictly on one
    side of a hyperplane induce a connected subgraph). Every vertex of the
    sum lies on a facet that is not hard, since its normal cone is
    full-dimensional and so is not inside S, and every hard facet is found,
    as a neighbour of a facet that is not hard (a vertex's edges span R^d).
    If the hard facets span more, the walk is run again with no facet hard.

    Args:
        parts: The summands in the coordinates of the sum's span (d >= 2).
        atol: Absolute tolerance of "on a face".
        permutation: Optional (P,) vertex map of a symmetry (vertex j of the
            concatenated summands goes to vertex ``permutation[j]``); the walk
            visits one facet per orbit and adds the images at the end.
        max_facets: Raise :class:`TooManyFacetsError` beyond this many facets.

    Returns:
        Unit facet normals, and the vertices as summand vertex indices.
    """
    walk = SumFaces(parts, atol)
    d = walk.points.shape[1]
    maps = _orbit(permutation, len(walk.points))
    everything = np.ones(len(walk.points), dtype=bool)
    flag = np.zeros((0, d))
    found: list[np.ndarray] = []
    hard: list[bool] = [True]
    tuples: list[np.ndarray] = []
    for limit in (HARD_LIMIT, math.inf):
        found, hard = [], [True]
        for group in _groups([p.dimension for p in parts], d - 1):
            for normal in _candidate_normals(group, parts, d, atol):
                start = walk.tight(normal[None], everything)
                first = (walk.planes(start, flag, everything)[0], start[0])
                found, hard, tuples = _walk(walk, first, maps, limit, max_facets)
                if not all(hard):
                    break
            if not all(hard):
                break
        if all(hard):
            raise ArithmeticError("no facet that is not hard to start the walk from")
        rows = np.array([row[m] for row in found for m in maps])
        kinds = np.repeat(hard, len(maps))
        packed = np.packbits(rows, axis=1)
        _, unique = np.unique(packed.view(f"V{packed.shape[1]}"), return_index=True)
        rows, kinds = rows[np.sort(unique)], kinds[np.sort(unique)]
        normals = walk.planes(rows, flag, everything)
        if not np.array_equal(_incidence(normals, parts, atol), rows):
            raise ArithmeticError("a symmetric image of a facet is not a facet")
        if not np.any(kinds) or np.linalg.matrix_rank(normals[kinds], 1e-9) <= d - 2:
            break
    chosen = np.vstack(tuples).astype(np.intp) + walk.starts[:-1]
    images = [np.sort(np.argsort(m)[chosen], axis=1) for m in maps]
    local = (np.vstack(images) - walk.starts[:-1]).astype(np.uint8)
    unique = np.unique(local.view(f"V{local.shape[1]}").ravel())
    return normals, unique.view(np.uint8).reshape(-1, len(parts)).astype(np.intp)


def minkowski_sum_walk(
    summands: Sequence[np.ndarray],
    offset: np.ndarray,
    symmetry: np.ndarray | None = None,
    tol: float = 1e-9,
    max_facets: int | None = None,
) -> MinkowskiSum:
    """Return the exact H- and V-representation of ``offset + sum conv(V_s)``.

    The same result as :func:`rt_drake.contact._minkowski.minkowski_sum`, by
    walking across ridges from facet to facet instead of trying every
    combination of summand faces.

    Args:
        summands: Point sets V_s, each (p_s, n), of affine dimension <= 3.
        offset: (n,) constant added to the sum.
        symmetry: Optional orthogonal (n, n) map that permutes the summands
            (in any order) and fixes ``offset``; speeds up the walk.
        tol: Relative tolerance of "on a face", times the summands' extent.
        max_facets: Stop with :class:`TooManyFacetsError` beyond this many.

    Raises:
        ValueError: If a summand has dimension > 3 or ``symmetry`` is wrong.
        TooManyFacetsError: If the sum has more than ``max_facets`` facets.
    """
    setup = prepare_sum(summands, offset, tol)
    if setup.dimension <= 1:
        return minkowski_sum(summands, offset, tol=tol)
    permutation = None
    if symmetry is not None:
        symmetry = np.asarray(symmetry, dtype=float)
        if np.abs(symmetry @ setup.offset - setup.offset).max() > setup.atol:
            raise ValueError("symmetry does not fix the offset")
        permutation = vertex_permutation(setup.parts, symmetry, setup.atol)
    normals, tuples = walk_facets(setup.parts, setup.atol, permutation, max_facets)
    return assemble_sum(setup, normals, tuples)
