"""The grasp check at the dense points after a round of LPs, skipping far points.

After each round of LPs (:mod:`._jerk`) every dense point's grasp ratios
``F_r w / g_r`` (``w = a u + b x + c``, N and N m in the cup frame of
:mod:`._samples`) are checked against ``1 + tolerance``
(:meth:`._jerk_points.DensePoints.grasp_screen`: every row at every point).
From one round to the next the profile moves little, so most points stay
far from the limit. With the wrench ``w0`` and largest ratio ``l0`` of a
point at an earlier check, Cauchy-Schwarz bounds each row's ratio:

    F_r w / g_r = F_r w0 / g_r + (F_r / g_r)(w - w0)
                <= l0 + max_r |F_r / g_r|_2 |w - w0|_2.

A point whose bound stays under the threshold is not evaluated (no pair
over, its bound as its largest ratio: it is not over, which is all the
check needs there). The grid points are always evaluated: their largest
ratios are the retime's reported margins.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from rt_drake.retiming._jerk_points import DensePoints

#: Margin under the threshold below which a bound skips a point (against
#: the rounding of the compiled ratios).
SAFETY = 1e-9


@dataclasses.dataclass(frozen=True, eq=False)
class ScreenReference:
    """Each dense point's wrench (P, 6) and largest grasp ratio (P,), last evaluated."""

    wrench: np.ndarray
    largest: np.ndarray


def grasp_check(
    dense: DensePoints,
    x: np.ndarray,
    u: np.ndarray,
    threshold: float,
    reference: ScreenReference | None,
) -> tuple[np.ndarray, np.ndarray, ScreenReference]:
    """Pairs with ``F_r w / g_r >= threshold`` (P, R), each point's largest ratio.

    ``x``, ``u``: (P,) the profile at the dense points. Where the module
    docstring's bound from ``reference`` (None: none yet) is under
    ``threshold - SAFETY`` and the point is not a grid point, the point is
    skipped and its bound stands for its largest ratio. Returns the new
    reference (the skipped points keep their old one: the bound holds from
    any earlier wrench).
    """
    assert dense.grasp is not None and dense.samples.wrench is not None
    a, b, c = dense.samples.wrench
    wrench = a * u[:, None] + b * x[:, None] + c
    if reference is None:
        over, largest = dense.grasp_screen(x, u, threshold)
        return over, largest, ScreenReference(wrench, largest)
    norm = dense.grasp.largest_norm
    bound = reference.largest + norm * np.linalg.norm(wrench - reference.wrench, axis=1)
    grid = (dense.k == 0) | (np.arange(len(x)) == len(x) - 1)
    at = np.flatnonzero(grid | (bound >= threshold - SAFETY))
    over, largest = dense.grasp_screen(x, u, threshold, at)
    skipped = np.ones(len(x), dtype=bool)
    skipped[at] = False
    largest[skipped] = bound[skipped]
    new_wrench = reference.wrench.copy()
    new_wrench[at] = wrench[at]
    new_largest = reference.largest.copy()
    new_largest[at] = largest[at]
    return over, largest, ScreenReference(new_wrench, new_largest)


__all__ = ["SAFETY", "ScreenReference", "grasp_check"]
