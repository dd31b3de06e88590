"""The grasp of a set of objects widened to hold a stop's start state.

A jerk-limited stop starts from the MOVE's own state at t, fixed
(:mod:`._jerk_stop`). The MOVE holds every object of the set at its points
and within the retimer's contract between them, so at t a row may be over
its bound by up to ``BETWEEN_TOLERANCE``, which would leave the stop's LPs
without a solution. As :func:`._jerk_stop.start_slack` does for one object,
each grasp row's offset is widened to the start's own worst value over the
set where that exceeds it:

    ``g_r <- g_r max(1, (1 + 1e-9) max_v n_r . w_v(u, x))``

with ``n_r = F_r / g_r`` and ``w_v = sum_p theta_vp (a_p u + b_p x + c_p)``
the wrench of the set's object v at the start (its worst vertex, in closed
form: :func:`._robust_rows.worst_rows`).
"""

from __future__ import annotations

import numpy as np

from rt_drake.retiming._robust_rows import Layout, worst_rows
from rt_drake.retiming._samples import PathSamples
from rt_drake.retiming.stage_rows import normalised_rows


def set_slack(
    start: PathSamples,
    x: float,
    u: float,
    F: np.ndarray,
    g: np.ndarray,
    layout: Layout,
) -> np.ndarray:
    """``g`` widened to the start's worst row values over the set (docstring).

    Args:
        start: The path at the stop's start, with the set's wrench columns
            (``wrench_set``, each (1, P, 6)).
        x: ``s'^2`` at the start (1/s^2).
        u: ``s''`` at the start (1/s^2).
        F: (R, 6) the grasp rows.
        g: (R,) their offsets.
        layout: The set's boxes among the columns.

    Returns:
        (R,) the widened offsets (``g`` where the start holds).
    """
    assert start.wrench_set is not None
    normals = normalised_rows(F, g)
    rows = normals.shape[1]
    worst = worst_rows(
        start.wrench_set, np.zeros(1, dtype=np.int64), np.array([u]), np.array([x]),
        normals, layout, ranks=rows,
    )  # fmt: skip
    assert worst.ranked is not None
    values, ranked_rows, _ = (v[0] for v in worst.ranked)
    ratio = np.zeros(rows)
    valid = ranked_rows >= 0
    ratio[ranked_rows[valid]] = values[valid]
    return np.asarray(g, dtype=float) * np.maximum(1.0, (1.0 + 1e-9) * ratio)


__all__ = ["set_slack"]
