"""The wrench set of a multi-cup tool whose cups share the load elastically.

The exact W_T of :mod:`rt_drake.contact.tool_polytope` (the Minkowski sum of
the cups' sets) lets every rim point carry any normal force its pyramid
allows: it assumes the load splits between the cups in whatever way holds
the object. A rigid tool on a rigid object does not choose its split. Each
rim point is a spring of the same normal stiffness k, so a small rigid
displacement of the object on the tool (``dz`` along T's z, rotations
``rx``, ``ry`` about T's x and y) sets every normal force:

    n_i = k (dz + rx y_i - ry x_i) = A_i c,   A_i = [y_i, -x_i, 1],
    c = k [rx, ry, dz]

with ``(x_i, y_i)`` rim point i in T (every cup in T's z = 0 plane, its axis
along T's z). The rims' normal forces must balance the normal part of the
wrench, ``b(w) = (tau_x, tau_y, f_z)`` of ``w`` minus the cups' suction
wrench; ``A^T n = b`` gives the spring (least-energy) split

    n(w) = A (A^T A)^-1 (b(w) - b_suction),

affine in w (the 2024 load-sharing model's split by spring energy, for
equal springs). The tangential part ``t(w) = (tau_z, f_x, f_y)`` must come
from friction: with normal forces n, point i adds any point of ``n_i Q_i``,
Q_i its friction polygon (vertices ``mu (cos a_j, sin a_j)`` in its contact
frame, :mod:`rt_drake.contact._cup`) mapped to ``(x_i f_y - y_i f_x, f_x,
f_y)``. So

    W_shared = {w : 0 <= n_i(w) <= f_max_i,  t(w) in sum_i n_i(w) Q_i}.

For n >= 0 the sum ``S(n) = sum_i n_i Q_i`` is a Minkowski sum of planar
polygons in 3-D; its facet normals are cross products of two polygons' edge
directions, a polygon's plane normal, or an edge crossed with its polygon's
plane normal, whatever n is (scaling a summand keeps its normal fan). With
``h_i`` the support function of Q_i, ``t in S(n)`` reads ``d . t <=
sum_i n_i h_i(d)`` for every such d, linear in w because n(w) is: W_shared
is a polytope whose rows this module writes down directly (a few hundred for
two paper cups, against 47,728 for the free split). It is the set of
wrenches the rims hold while every rim point stays in contact; a wrench
that would lift a point is refused (sound: the model is exact where it
accepts).

Conventions: wrenches ``[torque; force]`` (N*m, N) exerted by the cups on
the object, about T's origin, in T; rows ``F w <= g`` unit-norm, so ``F w -
g`` is a signed distance in raw wrench units.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from rt_drake import arguments
from rt_drake.contact._cup import (
    contact_positions,
    contact_rotations,
)
from rt_drake.contact.tool import (
    LoadSharing,
    ToolParameterError,
    ToolParameters,
    refuse_peel,
)
from rt_drake.contact.wrench_polytope import check_h_representation, is_realizable

#: m and rad: how far a cup may sit off T's z = 0 plane, or tilt its axis
#: from T's z, for the planar spring model.
_PLANAR_TOL = 1e-9
#: Directions closer than this (unit vectors) are one direction.
_SAME_DIRECTION = 1e-9


@dataclasses.dataclass(frozen=True)
class RimSprings:
    """The tool's rim points as equal springs in T's z = 0 plane.

    Attributes:
        positions: (n, 2) m, rim point i at ``(x_i, y_i)`` in T.
        polygons: (n, k_i, 3) per point, its friction polygon Q_i's vertices
            in ``(tau_z, f_x, f_y)`` per newton of normal force (a list when
            cups differ in sides).
        f_max: (n,) N, each point's largest normal force.
        split: (n, 3) ``A (A^T A)^-1``: normal part ``(tau_x, tau_y, f_z)``
            of the rims' wrench -> normal forces.
        suction: (3,) the normal part of the cups' suction wrench.
    """

    positions: np.ndarray
    polygons: list[np.ndarray]
    f_max: np.ndarray
    split: np.ndarray
    suction: np.ndarray

    def normal_forces(self, wrenches: np.ndarray) -> np.ndarray:
        """Return n(w) (..., n), N: the spring split of each (..., 6) wrench."""
        w = np.asarray(wrenches, dtype=float)
        b = w[..., [0, 1, 5]] - self.suction
        return b @ self.split.T


def rim_springs(tool: ToolParameters) -> RimSprings:
    """Return the rim points of ``tool`` as springs (see the module docstring).

    Raises:
        ToolParameterError: a cup off T's z = 0 plane or tilted from T's z
            (the planar model does not hold), or every rim point on one
            line (the split is not unique).
    """
    tool.validate()
    refuse_peel(tool, LoadSharing.ELASTIC)
    positions, polygons, f_max = [], [], []
    suction = np.zeros(3)
    for i, mount in enumerate(tool.cups):
        cup, R, p = mount.cup, mount.R_TC, mount.p_TC
        if abs(p[2]) > _PLANAR_TOL or np.abs(R[:, 2] - [0.0, 0.0, 1.0]).max() > (
            _PLANAR_TOL
        ):
            raise ToolParameterError(
                f"cup {i}: elastic load sharing needs every cup in the tool "
                f"frame's z = 0 plane with its axis along z, got p_TC = "
                f"{p.tolist()}, axis {R[:, 2].tolist()}"
            )
        angles = 2.0 * np.pi * np.arange(cup.sides) / cup.sides
        local = cup.friction * np.stack([np.cos(angles), np.sin(angles)], axis=1)
        for p_CP, R_CP in zip(
            contact_positions(cup), contact_rotations(cup), strict=True
        ):
            x, y = (p + R @ p_CP)[:2]
            t = local @ (R @ R_CP)[:2, :2].T  # tangential forces in T, per N
            polygons.append(
                np.column_stack([x * t[:, 1] - y * t[:, 0], t[:, 0], t[:, 1]])
            )
            positions.append((x, y))
            f_max.append(cup.max_normal_force)
        # Suction -P A along z at (p_x, p_y): torque (-P A p_y, P A p_x, 0).
        pull = cup.suction_force
        suction += np.array([-pull * p[1], pull * p[0], -pull])
    xy = np.array(positions)
    A = np.column_stack([xy[:, 1], -xy[:, 0], np.ones(len(xy))])
    if np.linalg.matrix_rank(A, tol=1e-12 * max(1.0, np.abs(xy).max())) < 3:
        raise ToolParameterError(
            "elastic load sharing needs rim points that are not all on one line"
        )
    split = A @ np.linalg.inv(A.T @ A)
    return RimSprings(
        positions=xy,
        polygons=polygons,
        f_max=np.array(f_max, dtype=float),
        split=split,
        suction=suction,
    )


def facet_directions(polygons: list[np.ndarray]) -> np.ndarray:
    """Return unit directions d (K, 3) holding every facet normal of a sum.

    The sums are ``sum_i n_i Q_i`` for any n >= 0; the directions are both
    signs of edge x edge (two polygons), of each plane normal, and of edge x
    its plane normal, duplicates merged.
    """
    edges, normals, own = [], [], []
    for vertices in polygons:
        polygon_edges = np.roll(vertices, -1, axis=0) - vertices
        normal = np.cross(polygon_edges[0], polygon_edges[1])
        normals.append(normal)
        own += [np.cross(edge, normal) for edge in polygon_edges]
        edges += list(polygon_edges)
    E = _unit(np.array(edges))
    i, j = np.triu_indices(len(E), k=1)
    candidates = np.vstack([np.cross(E[i], E[j]), np.array(normals), np.array(own)])
    candidates = candidates[np.linalg.norm(candidates, axis=1) > 1e-9]
    candidates = _unit(candidates)
    candidates = np.vstack([candidates, -candidates])
    return _unique_directions(candidates)


def shared_load_polytope(tool: ToolParameters) -> tuple[np.ndarray, np.ndarray]:
    """Return ``(F, g)``: W_shared of ``tool`` as unit rows ``F w <= g``.

    Rows: ``-n_i(w) <= 0`` and ``n_i(w) <= f_max`` per rim point, and
    ``d . t(w) - sum_i h_i(d) n_i(w) <= 0`` per direction d of
    :func:`facet_directions` (support ``h_i(d) = max_j d . v_ij``); n(w) is
    affine, ``n(w) = split (S w - suction)``. Rows implied by others are kept
    unless exactly duplicated (the retimer accepts redundant rows).

    Raises:
        ToolParameterError: see :func:`rim_springs`; g <= 0 (the object at
            rest with no load would already lift a rim point).
    """
    arguments.instance(tool, "tool", ToolParameters, where="shared_load_polytope")
    springs = rim_springs(tool)
    split, n0 = springs.split, -springs.split @ springs.suction  # n(0)
    normal_part = np.zeros((3, 6))
    normal_part[[0, 1, 2], [0, 1, 5]] = 1.0
    tangential_part = np.zeros((3, 6))
    tangential_part[[0, 1, 2], [2, 3, 4]] = 1.0
    dn_dw = split @ normal_part  # (n, 6): n(w) = dn_dw w + n0
    rows = [-dn_dw, dn_dw]
    offsets = [n0, springs.f_max - n0]
    directions = facet_directions(springs.polygons)
    support = np.column_stack(
        [np.max(directions @ vertices.T, axis=1) for vertices in springs.polygons]
    )  # (K, n): h_i(d)
    rows.append(directions @ tangential_part - support @ dn_dw)
    offsets.append(support @ n0)
    F = np.vstack(rows)
    g = np.concatenate(offsets)
    norms = np.linalg.norm(F, axis=1)
    F, g = F / norms[:, None], g / norms
    if np.any(g <= 0.0):
        raise ToolParameterError(
            "elastic load sharing: at zero load a rim point carries no normal "
            f"force (smallest n_i(0) = {n0.min():.3g} N); the suction must "
            "press every rim point"
        )
    keep = np.unique(np.round(np.column_stack([F, g]), 12), axis=0, return_index=True)[
        1
    ]
    keep.sort()
    return F[keep], g[keep]


@dataclasses.dataclass(frozen=True)
class SharedLoadSet:
    """W_shared of a tool: rows and a membership test.

    Attributes:
        cup: The tool.
        F: (R, 6) unit rows.
        g: (R,) offsets, > 0.
    """

    cup: ToolParameters
    F: np.ndarray
    g: np.ndarray

    def __post_init__(self) -> None:
        where = "SharedLoadSet"
        arguments.instance(self.cup, "cup", ToolParameters, where=where)
        F, g = check_h_representation(self.F, self.g, where)
        object.__setattr__(self, "F", F)
        object.__setattr__(self, "g", g)

    @classmethod
    def of(cls, tool: ToolParameters) -> SharedLoadSet:
        """Compute the rows of ``tool``'s set (milliseconds)."""
        arguments.instance(tool, "tool", ToolParameters, where="SharedLoadSet.of")
        F, g = shared_load_polytope(tool)
        return cls(cup=tool, F=F, g=g)

    def contains(self, wrenches: np.ndarray, tol: float = 1e-9) -> np.ndarray:
        """Return whether each (..., 6) wrench satisfies ``F w <= g + tol``."""
        return is_realizable(wrenches, self.F, self.g, tol)


def _unit(vectors: np.ndarray) -> np.ndarray:
    return vectors / np.linalg.norm(vectors, axis=1, keepdims=True)


def _unique_directions(directions: np.ndarray) -> np.ndarray:
    """Drop directions within :data:`_SAME_DIRECTION` of an earlier one."""
    rounded = np.round(directions / _SAME_DIRECTION) * _SAME_DIRECTION
    _, first = np.unique(rounded, axis=0, return_index=True)
    return directions[np.sort(first)]


__all__ = [
    "RimSprings",
    "SharedLoadSet",
    "facet_directions",
    "rim_springs",
    "shared_load_polytope",
]
