"""The exact contact wrench set W_c of a suction cup (paper Section II-C).

``W_c = {sum_i G_i f_i + [0, 0, 0, 0, 0, -P A] : f_i in pyramid_i}`` (eqs 8-9,
Assumption 1), in the conventions of :mod:`rt_drake.contact._cup`: wrenches
``[torque; force]`` in N*m and N that the cup exerts on the object, about the
cup frame's origin, expressed in C.

W_c is a Minkowski sum of m pyramids (each ``G_i`` times the bounded friction
cone, apex 0 plus k base vertices) plus a constant, so its facets and vertices
come from :func:`rt_drake.contact._minkowski.minkowski_sum`, using the cup's
symmetry (rotating the wrench by 2 pi/m about z maps contact i onto i + 1).
The enumeration runs in scaled coordinates ``[torque / r; force]`` (all in N)
and the rows are mapped back and normalised: ``F w <= g`` with ``|F_j| = 1``,
so ``F w - g`` is a signed distance in raw wrench units. When mu = 0 the set is
3-dimensional (tau_x, tau_y, f_z): F then starts with +/- row pairs stating
the zero components.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from rt_drake import arguments
from rt_drake.contact._cup import (
    CupParameters,
    contact_rotations,
    friction_pyramid,
    grasp_matrices,
    suction_wrench,
)
from rt_drake.contact._intersection import intersect
from rt_drake.contact._minkowski import minkowski_sum
from rt_drake.contact.exact_cost import DEFAULT_MAX_MEMORY, check_exact_cost
from rt_drake.contact.peel import peel_rows
from rt_drake.contact.tool import ToolParameters
from rt_drake.errors import InputError

#: A row of F whose norm is below this (relative to the largest row) is zero.
ZERO_ROW = 1e-12
#: Relative violation of ``F v <= g`` a vertex may have (rounding).
VERTEX_TOLERANCE = 1e-7


@dataclasses.dataclass(frozen=True)
class WrenchPolytope:
    """Contact wrench set ``W_c = {w : F w <= g} = conv(vertices)``.

    Attributes:
        cup: The parameters it was computed for: a cup (W_c, in the cup frame
            C), or a multi-cup tool (W_T, in the tool frame T, see
            :mod:`rt_drake.contact.tool_polytope`).
        F: (rows, 6) unit rows, one per facet (no redundant or duplicate row).
        g: (rows,) offsets; ``F w - g`` is a signed distance, N*m and N.
        vertices: (count, 6) vertices ``[torque; force]``.
    """

    cup: CupParameters | ToolParameters
    F: np.ndarray
    g: np.ndarray
    vertices: np.ndarray

    def __post_init__(self) -> None:
        """Check the types and shapes (consistency: :func:`check_polytope`)."""
        where = "WrenchPolytope"
        arguments.instance(
            self.cup, "cup", (CupParameters, ToolParameters), where=where
        )
        for name, shape in (
            ("F", ("rows", 6)),
            ("g", ("rows",)),
            ("vertices", ("count", 6)),
        ):
            value = arguments.array(
                getattr(self, name), name, shape, where=where, finite=False
            )
            object.__setattr__(self, name, value)

    def contains(self, wrenches: np.ndarray, tol: float = 1e-9) -> np.ndarray:
        """Return whether each wrench (..., 6) satisfies ``F w <= g + tol``."""
        return is_realizable(wrenches, self.F, self.g, tol)


def is_realizable(
    wrenches: np.ndarray, F: np.ndarray, g: np.ndarray, tol: float = 1e-9
) -> np.ndarray:
    """Return ``all(F w <= g + tol)`` for each wrench of a (..., 6) array.

    Args:
        wrenches: Wrenches ``[torque; force]`` on the object in C, (..., 6),
            finite.
        F: (rows, 6) H-representation matrix: finite, no all-zero row (a zero
            row constrains nothing, so it is a corrupted polytope).
        g: (rows,) offsets, finite.
        tol: Allowed violation, in the units of ``F w`` (distance if |F_j| = 1),
            finite and >= 0.

    Returns:
        A boolean array of shape ``wrenches.shape[:-1]`` (a numpy bool for one
        wrench).

    Raises:
        InputError: a shape, NaN or inf, a zero row of F, or a bad ``tol``
            (array-likes such as lists are accepted).
    """
    where = "is_realizable"
    wrenches = arguments.array(wrenches, "wrenches", ("...", 6), where=where)
    F, g = check_h_representation(F, g, where)
    tol = arguments.number(tol, "tol", where=where, low=0.0)
    flat = wrenches.reshape(-1, F.shape[1])
    inside = np.empty(len(flat), dtype=bool)
    chunk = max(1, 2**22 // max(len(g), 1))  # (chunk, rows) floats: 32 MB
    for start in range(0, len(flat), chunk):
        block = flat[start : start + chunk] @ F.T
        inside[start : start + chunk] = np.all(block <= g + tol, axis=-1)
    return inside.reshape(wrenches.shape[:-1])[()]


def check_h_representation(
    F: np.ndarray, g: np.ndarray, where: str = "wrench polytope"
) -> tuple[np.ndarray, np.ndarray]:
    """Return F and g as arrays if ``F w <= g`` is a well-formed H-representation.

    F is (rows, 6) and finite with at least one row and no all-zero row
    (``0 <= g_j`` accepts every wrench: a corrupted or underflowed row); g is
    (rows,) and finite. Raises InputError naming the argument, prefixed by
    ``where``.
    """
    F = arguments.array(F, "F", ("rows", 6), where=where)
    g = arguments.array(g, "g", ("rows",), where=where)
    if len(g) != len(F):
        raise InputError(
            f"{where}: g must have one offset per row of F ({len(F)}), got {len(g)}"
        )
    norms = np.linalg.norm(F, axis=1)
    if np.any(norms <= ZERO_ROW * max(float(norms.max(initial=0.0)), 1.0)):
        row = int(np.flatnonzero(norms <= ZERO_ROW * max(norms.max(), 1.0))[0])
        raise InputError(
            f"{where}: F row {row} is zero ({F[row].tolist()}): it constrains nothing"
        )
    return F, g


def check_polytope(polytope: WrenchPolytope, tol: float = VERTEX_TOLERANCE) -> None:
    """Raise InputError unless a computed or loaded W_c is consistent.

    The H-representation is well formed (:func:`check_h_representation`),
    the vertices are finite and satisfy it: ``F v <= g + tol * s`` with
    ``s`` the largest |vertex| component (a relative tolerance).
    """
    check_h_representation(polytope.F, polytope.g)
    vertices = np.asarray(polytope.vertices, dtype=float)
    if vertices.ndim != 2 or vertices.shape[1:] != (6,) or len(vertices) == 0:
        raise InputError(f"need vertices (count >= 1, 6), got {vertices.shape}")
    if not np.all(np.isfinite(vertices)):
        raise InputError("the vertices of the wrench polytope are not finite")
    scale = max(float(np.abs(vertices).max()), 1e-300)
    F, g = np.asarray(polytope.F, dtype=float), np.asarray(polytope.g, dtype=float)
    chunk = max(1, 2**22 // max(len(g), 1))  # (chunk, rows) floats: 32 MB
    excess = max(
        float((vertices[i : i + chunk] @ F.T - g).max(initial=0.0))
        for i in range(0, len(vertices), chunk)
    )
    excess /= scale
    if excess > tol:
        raise InputError(
            f"vertices violate their own H-representation by {excess:.3g} "
            f"(relative, tolerance {tol:g}): numerically unreliable for {polytope.cup}"
        )


def with_suction_force(
    polytope: WrenchPolytope, suction_force: float
) -> WrenchPolytope:
    """Return W_c of the same cup with another suction force P' A (N): exact, cheap.

    The suction force enters W_c only as the constant wrench
    ``[0, 0, 0, 0, 0, -P A]`` added to the Minkowski sum of the rim forces
    (module docstring), so changing it translates the set by
    ``d = (P A - P' A) e_z`` (force z component): the rows F stay, the offsets
    become ``g' = g + F d = g + (P A - P' A) F[:, 5]`` and the vertices move by
    d. A weaker vacuum (P' < P) moves the set toward +f_z: less pull.

    Raises:
        InputError: ``suction_force`` not > 0 (the cup parameters' own check),
            or a multi-cup tool's set (each cup has its own suction force).
    """
    where = "with_suction_force"
    arguments.instance(polytope, "polytope", WrenchPolytope, where=where)
    arguments.number(suction_force, "suction_force", where=where)
    if isinstance(polytope.cup, ToolParameters):
        raise InputError(
            "with_suction_force takes one cup's W_c, got a tool's set "
            f"({len(polytope.cup.cups)} cups, each with its own suction force)"
        )
    cup = dataclasses.replace(polytope.cup, suction_force=float(suction_force))
    shift = polytope.cup.suction_force - cup.suction_force
    return WrenchPolytope(
        cup=cup,
        F=polytope.F,
        g=polytope.g + shift * polytope.F[:, 5],
        vertices=polytope.vertices + np.array([0.0] * 5 + [shift]),
    )


def wrench_scale(cup: CupParameters | ToolParameters) -> np.ndarray:
    """Return the diagonal S with ``S w = [torque / L; force]`` (all in N).

    L is the cup's radius r, or a tool's ``length_scale`` (``max |p_TCi| +
    r_i``, which is r for one cup at the tool frame's origin).
    """
    length = cup.length_scale if isinstance(cup, ToolParameters) else cup.radius
    return np.array([1.0 / length] * 3 + [1.0] * 3)


def rotation_symmetry(cup: CupParameters) -> np.ndarray:
    """Return the (6, 6) map of a wrench rotated by 2 pi/m about C's z."""
    symmetry = np.zeros((6, 6))
    symmetry[:3, :3] = symmetry[3:, 3:] = contact_rotations(cup)[1 % cup.points]
    return symmetry


def contact_wrench_polytope(
    cup: CupParameters, max_memory: float = DEFAULT_MAX_MEMORY
) -> WrenchPolytope:
    """Compute the exact W_c of a cup: minimal H-rep and vertices.

    The paper's cup (m = 6, mu = 0.3, k = 4, 33.3 N, 20 N) gives 834 facets
    and 1779 vertices. A cup with ``peel_fraction`` gets the rim's set
    intersected with the lip's peel rows (:mod:`rt_drake.contact.peel`):
    the rows of both that are facets, and the vertices of the intersection.
    The cost is estimated first
    (:func:`rt_drake.contact.exact_cost.exact_cost`) and the result checked
    (:func:`check_polytope`).

    Args:
        cup: The cup model.
        max_memory: Bytes the enumeration may use (estimated up front, then
            counted before the largest allocation).

    Raises:
        InputError: a parameter out of range, or a result that is not a
            consistent polytope.
        TooLargeError: the estimate exceeds ``max_memory`` (the message gives
            the estimate and the largest accepted points and sides).
    """
    where = "contact_wrench_polytope"
    arguments.instance(cup, "cup", CupParameters, where=where)
    arguments.number(max_memory, "max_memory", where=where, above=0.0)
    cup.validate()
    if cup.peel_fraction is not None:
        rim = contact_wrench_polytope(
            dataclasses.replace(cup, peel_fraction=None), max_memory
        )
        peel_F, peel_g = peel_rows(cup)
        F, g, vertices = intersect(
            np.vstack([rim.F, peel_F]),
            np.concatenate([rim.g, peel_g]),
            wrench_scale(cup),
        )
        polytope = WrenchPolytope(cup=cup, F=F, g=g, vertices=vertices)
        check_polytope(polytope)
        return polytope
    check_exact_cost(cup, max_memory)
    scale = wrench_scale(cup)
    pyramid = friction_pyramid(cup)
    summands = [(pyramid @ G.T) * scale for G in grasp_matrices(cup)]
    exact = minkowski_sum(
        summands,
        suction_wrench(cup) * scale,
        symmetry=rotation_symmetry(cup),
        max_memory=max_memory,
    )
    F = exact.F * scale  # (a . S w <= b) reads ((a S) . w <= b)
    norms = np.linalg.norm(F, axis=1)
    polytope = WrenchPolytope(
        cup=cup,
        F=F / norms[:, None],
        g=exact.g / norms,
        vertices=exact.vertices / scale,
    )
    check_polytope(polytope)
    return polytope
