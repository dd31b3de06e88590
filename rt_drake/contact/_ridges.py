"""Facets of a facet of a Minkowski sum, and the step across a ridge.

``W = offset + P_1 + ... + P_m``, each summand of dimension <= 3, in the
coordinates of the sum's span L (dimension d, see
:mod:`rt_drake.contact._minkowski`). A facet of W with unit normal u is
``Phi = sum_s F_s``, ``F_s`` the face of summand s maximising u; it is named
by its incidence row (which summand vertices it holds). Its ridges, the
facets of Phi, come one of two ways:

- Product. If the dimensions q_s of the faces add up to d - 1, the sum is
  direct, Phi is a product, and its ridges are: one ``F_s`` replaced by one
  of its own facets sigma (an endpoint of an edge, an edge of a polygon, a
  2-face of a pyramid). With ``M = [D_1; ...; D_r; u]`` (the faces'
  orthonormal direction bases and u, a basis of R^d) and ``nu = D_s^T c``
  the unit normal of sigma within F_s pointing out of F_s, the ridge's
  outward normal within Phi is ``n = M^-1[:, block s] c``: orthogonal to u
  and to every direction of the ridge. Every choice of one vertex per F_s
  is a vertex of Phi.
- Enumeration. Otherwise (the faces' directions overlap), the enumeration
  of :mod:`rt_drake.contact._minkowski` restricted to the faces F_s: a ridge
  normal is orthogonal to u and to items (faces of the F_s, at most one per
  summand) whose dimensions add up to d - 2, each lying in the face of its
  F_s that the normal maximises; all combinations in one batched QR. The
  vertices of Phi are the choices whose ridges meet only there
  (:func:`rt_drake.contact._vertex_tuples.vertex_test`).

Step. Across a ridge with normal n within the facet u, the next facet's
normal is ``u' = cos(t) u + sin(t) n`` with the smallest angle t in
(0, pi) at which a vertex v off the ridge comes level with it: for
``a = (v - r) . u < 0`` and ``b = (v - r) . n`` (r a ridge vertex of v's
summand), ``t = atan2(-a, b)`` (gift wrapping). Planes are then re-derived
from all their incident vertices (SVD null vector), as in the enumeration.

The methods take a flag ``U`` (rows of unit normals the face's directions
are orthogonal to: empty for W itself) so that they also apply to faces of
lower dimension.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from rt_drake.contact._minkowski import _INDEPENDENT
from rt_drake.contact._summand import (
    Face,
    Summand,
    face_table,
)
from rt_drake.contact._vertex_tuples import vertex_test

#: Facets whose planes are fitted in one batched SVD (memory: K x P x d).
_CHUNK = 2048


class SumFaces:
    """All summands' vertices in one array, their faces, and the walk's steps.

    Attributes:
        points: (P, d) all summands' vertices, summand after summand.
        starts: (m + 1,) where each summand's vertices start in ``points``.
        owner: (P,) the summand of each vertex.
        tables: Each summand's :func:`face_table`.
    """

    def __init__(self, parts: Sequence[Summand], atol: float) -> None:
        self.parts, self.atol = parts, atol
        self.points = np.vstack([p.local for p in parts])
        sizes = [len(p.local) for p in parts]
        self.starts = np.concatenate([[0], np.cumsum(sizes)]).astype(np.intp)
        self.owner = np.repeat(np.arange(len(parts)), sizes)
        self.tables = [face_table(p) for p in parts]
        self.local = np.arange(len(self.points)) - self.starts[self.owner]
        if max(sizes) > 62:
            raise ValueError(f"a summand has {max(sizes)} vertices; at most 62")
        self.bits = np.left_shift(1, self.local).astype(np.int64)
        self._item_cache: dict[
            tuple[int, int], tuple[np.ndarray, np.ndarray, np.ndarray]
        ] = {}

    def masks(self, row: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Return each summand's face in ``row`` as a bit mask, and its size."""
        masks = np.add.reduceat(np.where(row, self.bits, 0), self.starts[:-1])
        return masks, np.add.reduceat(row.astype(np.intp), self.starts[:-1])

    def product(self, row: np.ndarray) -> np.ndarray:
        """Return (C, m) uint8: every choice of one vertex per summand in ``row``.

        Entries are indices within each summand.
        """
        index = np.flatnonzero(row)
        owner = self.owner[index]
        sizes = np.bincount(owner, minlength=len(self.parts))
        tuples = np.empty((int(np.prod(sizes)), len(sizes)), dtype=np.uint8)
        single = sizes == 1
        tuples[:, single] = self.local[index[single[owner]]]
        several = np.flatnonzero(~single)
        if len(several):
            picks = np.unravel_index(np.arange(len(tuples)), sizes[several])
            for s, pick in zip(several, picks, strict=True):
                tuples[:, s] = self.local[index[owner == s]][pick]
        return tuples

    def below(self, normals: np.ndarray, rows: np.ndarray) -> np.ndarray:
        """Return (K, P) ``v . u - max v' . u``, v' over v's summand in the row."""
        values = normals @ self.points.T
        masked = np.where(rows, values, -np.inf)
        maxima = np.maximum.reduceat(masked, self.starts[:-1], axis=1)
        return values - maxima[:, self.owner]

    def tight(self, normals: np.ndarray, face: np.ndarray) -> np.ndarray:
        """Return (K, P): the vertices of ``face`` maximising each normal."""
        return face & (self.below(normals, face) >= -self.atol)

    def planes(self, rows: np.ndarray, flag: np.ndarray, face: np.ndarray):
        """Return the unit normal (K, d) of each facet of a face, from its rows.

        The SVD null vector of the incident vertices (minus their summand's
        incident centroid) and the face's flag (j, d), oriented so that the
        face's other vertices lie below.

        Raises:
            ArithmeticError: If a row and the flag span fewer than d - 1
                directions (the row is not a facet of the face).
        """
        d = self.points.shape[1]
        normals = np.empty((len(rows), d))
        for k in range(0, len(rows), _CHUNK):
            chunk = rows[k : k + _CHUNK]
            counts = np.add.reduceat(chunk, self.starts[:-1], axis=1)
            sums = np.add.reduceat(
                chunk[:, :, None] * self.points, self.starts[:-1], axis=1
            )
            centres = (sums / np.maximum(counts, 1)[:, :, None])[:, self.owner]
            centred = np.where(chunk[:, :, None], self.points - centres, 0.0)
            # Incident rows first, then the zero rows dropped: same SVD.
            keep = max(int(chunk.sum(1).max()), d)
            order = np.argsort(~chunk, axis=1, kind="stable")[:, :keep]
            centred = np.take_along_axis(centred, order[:, :, None], axis=1)
            flags = np.broadcast_to(flag, (len(chunk), *flag.shape))
            _, singular, vt = np.linalg.svd(np.concatenate([centred, flags], 1))
            if np.any(singular[:, d - 2] <= self.atol):
                raise ArithmeticError("a facet's incident vertices span < d - 1")
            normal = vt[:, -1]
            heights = np.einsum("kpd,kd->kp", self.points - centres, normal)
            heights = np.where(face & ~chunk, heights, 0.0)
            extreme = heights[np.arange(len(chunk)), np.abs(heights).argmax(axis=1)]
            normals[k : k + _CHUNK] = np.where(extreme[:, None] > 0.0, -normal, normal)
        return normals

    def product_facets(
        self, n: np.ndarray, row: np.ndarray, flag: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
        """Return the facets of a product face and its vertices, else None.

        The face is the facet (n, row) of a face with flag ``flag``. Returns
        the facets' normals (r, d) within it, their rows (r, P), and its
        vertices (C, m) as vertex indices within each summand; None if its
        faces' directions overlap (or a face is not in a summand's table).
        """
        d = len(n)
        masks, sizes = self.masks(row)
        faces: list[tuple[int, Face]] = []
        for index in np.flatnonzero(sizes > 1):
            face = self.tables[index].get(int(masks[index]))
            if face is None:
                return None  # not a face of the summand: enumerate instead
            faces.append((int(index), face))
        if sum(len(f.directions) for _, f in faces) != d - 1 - len(flag):
            return None
        inverse = np.linalg.inv(np.vstack([*[f.directions for _, f in faces], n, flag]))
        normals, rows, column = [], [], 0
        for s, face in faces:
            q = len(face.directions)
            for sub, coefficients in face.subfaces:
                normals.append(inverse[:, column : column + q] @ coefficients)
                ridge = row.copy()
                ridge[self.starts[s] : self.starts[s + 1]] = sub
                rows.append(ridge)
            column += q
        unit = np.array(normals).reshape(-1, d)
        unit /= np.linalg.norm(unit, axis=1, keepdims=True)
        return unit, np.array(rows, dtype=bool).reshape(-1, len(row)), self.product(row)

    def _items(self, s: int, mask: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Return the faces of summand s inside face ``mask``, as arrays.

        Row 0 stands for "no item"; then one row per face of dimension >= 1:
        its dimension q, its directions padded to (3, d), and one vertex (an
        index into ``points``; -1 for row 0).
        """
        key = (s, mask)
        if key not in self._item_cache:
            d = self.points.shape[1]
            faces = [f for k, f in self.tables[s].items() if k & ~mask == 0]
            dims = np.array([0] + [len(f.directions) for f in faces])
            directions = np.zeros((len(faces) + 1, 3, d))
            for k, face in enumerate(faces):
                directions[k + 1, : len(face.directions)] = face.directions
            anchors = [-1] + [self.starts[s] + np.argmax(f.members) for f in faces]
            self._item_cache[key] = (dims, directions, np.array(anchors))
        return self._item_cache[key]

    def enumerated_facets(
        self, u: np.ndarray, row: np.ndarray, flag: np.ndarray, limit: float
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
        """Return the facets of the facet (u, row) of a face, and its vertices.

        The enumeration of :mod:`rt_drake.contact._minkowski` restricted to the
        faces F_s of this facet Phi (dimension k): a facet normal of Phi is
        orthogonal to ``[flag; u]`` and to items (faces of the F_s, at most
        one per summand) of dimensions adding up to k - 1, and each item lies
        in the face of its F_s that maximises it. All combinations are solved
        in one batched QR. The vertices are the sums of one vertex per F_s
        whose ridges through it meet only there (:func:`vertex_test`).

        Returns None, without enumerating, when the facet is "hard": more than
        ``limit`` combinations or candidate vertices.
        """
        d = len(u)
        fixed = np.vstack([flag, u])
        target = d - 1 - len(fixed)
        masks, sizes = self.masks(row)
        owners = np.flatnonzero(sizes > 1)
        options = [self._items(int(s), int(masks[s])) for s in owners]
        ways = np.zeros(target + 1)  # combinations by total dimension so far
        ways[0] = 1.0
        for dims, _, _ in options:
            counts = np.bincount(dims, minlength=target + 1)[: target + 1]
            ways = np.convolve(ways, counts)[: target + 1]
        if ways[target] > limit or float(np.prod(sizes, dtype=float)) > limit:
            return None
        room = np.cumsum([dims.max() for dims, _, _ in options][::-1])[::-1]
        combos, total = np.zeros((1, 0), dtype=np.intp), np.zeros(1, dtype=np.intp)
        for k, (dims, _, _) in enumerate(options):
            count = len(dims)
            combos = np.hstack(
                [
                    np.repeat(combos, count, axis=0),
                    np.tile(np.arange(count), len(combos))[:, None],
                ]
            )
            total = np.repeat(total, count) + np.tile(dims, len(total))
            later = room[k + 1] if k + 1 < len(room) else 0
            keep = (total <= target) & (total + later >= target)
            combos, total = combos[keep], total[keep]
        padded = np.concatenate([o[1][combos[:, k]] for k, o in enumerate(options)], 1)
        used = np.concatenate(
            [np.arange(3) < o[0][combos[:, k], None] for k, o in enumerate(options)], 1
        )
        stacked = np.concatenate(
            [
                np.broadcast_to(fixed, (len(combos), *fixed.shape)),
                padded[used].reshape(len(combos), target, d),
            ],
            axis=1,
        )
        # Householder QR of the rows: |R_ii| is how far row i sticks out of
        # the span of the rows before it; Q's last column is orthogonal to all.
        q, r = np.linalg.qr(np.swapaxes(stacked, 1, 2), mode="complete")
        heights = np.abs(np.diagonal(r, axis1=1, axis2=2))
        independent = np.all(heights > _INDEPENDENT, axis=1)
        normals, combos = q[independent, :, -1], combos[independent]
        values = np.where(row, normals @ self.points.T, np.nan)
        high = np.fmax.reduceat(values, self.starts[:-1], axis=1)
        low = np.fmin.reduceat(values, self.starts[:-1], axis=1)
        plus, minus = np.ones(len(combos), bool), np.ones(len(combos), bool)
        rows = np.arange(len(combos))
        for k, (s, (_, _, anchors)) in enumerate(zip(owners, options, strict=True)):
            anchor = anchors[combos[:, k]]
            value = values[rows, np.maximum(anchor, 0)]
            plus &= (anchor < 0) | (value >= high[:, s] - self.atol)
            minus &= (anchor < 0) | (value <= low[:, s] + self.atol)
        guesses = np.vstack([normals[plus], -normals[minus]])
        rows = self.tight(guesses, row)
        packed = np.packbits(rows, axis=1)
        _, first = np.unique(packed.view(f"V{packed.shape[1]}"), return_index=True)
        rows = rows[first]
        normals = self.planes(rows, fixed, row)
        if not np.array_equal(self.tight(normals, row), rows):
            raise ArithmeticError("a facet of a facet is not stable under re-fitting")
        candidates = self.product(row)
        return normals, rows, candidates[vertex_test(candidates, rows, self.starts)]

    def neighbours(
        self, face: np.ndarray, u: np.ndarray, n: np.ndarray, ridges: np.ndarray
    ) -> np.ndarray:
        """Return the normal of the facet of ``face`` across each ridge.

        ``u`` (R, d) facet normals, ``n`` (R, d) the ridges' normals within
        those facets, ``ridges`` (R, P) the ridges' rows.
        """
        a = np.where(face, self.below(u, face), 0.0)
        b = self.below(n, ridges)
        with np.errstate(invalid="ignore"):
            angle = np.where(a < -self.atol, np.arctan2(-a, b), np.inf)
        t = angle.min(axis=1)
        if not np.all(np.isfinite(t)):
            raise ArithmeticError("a ridge has no facet beyond it")
        return np.cos(t)[:, None] * u + np.sin(t)[:, None] * n
