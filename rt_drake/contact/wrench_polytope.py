"""The exact contact wrench set W_c of a suction cup (paper Section II-C).

``W_c = {sum_i G_i f_i + [0, 0, 0, 0, 0, -P A] : f_i in pyramid_i}`` (eqs 8-9,
Assumption 1), in the conventions of :mod:`rt_drake.contact.cup`: wrenches
``[torque; force]`` in N*m and N that the cup exerts on the object, about the
cup frame's origin, expressed in C.

W_c is a Minkowski sum of m pyramids (each ``G_i`` times the bounded friction
cone, apex 0 plus k base vertices) plus a constant, so its facets and vertices
come from :func:`rt_drake.contact.minkowski.minkowski_sum`, using the cup's
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

from rt_drake.contact.cup import (
    CupParameters,
    contact_rotations,
    friction_pyramid,
    grasp_matrices,
    suction_wrench,
)
from rt_drake.contact.minkowski import minkowski_sum
from rt_drake.contact.tool import ToolParameters


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

    def contains(self, wrenches: np.ndarray, tol: float = 1e-9) -> np.ndarray:
        """Return whether each wrench (..., 6) satisfies ``F w <= g + tol``."""
        return is_realizable(wrenches, self.F, self.g, tol)


def is_realizable(
    wrenches: np.ndarray, F: np.ndarray, g: np.ndarray, tol: float = 1e-9
) -> np.ndarray:
    """Return ``all(F w <= g + tol)`` for each wrench of a (..., 6) array.

    Args:
        wrenches: Wrenches ``[torque; force]`` on the object in C, (..., 6).
        F: (rows, 6) H-representation matrix.
        g: (rows,) offsets.
        tol: Allowed violation, in the units of ``F w`` (distance if |F_j| = 1).

    Returns:
        A boolean array of shape ``wrenches.shape[:-1]`` (a numpy bool for one
        wrench).
    """
    wrenches = np.asarray(wrenches, dtype=float)
    if wrenches.shape[-1:] != (F.shape[1],):
        raise ValueError(f"{wrenches.shape=} but {F.shape=}: need (..., 6) wrenches")
    return np.all(wrenches @ F.T <= g + tol, axis=-1)


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


def contact_wrench_polytope(cup: CupParameters) -> WrenchPolytope:
    """Compute the exact W_c of a cup: minimal H-rep and vertices.

    The paper's cup (m = 6, mu = 0.3, k = 4, 33.3 N, 20 N) gives 834 facets
    and 1779 vertices.
    """
    cup.validate()
    scale = wrench_scale(cup)
    pyramid = friction_pyramid(cup)
    summands = [(pyramid @ G.T) * scale for G in grasp_matrices(cup)]
    exact = minkowski_sum(
        summands, suction_wrench(cup) * scale, symmetry=rotation_symmetry(cup)
    )
    F = exact.F * scale  # (a . S w <= b) reads ((a S) . w <= b)
    norms = np.linalg.norm(F, axis=1)
    return WrenchPolytope(
        cup=cup,
        F=F / norms[:, None],
        g=exact.g / norms,
        vertices=exact.vertices / scale,
    )
