"""Which rows of the grasp polytope the stage LPs get, and the exactness check.

At grid point ``s_i`` the grasp constraint ``F (a u + b x + c) <= g`` is a
set of half-planes in the (u, x) plane, ``alpha_k u + beta_k x <= delta_k``
with ``alpha = F a``, ``beta = F b`` and ``delta = g - F c`` (the slack at
rest, > 0). Of the polytope's hundreds of rows only a few dozen bound these
2-D slices anywhere along a path.

:func:`grasp_candidates` selects them by ray shooting at every
``stride``-th grid point (float32, a selection and not a proof): from rest
(0, 0) along +x to ``x_top``, then from (0, h x_top) along +u and -u for h in
:data:`RAY_HEIGHTS`. The first row hit along a ray from a point where every
slack ``r_k`` is positive is the one maximising ``(alpha_k d_u + beta_k d_x)
/ r_k``. The union over grid points is handed to the stage LPs at every grid
point.

:func:`grasp_violations` then evaluates every row at every (u, x) the stage
LPs chose, both interpolation blocks, so that rows the selection missed are
found (the retimer adds them and solves again).
"""

from __future__ import annotations

import numpy as np

#: Heights, as fractions of the height x_top reached from rest along +x, of
#: the +u and -u rays.
RAY_HEIGHTS = (0.0, 0.5, 0.9)

#: Grid stride of the ray shooting (the selection is shared by all points).
RAY_STRIDE = 2

#: Float32 screening margin of :func:`grasp_violations` (relative).
SCREEN = 1e-5


def grasp_rest_slack(c: np.ndarray, F: np.ndarray, g: np.ndarray) -> np.ndarray:
    """Slack ``g - F c`` (G, R) of every grasp row with the robot at rest.

    Float32, then float64 for every grid point with a slack within float32
    rounding of zero (so the sign of each slack is exact).
    """
    slack = row_products(c, F)
    np.subtract(g.astype(np.float32), slack, out=slack)
    margin = SCREEN * (1.0 + g.max() + np.abs(c).sum(axis=1))
    unsure = np.flatnonzero(slack.min(axis=1) <= margin)
    if unsure.size:
        slack = slack.astype(np.float64)
        slack[unsure] = g - np.einsum("gj,kj->gk", c[unsure], F)
    return slack


def grasp_candidates(
    a: np.ndarray,
    b: np.ndarray,
    rest_slack: np.ndarray,
    F: np.ndarray,
    x_cap: np.ndarray,
    stride: int = RAY_STRIDE,
) -> np.ndarray:
    """Return the sorted indices of the grasp rows selected by ray shooting.

    Args:
        a: (G, 6) wrench coefficients of u.
        b: (G, 6) wrench coefficients of x.
        rest_slack: (G, R) ``g - F c``, all > 0.
        F: (R, 6) grasp rows.
        x_cap: (G,) velocity bound on x (caps x_top).
        stride: Shoot at every ``stride``-th grid point.
    """
    alpha, beta = np.split(row_products(np.vstack([a[::stride], b[::stride]]), F), 2)
    slack = np.ascontiguousarray(rest_slack[::stride], dtype=np.float32)
    points = np.arange(len(slack))
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        ratio = np.divide(beta, slack)  # one (G / stride, R) buffer, reused
        top = ratio.argmax(axis=1)
        x_top = np.minimum(
            slack[points, top] / beta[points, top], x_cap[::stride].astype(np.float32)
        )
        lift = np.multiply(beta, x_top[:, None], out=beta)
        hits = [top]
        for height in RAY_HEIGHTS:
            if height:  # alpha / (slack - height lift)
                np.multiply(lift, np.float32(height), out=ratio)
                np.subtract(slack, ratio, out=ratio)
                np.divide(alpha, ratio, out=ratio)
            else:
                np.divide(alpha, slack, out=ratio)
            hits += [ratio.argmax(axis=1), ratio.argmin(axis=1)]
    return np.unique(np.concatenate(hits))


def grasp_violations(
    a: np.ndarray,
    b: np.ndarray,
    c: np.ndarray,
    F: np.ndarray,
    g: np.ndarray,
    u: np.ndarray,
    x: np.ndarray,
    ds: np.ndarray,
    tol: float,
) -> np.ndarray:
    """Indices of the grasp rows violated where the stage LPs enforced them.

    Stage i (i < N) enforced ``s_i`` at ``(u_i, x_i)`` and ``s_{i+1}`` at
    ``(u_i, x_i + 2 ds_i u_i)``. Each of the 2N wrenches is screened against
    every row of F in float32, keeping the rows within ``SCREEN (1 + max g +
    max |w|_1)`` of their bound (well above float32 rounding), and the kept
    pairs are evaluated exactly in float64.

    Returns:
        Sorted rows with ``F_k w - g_k > tol`` (N or N m) at some stage.
    """
    x_next = x[:-1] + 2.0 * ds * u
    w_here = a[:-1] * u[:, None] + b[:-1] * x[:-1, None] + c[:-1]
    w_next = a[1:] * u[:, None] + b[1:] * x_next[:, None] + c[1:]
    wrenches = np.vstack([w_here, w_next])  # (2N, 6)
    # One margin for all wrenches (the largest): a comparison with a row
    # vector, with no (2N, R) temporary for the slack.
    margin = SCREEN * (1.0 + g.max() + np.abs(wrenches).sum(axis=1).max())
    near = np.flatnonzero(row_products(wrenches, F) > (g - margin).astype(np.float32))
    column, row = np.divmod(near, F.shape[0])  # (np.nonzero is slow in 2-D)
    excess = np.einsum("ij,ij->i", F[row], wrenches[column]) - g[row]
    return np.unique(row[excess > tol])


def row_products(vectors: np.ndarray, F: np.ndarray) -> np.ndarray:
    """``vectors @ F.T`` in float32 by einsum, (M, 6) x (R, 6) -> (M, R).

    einsum's own loop, not BLAS: on a busy 2-core machine OpenBLAS's threads
    made this product 10 to 50 times slower (CPU and wall time).
    """
    return np.einsum(
        "mj,jr->mr", vectors.astype(np.float32), np.ascontiguousarray(F.T, np.float32)
    )


__all__ = [
    "RAY_HEIGHTS",
    "RAY_STRIDE",
    "SCREEN",
    "grasp_candidates",
    "grasp_rest_slack",
    "grasp_violations",
    "row_products",
]
