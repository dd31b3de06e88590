"""The exact wrench set W_T of a multi-cup tool, in the tool frame T.

With the conventions of :mod:`rt_drake.contact.tool` (wrenches
``[torque; force]`` in N*m and N, exerted by the cups on the object, about
T's origin, expressed in T), cup i can exert exactly its set W_ci mapped by
its adjoint, and the cups act together, so

    W_T = sum_i Ad_i W_ci
        = {sum_i sum_j Ad_i G_ij f_ij + sum_i Ad_i [0, 0, 0, 0, 0, -P_i A_i]}

with every rim force f_ij in its cup's bounded friction pyramid. It is a
Minkowski sum of all cups' rim pyramids, each mapped by ``Ad_i G_ij``, plus
the sum of the mapped suction wrenches: its facets and vertices come from
:func:`rt_drake.contact._adjacency.minkowski_sum_walk`, in scaled coordinates
``[torque / L; force]`` with L = :attr:`ToolParameters.length_scale`, the
rows then mapped back and normalised (``F w - g`` is a signed distance in
raw wrench units).

One cup: W_T is that cup's exact W_c (:func:`contact_wrench_polytope`, with
its m-fold symmetry) mapped by its pose: ``w_T = Ad w_C``, so the rows are
``F_C Ad^-1`` (renormalised) and the vertices ``Ad v``. At T's origin that is
W_c itself.

Symmetry: if a rotation Q about T's z axis (by 2 pi/k) maps every cup's rim
pyramids onto rim pyramids of the tool (same parameters, poses related by Q
up to each cup's own m-fold symmetry) and fixes the suction wrench, the walk
uses the wrench rotation ``blockdiag(Q, Q)``; it is checked, never assumed.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from rt_drake import arguments
from rt_drake.contact._adjacency import minkowski_sum_walk
from rt_drake.contact._cup import (
    friction_pyramid,
    grasp_matrices,
    suction_wrench,
)
from rt_drake.contact._lp import is_realizable_lp
from rt_drake.contact.exact_cost import DEFAULT_MAX_MEMORY
from rt_drake.contact.tool import (
    LoadSharing,
    ToolParameters,
    is_identity_pose,
    refuse_peel,
)
from rt_drake.contact.wrench_polytope import (
    WrenchPolytope,
    contact_wrench_polytope,
    wrench_scale,
)

#: Relative tolerance (times the tool's largest wrench) of the symmetry test.
_SYMMETRY_TOL = 1e-9
#: Default facet limit of the exact W_T of several cups: two paper cups have
#: 47,728 facets (about 1 min); four have more than 1.5 million (> 20 min).
DEFAULT_MAX_FACETS = 200_000


def tool_summands(tool: ToolParameters) -> tuple[list[np.ndarray], np.ndarray]:
    """Return the rim pyramids mapped to T and the total suction wrench.

    Returns:
        One (k_i + 1, 6) array per rim point of every cup: the wrenches
        ``Ad_i G_ij f`` about T's origin in T for the pyramid's vertices f
        (apex 0, then the k_i base vertices), and the (6,) wrench
        ``sum_i Ad_i [0, 0, 0, 0, 0, -P_i A_i]``.
    """
    arguments.instance(tool, "tool", ToolParameters, where="tool_summands")
    summands, offset = [], np.zeros(6)
    for mount in tool.cups:
        adjoint = mount.adjoint()
        pyramid = friction_pyramid(mount.cup)
        summands += [pyramid @ (adjoint @ G).T for G in grasp_matrices(mount.cup)]
        offset = offset + adjoint @ suction_wrench(mount.cup)
    return summands, offset


def _maps_onto(summands: list[np.ndarray], symmetry: np.ndarray, atol: float) -> bool:
    """Return True if ``symmetry`` maps every summand onto a summand."""
    unused = list(range(len(summands)))
    for points in summands:
        image = points @ symmetry.T
        for t in unused:
            target = summands[t]
            if len(target) == len(image):
                gap = np.linalg.norm(image[:, None] - target[None], axis=2)
                if np.all(gap.min(axis=1) <= atol) and np.all(gap.min(axis=0) <= atol):
                    unused.remove(t)
                    break
        else:
            return False
    return True


def tool_symmetry(tool: ToolParameters) -> np.ndarray | None:
    """Return ``blockdiag(Q, Q)`` for the largest-order valid rotation, or None.

    Q is the rotation by ``2 pi/k`` about T's z axis, k from the total number
    of rim points down to 2; it is valid when it maps the set of rim pyramids
    (in T) onto itself and fixes the suction wrench.
    """
    arguments.instance(tool, "tool", ToolParameters, where="tool_symmetry")
    summands, offset = tool_summands(tool)
    extent = max(float(np.abs(np.vstack(summands)).max()), float(np.abs(offset).max()))
    atol = _SYMMETRY_TOL * max(extent, 1.0)
    for k in range(sum(m.cup.points for m in tool.cups), 1, -1):
        c, s = np.cos(2.0 * np.pi / k), np.sin(2.0 * np.pi / k)
        Q = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
        symmetry = np.zeros((6, 6))
        symmetry[:3, :3] = symmetry[3:, 3:] = Q
        if np.abs(symmetry @ offset - offset).max() <= atol and _maps_onto(
            summands, symmetry, atol
        ):
            return symmetry
    return None


def tool_wrench_polytope(
    tool: ToolParameters,
    max_facets: int | None = DEFAULT_MAX_FACETS,
    max_memory: float = DEFAULT_MAX_MEMORY,
) -> WrenchPolytope:
    """Compute the exact W_T of a tool: minimal H-rep and vertices, in T.

    The result's ``cup`` attribute is ``tool``. One cup at T's origin gives
    exactly :func:`contact_wrench_polytope` of that cup (834 rows, 1779
    vertices for the paper's cup); two paper cups 0.12 m apart, 47,728 rows.

    Args:
        tool: The tool.
        max_facets: Stop with :class:`TooManyFacetsError` (a
            ``TooLargeError``) once the walk has found more facets than this
            (None: no limit).
        max_memory: Bytes a single cup's enumeration may use (see
            :func:`contact_wrench_polytope`).
    """
    where = "tool_wrench_polytope"
    arguments.instance(tool, "tool", ToolParameters, where=where)
    if max_facets is not None:
        arguments.integer(max_facets, "max_facets", where=where, low=1)
    arguments.number(max_memory, "max_memory", where=where, above=0.0)
    tool.validate()
    if len(tool.cups) == 1:
        mount = tool.cups[0]
        cup = contact_wrench_polytope(mount.cup, max_memory)
        if is_identity_pose(mount):
            return WrenchPolytope(cup=tool, F=cup.F, g=cup.g, vertices=cup.vertices)
        adjoint = mount.adjoint()
        F = np.linalg.solve(adjoint.T, cup.F.T).T  # F_C Ad^-1
        norms = np.linalg.norm(F, axis=1)
        return WrenchPolytope(
            cup=tool,
            F=F / norms[:, None],
            g=cup.g / norms,
            vertices=cup.vertices @ adjoint.T,
        )
    refuse_peel(tool, LoadSharing.ANY)
    scale = wrench_scale(tool)
    summands, offset = tool_summands(tool)
    exact = minkowski_sum_walk(
        [s * scale for s in summands],
        offset * scale,
        symmetry=tool_symmetry(tool),
        max_facets=max_facets,
    )
    F = exact.F * scale  # (a . S w <= b) reads ((a S) . w <= b)
    norms = np.linalg.norm(F, axis=1)
    return WrenchPolytope(
        cup=tool,
        F=F / norms[:, None],
        g=exact.g / norms,
        vertices=exact.vertices / scale,
    )


@dataclasses.dataclass(frozen=True)
class ToolWrenchSet:
    """W_T without its facets: a support function and a membership LP.

    For tools whose exact H-representation is too large to compute or use;
    :func:`rt_drake.contact.guided_approximation` builds a sound inner
    approximation from it.

    Attributes:
        cup: The tool (named like :attr:`WrenchPolytope.cup`).
    """

    cup: ToolParameters

    def __post_init__(self) -> None:
        arguments.instance(self.cup, "cup", ToolParameters, where="ToolWrenchSet")

    def support(self, directions: np.ndarray) -> np.ndarray:
        """Return a point of W_T maximising ``u . w`` for each direction (K, 6).

        ``h(u) = sum_s max_j u . v_sj + u . offset`` over the rim pyramids'
        vertices in T: the maximiser (one vertex per pyramid) is a vertex of
        W_T for a generic u, and in W_T always.
        """
        summands, offset = tool_summands(self.cup)
        directions = arguments.array(
            directions, "directions", ("...", 6), where="ToolWrenchSet.support"
        )
        directions = np.atleast_2d(directions)
        points = np.tile(offset, (len(directions), 1))
        for vertices in summands:
            points += vertices[np.argmax(directions @ vertices.T, axis=1)]
        return points

    def contains(self, wrenches: np.ndarray, tol: float = 1e-8) -> np.ndarray:
        """Return whether each (..., 6) wrench is in W_T: LP residual <= tol."""
        return is_realizable_lp(wrenches, self.cup, tol)
