"""Vertices of a Minkowski sum as tuples of summand vertices.

A vertex of ``W = offset + P_1 + ... + P_m`` is a sum of one vertex per
summand; it is written as the tuple of their indices. Every vertex lies on a
facet, and a candidate tuple x is a vertex exactly when its minimal face, the
intersection of the facets through x (``sum_s`` of the intersections of their
faces of P_s), is x alone: :func:`vertex_test` checks that from the facets'
vertex incidence.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from rt_drake.contact.exact_cost import BYTES_PER_VERTEX_CODE
from rt_drake.errors import TooLargeError


def _codes(tuples: np.ndarray, base: int) -> np.ndarray:
    """Encode (C, m) vertex indices as integers ``sum_s t_s base^s``."""
    return tuples @ (base ** np.arange(tuples.shape[1], dtype=np.int64))


def _decode(codes: np.ndarray, base: int, count: int) -> np.ndarray:
    return (codes[:, None] // base ** np.arange(count, dtype=np.int64)) % base


def vertex_test(
    tuples: np.ndarray, incidence: np.ndarray, starts: np.ndarray
) -> np.ndarray:
    """Return which candidate tuples are vertices of the sum.

    Args:
        tuples: (C, m) vertex indices, one per summand.
        incidence: (rows, sum p) booleans: summand vertex j lies on facet k.
        starts: (m + 1,) offsets of each summand's vertices in the columns.

    A sum x of one vertex per summand is a vertex when the intersection of the
    facets through x holds, in every summand, only x's own vertex.
    """
    m = tuples.shape[1]
    table = incidence.astype(np.float32)
    vertex = np.zeros(len(tuples), dtype=bool)
    for chunk in range(0, len(tuples), 4096):
        rows = tuples[chunk : chunk + 4096] + starts[:-1]
        onehot = np.zeros((len(rows), table.shape[1]), dtype=np.float32)
        np.put_along_axis(onehot, rows, 1.0, axis=1)
        tight = (onehot @ table.T) == m
        common = tight.astype(np.float32) @ table
        minimal = common == tight.sum(axis=1, keepdims=True)
        vertex[chunk : chunk + 4096] = minimal.sum(axis=1) == m
    return vertex


def cyclic_vertex_tuples(
    incidence: np.ndarray,
    seeds: np.ndarray,
    sizes: Sequence[int],
    perms: list[np.ndarray] | None,
    max_memory: float | None = None,
) -> np.ndarray:
    """Return (count, m) vertex indices, one per summand, of the sum's vertices.

    Candidates come from the facets ``seeds`` (incidence rows): every choice
    of one vertex per summand on a seed facet, ``sum_rows prod_s |row_s|`` of
    them; with ``perms`` (vertex permutations of the symmetry) one tuple per
    orbit is tested and the rest follow by rotation. The test uses every facet
    of ``incidence``.

    Raises:
        TooLargeError: before allocating them, if the candidates would take
            more than ``max_memory`` bytes (``BYTES_PER_VERTEX_CODE`` each),
            or their codes would not fit in 62 bits.
    """
    m, base = len(sizes), max(sizes)
    if float(base) ** m >= 2.0**62:
        raise TooLargeError(f"{m} summands of {base} vertices: too many to encode")
    starts = np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64)
    per_summand = np.add.reduceat(seeds.astype(np.float64), starts[:-1], axis=1)
    count = float(np.prod(per_summand, axis=1).sum())
    if max_memory is not None and BYTES_PER_VERTEX_CODE * count > max_memory:
        raise TooLargeError(
            f"{count:.3g} candidate vertex combinations need about "
            f"{BYTES_PER_VERTEX_CODE * count / 2**30:.3g} GB "
            f"(limit {max_memory / 2**30:.3g} GB)"
        )
    weights = base ** np.arange(m, dtype=np.int64)
    pieces: list[np.ndarray] = []
    for row in seeds:
        code = np.zeros(1, dtype=np.int64)
        for s in range(m):
            local = np.flatnonzero(row[starts[s] : starts[s + 1]])
            code = np.add.outer(code, local * weights[s]).ravel()
        pieces.append(code)
    codes = np.unique(np.concatenate(pieces))

    def rotate(tuples: np.ndarray, perms: list[np.ndarray]) -> np.ndarray:
        return np.roll(
            np.column_stack([p[t] for p, t in zip(perms, tuples.T, strict=True)]), 1, 1
        )

    if perms is not None:  # test one tuple per rotation orbit
        tuples, lowest = _decode(codes, base, m), codes
        for _ in range(m - 1):
            tuples = rotate(tuples, perms)
            lowest = np.minimum(lowest, _codes(tuples, base))
        codes = np.unique(lowest)
    tuples = _decode(codes, base, m)
    tuples = tuples[vertex_test(tuples, incidence, starts)]
    if perms is not None:
        images = [tuples]
        for _ in range(m - 1):
            images.append(rotate(images[-1], perms))
        tuples = _decode(np.unique(_codes(np.vstack(images), base)), base, m)
    return tuples
