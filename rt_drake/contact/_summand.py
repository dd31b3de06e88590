"""Face lattice of one Minkowski summand: a polytope of dimension <= 3 in R^d.

``rt_drake.contact._minkowski`` needs, for each summand ``P = conv(V)``, its
vertices and its faces of dimension 1, 2 and 3 (edges, 2-faces, the whole
polytope when it is 3-dimensional), each with an orthonormal basis of its
directions. They come from qhull in the summand's own (<= 3)-dimensional
coordinates, where it is cheap and exact enough: faces are then identified
by their vertices with an absolute tolerance.

:func:`face_table` lists the same faces with their own facets, for the walk
of :mod:`rt_drake.contact._adjacency`; :func:`vertex_permutation` and
:func:`cyclic_permutations` turn a symmetry of the sum into a map of the
summands' vertices.
"""

from __future__ import annotations

import dataclasses
import itertools

import numpy as np
from scipy.spatial import ConvexHull


@dataclasses.dataclass(frozen=True)
class Summand:
    """Vertices and faces of one summand.

    Attributes:
        full: (p, n) vertices in the ambient space R^n.
        local: (p, d) the same vertices in coordinates of the sum's span L.
        options: For each face dimension q in {1, 2, 3}: ``members`` (faces, p)
            booleans (vertex j lies on the face), ``anchor`` (faces,) one
            vertex of each face, and ``directions`` (faces, q, d), an
            orthonormal basis of each face's directions.
    """

    full: np.ndarray
    local: np.ndarray
    options: dict[int, tuple[np.ndarray, np.ndarray, np.ndarray]]

    @property
    def dimension(self) -> int:
        """Affine dimension of the summand (0 to 3)."""
        return max(self.options, default=0)


def _directions(points: np.ndarray, dim: int) -> np.ndarray:
    """Return a (dim, d) orthonormal basis of the directions of ``points``."""
    return np.linalg.svd(points - points[0])[2][:dim]


def make_summand(full: np.ndarray, local: np.ndarray, atol: float) -> Summand:
    """Prune a point set to its vertices and list its faces by dimension.

    Args:
        full: (p, n) points in the ambient space.
        local: (p, d) the same points in coordinates of the sum's span.
        atol: Absolute tolerance on distances (same units as the points).
    """
    diffs = local - local[0]
    singular = np.linalg.svd(diffs, compute_uv=False)
    dim = int(np.sum(singular > atol))
    if dim > 3:
        raise ValueError(f"a Minkowski summand has dimension {dim}; at most 3")
    faces: dict[int, list[tuple[int, ...]]] = {}
    keep = np.array([0])
    if dim > 0:
        coords = diffs @ np.linalg.svd(diffs)[2][:dim].T
        if dim == 1:
            keep = np.array([np.argmin(coords[:, 0]), np.argmax(coords[:, 0])])
        else:
            keep = np.sort(ConvexHull(coords).vertices)
        coords = coords[keep]
        faces[dim] = [tuple(range(len(keep)))]
        if dim >= 2:
            hull = ConvexHull(coords)
            distance = np.abs(coords @ hull.equations[:, :-1].T + hull.equations[:, -1])
            faces[dim - 1] = sorted(
                {tuple(np.flatnonzero(c <= atol)) for c in distance.T}
            )
        if dim == 3:
            faces[1] = sorted(
                {
                    common
                    for a, b in itertools.combinations(faces[2], 2)
                    if len(common := tuple(sorted(set(a) & set(b)))) >= 2
                }
            )
    local = local[keep]
    options = {}
    for q, items in sorted(faces.items()):
        members = np.zeros((len(items), len(keep)), dtype=bool)
        directions = np.empty((len(items), q, local.shape[1]))
        for row, item in enumerate(items):
            members[row, list(item)] = True
            directions[row] = _directions(local[list(item)], q)
        options[q] = (members, np.argmax(members, axis=1), directions)
    return Summand(full=full[keep], local=local, options=options)


def cyclic_permutations(
    summands: list[Summand], symmetry: np.ndarray, atol: float
) -> list[np.ndarray]:
    """Return, for each summand s, where ``symmetry`` sends its vertices.

    ``perm[s][j]`` is the index in summand ``s + 1 (mod m)`` of the vertex
    ``symmetry @ summands[s].full[j]``.

    Raises:
        ValueError: If ``symmetry`` does not map summand s onto summand s + 1.
    """
    permutations = []
    for s, summand in enumerate(summands):
        target = summands[(s + 1) % len(summands)].full
        image = summand.full @ symmetry.T
        distance = np.linalg.norm(image[:, None, :] - target[None, :, :], axis=2)
        perm = np.argmin(distance, axis=1)
        if (
            len(target) != len(image)
            or len(set(perm.tolist())) != len(perm)
            or distance[np.arange(len(perm)), perm].max(initial=0.0) > atol
        ):
            raise ValueError(
                f"symmetry does not map summand {s} onto summand "
                f"{(s + 1) % len(summands)}"
            )
        permutations.append(perm)
    return permutations


def vertex_permutation(
    summands: list[Summand], symmetry: np.ndarray, atol: float
) -> np.ndarray:
    """Return where ``symmetry`` sends each vertex of the concatenated summands.

    ``perm[j]`` is the index, among all summands' vertices in order, of
    ``symmetry @ v_j``; ``symmetry`` must map each summand onto a summand (a
    permutation of the summands, in any order).

    Raises:
        ValueError: If ``symmetry`` does not map the summands onto each other.
    """
    starts = np.cumsum([0] + [len(s.full) for s in summands])
    permutation = np.empty(starts[-1], dtype=np.intp)
    targets = set(range(len(summands)))
    for s, summand in enumerate(summands):
        image = summand.full @ symmetry.T
        for t in sorted(targets):
            target = summands[t].full
            if len(target) != len(image):
                continue
            distance = np.linalg.norm(image[:, None, :] - target[None, :, :], axis=2)
            perm = np.argmin(distance, axis=1)
            if len(set(perm.tolist())) == len(perm) and np.all(
                distance[np.arange(len(perm)), perm] <= atol
            ):
                permutation[starts[s] : starts[s + 1]] = starts[t] + perm
                targets.remove(t)
                break
        else:
            raise ValueError(f"symmetry does not map summand {s} onto a summand")
    return permutation


@dataclasses.dataclass(frozen=True)
class Face:
    """A face of one summand: directions and its own facets (sub-faces).

    Attributes:
        members: (p,) booleans: which of the summand's vertices it holds.
        directions: (q, d) orthonormal basis of the face's directions.
        subfaces: One ``(members, coefficients)`` per facet sigma of the face:
            members (p,) booleans over the summand's vertices, coefficients
            (q,) ``D nu`` with nu sigma's outward unit normal within the face.
    """

    members: np.ndarray
    directions: np.ndarray
    subfaces: list[tuple[np.ndarray, np.ndarray]]


def vertex_mask(members: np.ndarray) -> int:
    """Return the integer with bit j set when vertex j is a member."""
    return int.from_bytes(np.packbits(members, bitorder="little").tobytes(), "little")


def face_table(summand: Summand) -> dict[int, Face]:
    """Return every face of dimension >= 1 of a summand, by vertex mask.

    The facets of an edge are its endpoints, of a polygon its edges, of a
    3-D summand its 2-faces. For a facet sigma of a face with directions D
    (q, d), ``nu = D^T c`` is the unit vector in the face's span orthogonal
    to sigma with ``nu . (x - y) < 0`` for x in the face off sigma, y in
    sigma; c is stored.
    """
    table: dict[int, Face] = {}
    points = summand.local
    for q, (members, _, directions) in sorted(summand.options.items()):
        if q == 1:
            lower = [np.eye(len(points), dtype=bool)[j] for j in range(len(points))]
        else:
            lower = list(summand.options[q - 1][0])
        for face, basis in zip(members, directions, strict=True):
            subfaces = []
            for sub in lower:
                if not np.all(face[sub]) or np.array_equal(face, sub):
                    continue
                inner = points[sub] - points[sub][0]
                coefficients = np.linalg.svd(inner @ basis.T)[2][-1]
                outside = points[face & ~sub][0] - points[sub][0]
                if (outside @ basis.T) @ coefficients > 0.0:
                    coefficients = -coefficients
                subfaces.append((sub, coefficients))
            table[vertex_mask(face)] = Face(face, basis, subfaces)
    return table
