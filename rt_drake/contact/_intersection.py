"""The intersection of a wrench polytope with more half-spaces: rows and vertices.

``P' = {w : F w <= g} ∩ {w : A w <= b}``, both with the zero wrench strictly
inside (g > 0, b > 0), is computed by Qhull's half-space intersection
(scipy's ``HalfspaceIntersection``, the dual convex hull) in scaled
coordinates ``S w = [torque / r; force]`` (all in N, so the rows are well
conditioned). The vertices are Qhull's intersection points, merged when
closer than :data:`MERGE` (relative); a row is a facet when the vertices on
it (``F_j v >= g_j - tol``) span a 5-dimensional affine hull. A row that is
not is dropped only once an LP shows it redundant (``max F_j w`` over the
other rows is at most ``g_j``), so the rows never lose a constraint even if
Qhull, which merges facets on these degenerate inputs, missed a vertex: that
is an error instead. The result is a minimal H-representation and its
vertices.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import linprog
from scipy.spatial import HalfspaceIntersection

from rt_drake.errors import InputError

#: Relative distance below which two intersection points are one vertex, and
#: a vertex lies on a row.
MERGE = 1e-9
#: Qhull's options: scipy's default for 6 dimensions (``Qx``) and ``Q12``,
#: which lets Qhull merge the wide facets of these degenerate inputs (the
#: octagon's rows meet the rim's edges) instead of stopping.
QHULL_OPTIONS = "Qx Q12"
#: Relative excess of an LP's optimum over a row's offset that shows the row
#: is not redundant.
LP_TOLERANCE = 1e-7
#: Singular value (relative) below which the vertices on a row are degenerate.
RANK_TOLERANCE = 1e-9


def intersect(
    F: np.ndarray, g: np.ndarray, scale: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Return ``(F', g', vertices)`` of ``{w : F w <= g}`` (a bounded polytope).

    Args:
        F: (rows, 6) rows in raw wrench units (redundant rows allowed).
        g: (rows,) offsets.
        scale: (6,) the diagonal S of the scaled coordinates.

    Returns:
        F' unit rows (one per facet), g' and the (count, 6) vertices, in raw
        wrench units.
    """
    scaled = F / scale  # F w = (F S^-1)(S w)
    norms = np.linalg.norm(scaled, axis=1)
    scaled, offsets = scaled / norms[:, None], g / norms
    hull = HalfspaceIntersection(
        np.hstack([scaled, -offsets[:, None]]),
        _interior_point(scaled, offsets),
        qhull_options=QHULL_OPTIONS,
    )
    points = hull.intersections
    size = max(float(np.abs(points).max()), 1.0)
    _, first = np.unique(np.round(points / (MERGE * size)), axis=0, return_index=True)
    points = points[np.sort(first)]
    on_row = scaled @ points.T >= offsets[:, None] - MERGE * size
    facet = np.array([_is_facet(points[on_row[j]], F.shape[1]) for j in range(len(F))])
    for j in np.flatnonzero(~facet):
        others = facet.copy()
        others[j] = False
        _check_redundant(scaled[others], offsets[others], scaled[j], offsets[j])
    keep = np.flatnonzero(facet)
    rows = scaled[keep] * scale  # back to raw units, then unit rows
    row_norms = np.linalg.norm(rows, axis=1)
    return rows / row_norms[:, None], offsets[keep] / row_norms, points / scale


def _interior_point(F: np.ndarray, g: np.ndarray) -> np.ndarray:
    """A point strictly inside ``F x <= g`` (unit rows).

    0, or the centre of the largest ball inside (an LP) when 0 is not
    strictly inside.

    Raises:
        InputError: the set has no interior (the rows leave no wrench).
    """
    if np.all(g > 0.0):
        return np.zeros(F.shape[1])
    # max t  s.t.  F x + t <= g  (|F_j| = 1): the ball of radius t at x.
    cost = np.zeros(F.shape[1] + 1)
    cost[-1] = -1.0
    A = np.hstack([F, np.ones((len(F), 1))])
    result = linprog(cost, A_ub=A, b_ub=g, bounds=(None, None), method="highs")
    if result.status != 0 or result.x[-1] <= LP_TOLERANCE * max(g.max(), 1.0):
        raise InputError(
            "intersect: the rows leave no wrench (the set has no interior)"
        )
    return np.asarray(result.x[:-1])


def _is_facet(points: np.ndarray, dimension: int) -> bool:
    """Whether ``points`` span an affine hull of ``dimension - 1``."""
    if len(points) < dimension:
        return False
    spread = points[1:] - points[0]
    singular = np.linalg.svd(spread, compute_uv=False)
    return bool(singular[dimension - 2] > RANK_TOLERANCE * max(singular[0], 1.0))


def _check_redundant(
    F: np.ndarray, g: np.ndarray, row: np.ndarray, offset: float
) -> None:
    """Raise InputError unless ``max row . w`` over ``F w <= g`` is <= offset."""
    result = linprog(-row, A_ub=F, b_ub=g, bounds=(None, None), method="highs")
    if result.status != 0 or -result.fun > offset * (1.0 + LP_TOLERANCE):
        raise InputError(
            "intersect: a row with too few vertices on it is not redundant "
            f"(LP status {result.status}): the vertex enumeration is unreliable"
        )
