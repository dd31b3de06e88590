"""Exact facets and vertices of a Minkowski sum of small polytopes.

``W = offset + P_1 + ... + P_m`` with ``P_s = conv(V_s)`` of affine dimension
at most 3 in R^n (for the cup: the rim-force pyramids mapped to wrench space).

Facets. For a direction u, the face of W maximising ``u . w`` is the sum of
the faces ``F_s(u)`` of the summands. In the span L of W (dimension d), u is a
facet normal exactly when these faces together span d - 1 directions. A basis
of those directions can always be drawn with at most one item per summand: an
edge (1 direction), a 2-face (2) or the whole summand (3). So the candidate
normals are the unit vectors orthogonal to such combinations, each built by
one Householder step per direction. A candidate is kept, as +u or -u, only
when every chosen item lies in the face of its summand maximising that sign:
then it is a facet normal. Facets are identified by their vertex incidence,
and each plane is re-derived from all its incident vertices (SVD null
vector), so the result is exact to rounding: no redundant row, no duplicate,
no facet missing.

Vertices. Every vertex of W lies on a facet, as a sum of one vertex per
summand taken from the facet's faces. Such a sum x is a vertex exactly when
its minimal face, the intersection of the facets through x, which is
``sum_s (intersection of their faces of P_s)``, is x alone.

Symmetry. Given an orthogonal R with ``R P_s = P_{s+1 (mod m)}`` and
``R offset = offset`` (the cup's rotation by 2 pi/m), only one combination of
summands per rotation orbit is enumerated, and facets and vertices are
completed by rotating: about m times less work.

If d < n, the rows ``c . w <= c . w0`` and ``-c . w <= -c . w0`` for an
orthonormal basis c of L's complement come first (the affine hull).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator, Sequence

import numpy as np

from rt_drake.contact._summand import (
    Summand,
    cyclic_permutations,
    make_summand,
)
from rt_drake.contact._vertex_tuples import cyclic_vertex_tuples

#: A combination's next direction must stick out of the span of the previous
#: ones by this much (directions are unit vectors), or it is skipped.
_INDEPENDENT = 1e-7


@dataclasses.dataclass(frozen=True)
class MinkowskiSum:
    """H- and V-representation of a Minkowski sum.

    Attributes:
        F: (rows, n) unit rows; ``F w <= g`` describes the sum.
        g: (rows,) offsets.
        vertices: (count, n) vertices of the sum.
        equalities: The first ``2 * equalities`` rows are +/- pairs describing
            the affine hull (0 when the sum is full-dimensional).
    """

    F: np.ndarray
    g: np.ndarray
    vertices: np.ndarray
    equalities: int


def _groups(dims: Sequence[int], target: int) -> Iterator[list[tuple[int, int]]]:
    """Yield lists of (summand, item dimension) whose dimensions sum to target."""

    def recurse(s: int, remaining: int, chosen: list[tuple[int, int]]):
        if remaining == 0:
            yield chosen
        elif s < len(dims) and sum(dims[s:]) >= remaining:
            for q in range(min(dims[s], remaining), 0, -1):
                yield from recurse(s + 1, remaining - q, [*chosen, (s, q)])
            yield from recurse(s + 1, remaining, chosen)

    return recurse(0, target, [])


def _is_canonical(group: list[tuple[int, int]], count: int) -> bool:
    """True if the group's dimension pattern is the largest of its rotations."""
    pattern = [0] * count
    for s, q in group:
        pattern[s] = q
    return all(pattern >= pattern[k:] + pattern[:k] for k in range(1, count))


def _drop_direction(basis: np.ndarray, unit: np.ndarray) -> np.ndarray:
    """Remove one direction from K orthonormal bases, by Householder reflections.

    Returns (K, r - 1, d): the span of ``basis`` (K, r, d) orthogonal to the
    combination ``unit`` (K, r) of its rows.
    """
    v = unit.copy()
    v[:, 0] += np.where(unit[:, 0] >= 0.0, 1.0, -1.0)
    scale = 2.0 / np.sum(v * v, axis=1)
    reflection = (
        np.eye(unit.shape[1]) - scale[:, None, None] * v[:, :, None] * v[:, None, :]
    )
    return reflection[:, 1:, :] @ basis


def _candidate_normals(
    group: list[tuple[int, int]], summands: Sequence[Summand], d: int, atol: float
) -> np.ndarray:
    """Return the facet normals (K, d) orthogonal to one group's items."""
    basis = np.eye(d)[None]
    choice = np.zeros((1, 0), dtype=np.intp)
    for s, q in group:
        directions = summands[s].options[q][2]
        count, options = len(basis), len(directions)
        basis = np.repeat(basis, options, axis=0)
        steps = np.tile(directions, (count, 1, 1))
        column = np.tile(np.arange(options), count)[:, None]
        choice = np.hstack([np.repeat(choice, options, axis=0), column])
        for j in range(q):
            coeffs = np.einsum("krd,kd->kr", basis, steps[:, j])
            norms = np.linalg.norm(coeffs, axis=1)
            keep = norms > _INDEPENDENT
            basis, steps, choice = basis[keep], steps[keep], choice[keep]
            basis = _drop_direction(basis, coeffs[keep] / norms[keep, None])
    normals = basis[:, 0, :]
    plus = np.ones(len(normals), dtype=bool)
    minus = plus.copy()
    rows = np.arange(len(normals))
    for item, (s, q) in enumerate(group):
        # The normal is orthogonal to the item, so its vertices share one value.
        values = normals @ summands[s].local.T
        value = values[rows, summands[s].options[q][1][choice[:, item]]]
        plus &= value >= values.max(axis=1) - atol
        minus &= value <= values.min(axis=1) + atol
    return np.vstack([normals[plus], -normals[minus]])


def _incidence(normals: np.ndarray, summands: Sequence[Summand], atol: float):
    """Return (K, sum p) booleans: vertex j of a summand maximises the normal."""
    blocks = []
    for summand in summands:
        values = normals @ summand.local.T
        blocks.append(values >= values.max(axis=1, keepdims=True) - atol)
    return np.hstack(blocks)


def _rederive(
    candidates: np.ndarray, summands: Sequence[Summand], atol: float
) -> tuple[np.ndarray, np.ndarray]:
    """Return one re-derived unit normal per distinct facet, and its incidence.

    Each plane is the SVD null vector of all its incident vertices' differences.
    """
    d = candidates.shape[1]
    incidence = _incidence(candidates, summands, atol)
    packed = np.packbits(incidence, axis=1)
    _, first = np.unique(packed.view(f"V{packed.shape[1]}"), return_index=True)
    normals = np.empty((len(first), d))
    starts = np.cumsum([0] + [len(s.local) for s in summands])
    for row, (key, guess) in enumerate(
        zip(incidence[first], candidates[first], strict=True)
    ):
        directions = []
        for s, summand in enumerate(summands):
            face = summand.local[key[starts[s] : starts[s + 1]]]
            directions.append(face - face[0])
        _, singular, vt = np.linalg.svd(np.vstack(directions))
        if d > 1 and (len(singular) < d - 1 or singular[d - 2] <= atol):
            raise ArithmeticError("a facet's incident vertices span < d - 1")
        normals[row] = vt[-1] if vt[-1] @ guess > 0.0 else -vt[-1]
    return normals, incidence[first]


def _facets(
    summands: Sequence[Summand], d: int, atol: float, rotation: np.ndarray | None
) -> tuple[np.ndarray, np.ndarray]:
    """Return the facets of the sum.

    Returns the unit facet normals (rows, d) in the span L, and the incidence
    of a subset of them holding at least one facet per rotation orbit.
    """
    groups = _groups([s.dimension for s in summands], d - 1)
    if rotation is not None:
        groups = (g for g in groups if _is_canonical(g, len(summands)))
    found = [_candidate_normals(g, summands, d, atol) for g in groups]
    normals, seeds = _rederive(np.vstack([np.zeros((0, d)), *found]), summands, atol)
    if rotation is not None:
        images = [normals]
        for _ in range(len(summands) - 1):
            images.append(images[-1] @ rotation.T)
        normals = _rederive(np.vstack(images), summands, atol)[0]
    # Confirm: re-deriving from the accurate planes changes nothing.
    return _rederive(normals, summands, atol)[0], seeds


@dataclasses.dataclass(frozen=True)
class SumSetup:
    """A Minkowski sum's summands in the coordinates of its span L.

    Attributes:
        parts: The summands, pruned to their vertices, with their faces.
        span: (d, n) orthonormal basis of L.
        complement: (n - d, n) orthonormal basis of L's orthogonal complement.
        offset: (n,) the constant term.
        base: (n,) one point of the sum (offset plus every summand's first point).
        atol: Absolute tolerance of "on a face", in the summands' units.
    """

    parts: list[Summand]
    span: np.ndarray
    complement: np.ndarray
    offset: np.ndarray
    base: np.ndarray
    atol: float

    @property
    def dimension(self) -> int:
        """Dimension d of the span L."""
        return len(self.span)


def prepare_sum(
    summands: Sequence[np.ndarray], offset: np.ndarray, tol: float
) -> SumSetup:
    """Find the span of the sum and each summand's vertices and faces in it.

    ``tol`` is relative to the summands' extent (largest coordinate spread).
    """
    offset = np.asarray(offset, dtype=float)
    full = [np.asarray(v, dtype=float).reshape(-1, offset.size) for v in summands]
    spread = np.vstack([v - v[0] for v in full])
    atol = tol * max(float(np.abs(spread).max(initial=0.0)), 1.0)
    # vt must be (n, n); u need not be (N, N) (N points: N^2 floats).
    _, singular, vt = np.linalg.svd(spread, full_matrices=len(spread) < spread.shape[1])
    d = int(np.sum(singular > atol))
    span = vt[:d]
    return SumSetup(
        parts=[make_summand(v, v @ span.T, atol) for v in full],
        span=span,
        complement=vt[d:],
        offset=offset,
        base=offset + sum(v[0] for v in full),
        atol=atol,
    )


def assemble_sum(
    setup: SumSetup, normals: np.ndarray, tuples: np.ndarray
) -> MinkowskiSum:
    """Return the sum from its facet normals (in L) and vertex index tuples.

    The affine-hull rows come first, then the facets sorted by row and offset;
    each offset is the support value ``sum_s max_j F_k . v_sj + F_k . offset``.
    """
    parts, span, complement, offset = (
        setup.parts,
        setup.span,
        setup.complement,
        setup.offset,
    )
    vertices = offset + sum(p.full[tuples[:, s]] for s, p in enumerate(parts))
    rows = normals @ span
    g = rows @ offset + sum(np.max(p.full @ rows.T, axis=0) for p in parts)
    order = np.lexsort(np.column_stack([rows, g]).T[::-1])
    base = setup.base
    F = np.vstack([complement, -complement, rows[order]])
    g = np.concatenate([complement @ base, -complement @ base, g[order]])
    return MinkowskiSum(F=F, g=g, vertices=vertices, equalities=len(complement))


def minkowski_sum(
    summands: Sequence[np.ndarray],
    offset: np.ndarray,
    symmetry: np.ndarray | None = None,
    tol: float = 1e-9,
    max_memory: float | None = None,
) -> MinkowskiSum:
    """Return the exact H- and V-representation of ``offset + sum conv(V_s)``.

    Args:
        summands: Point sets V_s, each (p_s, n), of affine dimension <= 3.
        offset: (n,) constant added to the sum.
        symmetry: Optional orthogonal (n, n) R mapping summand s onto summand
            s + 1 (mod m) and fixing ``offset``; speeds up the enumeration.
        tol: Relative tolerance of "on a face", times the summands' extent.
        max_memory: Bytes the candidate vertex combinations may take (counted
            exactly before they are made); None: no limit.

    Raises:
        ValueError: If a summand has dimension > 3 or ``symmetry`` is wrong.
        TooLargeError: The vertex candidates would exceed ``max_memory``.
    """
    setup = prepare_sum(summands, offset, tol)
    parts, span, atol, d = setup.parts, setup.span, setup.atol, setup.dimension
    perms, rotation = None, None
    if symmetry is not None:
        symmetry = np.asarray(symmetry, dtype=float)
        if np.abs(symmetry @ setup.offset - setup.offset).max() > atol:
            raise ValueError("symmetry does not fix the offset")
        perms = cyclic_permutations(parts, symmetry, atol)
        rotation = span @ symmetry @ span.T
    if d == 0:
        normals, tuples = np.zeros((0, 0)), np.zeros((1, len(parts)), dtype=np.intp)
    else:
        normals, seeds = _facets(parts, d, atol, rotation)
        incidence = _incidence(normals, parts, atol)
        sizes = [len(p.local) for p in parts]
        tuples = cyclic_vertex_tuples(incidence, seeds, sizes, perms, max_memory)
    return assemble_sum(setup, normals, tuples)
