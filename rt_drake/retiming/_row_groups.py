"""Grasp rows in boxes, so that the exactness check skips most of them.

The exactness check (:func:`rt_drake.retiming.stage_rows.wrench_ratios`) needs,
at every wrench w the stage LPs enforced, the largest ``n_k w`` over the
polytope's rows (n_k = F_k / g_k) and every row above a floor (the rows
looked at between grid points) or above its bound. Most rows are far below
both. :func:`group_rows` sorts the rows into :data:`GROUPS` groups of
neighbouring normals (a k-d split at the median of the widest coordinate,
weighted by the wrenches' magnitudes), each with its bounding box, centre
c and half-widths r. For every row of a group and any w, in real numbers,

    n_k w <= c w + sum_d r_d |w_d|,

and :func:`grouped_ratios` adds ``MARGIN sum_d (|c_d| + r_d) |w_d|`` for
the rounding of both sides (each below 8 units in the last place of that
sum). A group whose bound is at most both the best value found so far and
the floor cannot hold the maximum nor a row above the floor: it is skipped.
At a wrench whose maximum is not wanted (past the first ``exact``: the
retimer needs the maxima at the grid points only), a group whose bound is
at most the floor is skipped.
The maximum and every row above the floor come out as evaluating every row
would give them, to the last bit (the same products, in the same order).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit

#: Groups are 2**DEPTH (32: about 26 rows each for 834 rows).
DEPTH = 5
GROUPS = 1 << DEPTH
#: Relative allowance for rounding in the bound (8 ulp would do).
MARGIN = 1e-12


class RowGroups(NamedTuple):
    """Rows sorted into groups, with their boxes.

    Attributes:
        order: (R,) row index of each sorted position.
        start: (GROUPS + 1,) group j holds sorted positions start[j] to
            start[j + 1] - 1.
        normals: (6, R) the rows' ``F_k / g_k`` in sorted order.
        g: (R,) the rows' bounds in sorted order.
        center, radius: (6, GROUPS) each group's box (centre, half-widths).
        reach: (6, GROUPS) ``|center| + radius`` (for the margin).
    """

    order: np.ndarray
    start: np.ndarray
    normals: np.ndarray
    g: np.ndarray
    center: np.ndarray
    radius: np.ndarray
    reach: np.ndarray


def group_rows(normals: np.ndarray, g: np.ndarray, scale: np.ndarray) -> RowGroups:
    """Sort the rows into groups of neighbouring normals.

    Args:
        normals: (6, R) ``(F / g)ᵀ``, C-contiguous float64.
        g: (R,) the rows' bounds, C-contiguous float64.
        scale: (6,) typical magnitude of each wrench coordinate (the split
            is along the coordinate whose spread, times its scale, is
            widest).
    """
    rows = normals.shape[1]
    order = np.arange(rows)
    start = np.empty(GROUPS + 1, dtype=np.int64)
    sorted_normals = np.empty_like(normals)
    sorted_g = np.empty_like(g)
    boxes = np.zeros((3, 6, GROUPS))
    _build(normals, g, scale, order, start, sorted_normals, sorted_g, boxes)
    return RowGroups(order, start, sorted_normals, sorted_g, *boxes)


@njit(cache=True)
def _select(order, keys, low, high, kth):  # noqa: D417
    """Reorder ``order[low:high]`` so that position kth holds its median key.

    Quickselect (Hoare partition, median-of-three pivot): keys at positions
    before kth are at most, after kth at least, that of kth.
    """
    left, right = low, high - 1
    while right > left:
        a, b, c = (
            keys[order[left]],
            keys[order[(left + right) // 2]],
            keys[order[right]],
        )
        pivot = max(min(a, b), min(max(a, b), c))
        i, j = left, right
        while i <= j:
            while keys[order[i]] < pivot:
                i += 1
            while keys[order[j]] > pivot:
                j -= 1
            if i <= j:
                order[i], order[j] = order[j], order[i]
                i += 1
                j -= 1
        if kth <= j:
            right = j
        elif kth >= i:
            left = i
        else:
            return


@njit(cache=True)
def _build(normals, g, scale, order, start, sorted_normals, sorted_g, boxes):  # noqa: D417
    """K-d split of the rows into ``GROUPS`` groups; fill the outputs."""
    rows = normals.shape[1]
    start[0], start[GROUPS] = 0, rows
    for level in range(DEPTH):
        step = GROUPS >> level
        for m in range(1 << level):
            low, high = start[m * step], start[(m + 1) * step]
            middle = (low + high) // 2
            start[m * step + step // 2] = middle
            if high - low < 2:
                continue
            widest, width = 0, -1.0
            for d in range(6):
                smallest, largest = np.inf, -np.inf
                for k in range(low, high):
                    value = normals[d, order[k]]
                    smallest = min(smallest, value)
                    largest = max(largest, value)
                if (largest - smallest) * scale[d] > width:
                    widest, width = d, (largest - smallest) * scale[d]
            _select(order, normals[widest], low, high, middle)
    for k in range(rows):
        sorted_g[k] = g[order[k]]
        for d in range(6):
            sorted_normals[d, k] = normals[d, order[k]]
    for j in range(GROUPS):
        if start[j + 1] == start[j]:
            continue
        for d in range(6):
            smallest, largest = np.inf, -np.inf
            for k in range(start[j], start[j + 1]):
                smallest = min(smallest, sorted_normals[d, k])
                largest = max(largest, sorted_normals[d, k])
            boxes[0, d, j] = 0.5 * (smallest + largest)
            boxes[1, d, j] = 0.5 * (largest - smallest)
            boxes[2, d, j] = abs(boxes[0, d, j]) + boxes[1, d, j]


@njit(cache=True)
def _group_max(low, high, n, w0, w1, w2, w3, w4, w5, row_max, values):  # noqa: D417
    """``max_k n_k w`` over sorted positions low..high-1; update row_max.

    The values first (a loop that vectorises: no reduction), then their
    maximum.
    """
    for k in range(low, high):
        value = (
            n[0, k] * w0
            + n[1, k] * w1
            + n[2, k] * w2
            + n[3, k] * w3
            + n[4, k] * w4
            + n[5, k] * w5
        )
        values[k] = value
        previous = row_max[k]
        row_max[k] = value if value > previous else previous
    best = -np.inf
    for k in range(low, high):
        best = values[k] if values[k] > best else best
    return best


@njit(cache=True)
def _group_violated(low, high, groups, tol, w0, w1, w2, w3, w4, w5, violated):  # noqa: D417
    """Mark the rows of positions low..high-1 with ``g_k (n_k w - 1) > tol``."""
    order, n, g = groups[0], groups[2], groups[3]
    for k in range(low, high):
        value = (
            n[0, k] * w0
            + n[1, k] * w1
            + n[2, k] * w2
            + n[3, k] * w3
            + n[4, k] * w4
            + n[5, k] * w5
        )
        if g[k] * (value - 1.0) > tol:
            violated[order[k]] = True


@njit(cache=True)
def grouped_ratios(wrenches, groups, tol, floor, exact, ratio, violated, row_max):  # noqa: D417
    """The exactness check over the groups (see the module docstring).

    Args:
        wrenches: (M, 6).
        groups: :class:`RowGroups`.
        tol: Excess ``g_k (n_k w - 1)`` above which row k is violated.
        floor: Rows above it are found exactly (-inf: every row).
        exact: The first ``exact`` wrenches get their largest value; the
            others only the rows above ``floor`` (a group that cannot hold
            one is skipped even if it could hold the wrench's maximum).
        ratio: (M,) out: ``max_k n_k w`` at each of the first ``exact``
            wrenches; at the others the same where above ``floor``, else at
            most ``floor`` (-inf if no group was looked at).
        violated: (R,) bool, out: rows violated somewhere (set to True).
        row_max: (R,) out: ``max_w n_k w`` where above ``floor``, at most
            ``floor`` elsewhere (-inf if never evaluated).
    """
    order, start, n, _, center, radius, reach = groups
    count = start.shape[0] - 1
    bound = np.empty(count)
    sorted_max = np.full(n.shape[1], -np.inf)
    values = np.empty(n.shape[1])
    for i in range(wrenches.shape[0]):
        w0, w1, w2 = wrenches[i, 0], wrenches[i, 1], wrenches[i, 2]
        w3, w4, w5 = wrenches[i, 3], wrenches[i, 4], wrenches[i, 5]
        a0, a1, a2, a3, a4, a5 = abs(w0), abs(w1), abs(w2), abs(w3), abs(w4), abs(w5)
        for j in range(count):  # vectorises (no reduction)
            value = (
                center[0, j] * w0
                + center[1, j] * w1
                + center[2, j] * w2
                + center[3, j] * w3
                + center[4, j] * w4
                + center[5, j] * w5
            )
            spread = (
                radius[0, j] * a0
                + radius[1, j] * a1
                + radius[2, j] * a2
                + radius[3, j] * a3
                + radius[4, j] * a4
                + radius[5, j] * a5
            )
            size = (
                reach[0, j] * a0
                + reach[1, j] * a1
                + reach[2, j] * a2
                + reach[3, j] * a3
                + reach[4, j] * a4
                + reach[5, j] * a5
            )
            bound[j] = value + spread + MARGIN * size
        top, top_bound = 0, -np.inf
        for j in range(count):
            if bound[j] > top_bound:
                top, top_bound = j, bound[j]
        best = -np.inf
        wanted = i < exact  # this wrench's maximum, or only rows above floor
        for step in range(count + 1):  # the likeliest group first
            j = top if step == 0 else step - 1
            if step > 0 and j == top:
                continue
            if (wanted and step > 0 and bound[j] <= min(best, floor)) or (
                not wanted and bound[j] <= floor
            ):
                continue
            low, high = start[j], start[j + 1]
            value = _group_max(low, high, n, w0, w1, w2, w3, w4, w5, sorted_max, values)
            if value > 1.0:  # g (n w - 1) > tol > 0 needs n w > 1
                _group_violated(
                    low, high, groups, tol, w0, w1, w2, w3, w4, w5, violated
                )
            best = value if value > best else best
        ratio[i] = best
    for k in range(n.shape[1]):
        row_max[order[k]] = sorted_max[k]


__all__ = ["DEPTH", "GROUPS", "MARGIN", "RowGroups", "group_rows", "grouped_ratios"]
