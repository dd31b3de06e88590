"""Which rows of the grasp polytope the stage LPs get, and the exactness check.

At grid point ``s_i`` the grasp constraint ``F (a u + b x + c) <= g`` is a
set of half-planes in the (u, x) plane, ``alpha_k u + beta_k x <= delta_k``
with ``alpha = F a``, ``beta = F b`` and ``delta = g - F c`` (the slack at
rest, > 0). Of the polytope's hundreds of rows only a few dozen bound these
2-D slices anywhere along a path.

Both functions run compiled (numba) in float64 over the normalised rows
``n_k = F_k / g_k`` (so row k reads ``n_k w <= 1``):

- :func:`rest_and_candidates` checks every row at rest at every grid point
  (``n_k c_i < 1``) and selects rows by ray shooting at every ``stride``-th
  grid point: from rest (0, 0) along +x to ``x_top`` (capped by the velocity
  bound), then from (0, h x_top) along +u and -u for h in
  :data:`RAY_HEIGHTS`. From a point where every row's slack ``r_k`` is
  positive, the first row hit along a direction ``(d_u, d_x)`` is the one
  maximising ``(alpha_k d_u + beta_k d_x) / r_k``. The union over grid points
  is handed to the stage LPs at every grid point. A selection, not a proof:
- :func:`wrench_ratios` evaluates every row at every wrench the stage LPs
  enforced; rows the selection missed are found there (the retimer adds them
  and solves again).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from rt_drake.retiming._row_groups import (
    RowGroups,
    group_rows,
    grouped_ratios,
)
from rt_drake.retiming.seidel import kernel_array

#: Heights, as fractions of the height x_top reached from rest along +x, of
#: the +u and -u rays.
RAY_HEIGHTS = np.array([0.0, 0.5, 0.9])

#: Grid stride of the ray shooting (the selection is shared by all points).
RAY_STRIDE = 2


def normalised_rows(F: np.ndarray, g: np.ndarray) -> np.ndarray:
    """``(F / g)ᵀ`` as a (6, R) C-contiguous array (row k reads ``n_k w <= 1``)."""
    return np.ascontiguousarray((F / np.asarray(g)[:, None]).T, dtype=np.float64)


def rest_and_candidates(
    a: np.ndarray,
    b: np.ndarray,
    c: np.ndarray,
    normals: np.ndarray,
    x_cap: np.ndarray,
    stride: int = RAY_STRIDE,
) -> tuple[np.ndarray, np.ndarray]:
    """Check the grasp at rest and select rows by ray shooting.

    Args:
        a: (G, 6) wrench per unit u (``w = a u + b x + c``).
        b: (G, 6) wrench per unit x.
        c: (G, 6) wrench at rest.
        normals: (6, R) from :func:`normalised_rows`.
        x_cap: (G,) velocity bound on x (caps x_top).
        stride: Shoot at every ``stride``-th grid point.

    Returns:
        rest: (G,) ``max_k n_k c_i``; the object is held at rest at ``s_i``
            iff it is < 1.
        rows: Sorted indices of the selected rows (none if some rest >= 1).
    """
    rest = np.empty(len(c))
    selected = np.zeros(normals.shape[1], dtype=np.bool_)
    _rest_and_rays(
        *(kernel_array(v) for v in (a, b, c)),
        normals,
        kernel_array(x_cap),
        int(stride),
        RAY_HEIGHTS,
        rest,
        selected,
    )
    return rest, np.flatnonzero(selected)


def wrench_ratios(
    wrenches: np.ndarray,
    normals: np.ndarray,
    g: np.ndarray,
    tol: float,
    floor: float = -np.inf,
    groups: RowGroups | None = None,
    exact: int | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Evaluate every grasp row at every wrench (rows far below skipped).

    Rows are grouped in boxes (:mod:`._row_groups`); a group that can hold
    neither a wrench's largest value nor a value above ``floor`` is skipped
    at that wrench, which changes none of the results below (nor does the
    grouping: any grouping of these rows gives the same results).

    Args:
        wrenches: (M, 6) wrenches on the object (N m, N).
        normals: (6, R) from :func:`normalised_rows`.
        g: (R,) the rows' offsets.
        tol: Excess (N or N m, >= 0) above which a row counts as violated.
        floor: ``row_max`` is exact where above it (at most 1; -inf: for
            every row).
        groups: The rows grouped by :func:`wrench_groups` (to reuse them
            across calls); None: grouped here for these wrenches.
        exact: Only the first ``exact`` wrenches need their ``ratio`` (None:
            all); at the others only rows above ``floor`` are looked for
            (the same ``violated`` and ``row_max``, in fewer products).

    Returns:
        ratio: (M,) ``max_k n_k w`` (<= 1: the wrench is in the polytope);
            past the first ``exact`` wrenches, that where above ``floor``,
            else at most ``floor``.
        violated: Sorted rows with ``g_k (n_k w - 1) > tol`` at some wrench.
        row_max: (R,) ``max_w n_k w`` of each row over the wrenches where
            that is above ``floor``; at most ``floor`` for the others.
    """
    if not tol >= 0.0:
        raise ValueError(f"tol must be >= 0, got {tol}")
    wrenches = kernel_array(wrenches)
    if groups is None:
        groups = wrench_groups(wrenches, normals, g)
    ratio = np.empty(len(wrenches))
    violated = np.zeros(len(g), dtype=np.bool_)
    row_max = np.empty(len(g))
    count = len(wrenches) if exact is None else min(int(exact), len(wrenches))
    grouped_ratios(
        wrenches,
        groups,
        float(tol),
        min(float(floor), 1.0),
        count,
        ratio,
        violated,
        row_max,
    )
    return ratio, np.flatnonzero(violated), row_max


def wrench_groups(
    wrenches: np.ndarray, normals: np.ndarray, g: np.ndarray
) -> RowGroups:
    """The grasp rows grouped for :func:`wrench_ratios` at such wrenches.

    The wrenches only weight the split (by each coordinate's magnitude), so
    the groups serve as well for other wrenches of the same path.
    """
    scale = np.abs(wrenches).max(axis=0) if len(wrenches) else np.ones(6)
    return group_rows(normals, kernel_array(g), kernel_array(scale))


@njit(cache=True)
def _products(n, w0, w1, w2, w3, w4, w5, out):
    """``out[k] = n[:, k] . w`` for every row k."""
    for k in range(n.shape[1]):
        out[k] = (
            n[0, k] * w0
            + n[1, k] * w1
            + n[2, k] * w2
            + n[3, k] * w3
            + n[4, k] * w4
            + n[5, k] * w5
        )


#: Skipping a division (:func:`_argmax_ratio`, :func:`_side_hits`): a row
#: with ``d > 1e-290`` and ``num <= best' d (1 - 2^-50)`` (as computed)
#: cannot beat ``best``, where ``best' = best`` if it is at least 1e-290,
#: else 0. Then ``num / d <= best (1 - 5u)`` (u the unit roundoff; an
#: underflow in the products adds at most 5e-324 / d), which rounds below
#: ``best``, or ``num <= 0``: the row found is the one dividing every row
#: would find, with a fraction of the divisions.
_SHRINK = 1.0 - 2.0**-50
_NORMAL = 1e-290


@njit(cache=True)
def _argmax_ratio(num, den):
    """First k maximising ``num[k] / den[k]`` among the positive ones (else -1).

    Divides only the rows that can beat the best so far (see ``_SHRINK``).
    """
    hit, best, scale = -1, 0.0, 0.0
    for k in range(num.shape[0]):
        d = den[k]
        if d > _NORMAL and num[k] <= scale * d * _SHRINK:
            continue
        value = num[k] / d
        if value > best:
            hit, best = k, value
            scale = best if best >= _NORMAL else 0.0
    return hit


@njit(cache=True)
def _side_hits(alpha, beta, slack, lifts, selected):
    """Mark the rows maximising and minimising ``alpha / (slack - lift beta)``.

    For every lift (rays along +u and -u from (0, lift)); only positive
    maxima count (none: that ray hits nothing). Divides only the rows that
    can beat the running extremes (see ``_SHRINK``).
    """
    for j in range(lifts.shape[0]):
        lift = lifts[j]
        plus, minus = -1, -1
        best_plus = best_minus = scale_plus = scale_minus = 0.0
        for k in range(alpha.shape[0]):
            d = slack[k] - lift * beta[k]
            top = alpha[k]
            if (
                d > _NORMAL
                and top <= scale_plus * d * _SHRINK
                and -top <= scale_minus * d * _SHRINK
            ):
                continue
            value = top / d
            if value > best_plus:
                plus, best_plus = k, value
                scale_plus = best_plus if best_plus >= _NORMAL else 0.0
            if -value > best_minus:
                minus, best_minus = k, -value
                scale_minus = best_minus if best_minus >= _NORMAL else 0.0
        if plus >= 0:
            selected[plus] = True
        if minus >= 0:
            selected[minus] = True


@njit(cache=True)
def _rest_and_rays(a, b, c, n, x_cap, stride, heights, rest, selected):
    rows = n.shape[1]
    slack = np.empty(rows)
    alpha = np.empty(rows)
    beta = np.empty(rows)
    held = True
    for i in range(c.shape[0]):
        _products(n, c[i, 0], c[i, 1], c[i, 2], c[i, 3], c[i, 4], c[i, 5], slack)
        worst = -np.inf
        for k in range(rows):
            if slack[k] > worst:
                worst = slack[k]
            slack[k] = 1.0 - slack[k]
        rest[i] = worst
        held = held and worst < 1.0
        if not held or i % stride:
            continue
        _products(n, a[i, 0], a[i, 1], a[i, 2], a[i, 3], a[i, 4], a[i, 5], alpha)
        _products(n, b[i, 0], b[i, 1], b[i, 2], b[i, 3], b[i, 4], b[i, 5], beta)
        # Along +x from rest: the first row hit maximises beta / slack.
        top = _argmax_ratio(beta, slack)
        x_top = x_cap[i]
        if top >= 0:
            selected[top] = True
            x_top = min(x_top, slack[top] / beta[top])
        # Along +-u from (0, h x_top): alpha / shifted slack, max and min.
        if np.isfinite(x_top):
            _side_hits(alpha, beta, slack, heights * x_top, selected)
        else:  # nothing bounds +x here (no row, no velocity limit)
            _side_hits(alpha, beta, slack, np.zeros(1), selected)
    if not held:
        selected[:] = False


__all__ = [
    "RAY_HEIGHTS",
    "RAY_STRIDE",
    "normalised_rows",
    "rest_and_candidates",
    "wrench_groups",
    "wrench_ratios",
]
