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
form: :func:`._robust_rows.worst_rows`). With torque limits, each joint's
limit likewise (:func:`set_torque_slack`).
"""

from __future__ import annotations

import numpy as np

from rt_drake.dynamics.wrench import PathCoefficients
from rt_drake.retiming._robust_rows import Layout, worst_rows
from rt_drake.retiming._samples import PathSamples
from rt_drake.retiming._set_tables import torque_columns, torque_normals
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
    ratio = _worst_ratios(start.wrench_set, x, u, normalised_rows(F, g), layout)
    return np.asarray(g, dtype=float) * np.maximum(1.0, (1.0 + 1e-9) * ratio)


def set_torque_slack(
    start: PathSamples, x: float, u: float, torque: np.ndarray, layout: Layout
) -> np.ndarray:
    """Torque limits widened to the start's worst ``|tau_j|`` over the set.

    ``tau_max_j <- tau_max_j max(1, (1 + 1e-9) max_v |tau_j(v)| /
    tau_max_j)``, ``tau(v)`` the joint torques (N m) with the set's object v
    held (the arm's, ``start.torque``, plus its share, ``start.torque_set``:
    :func:`._set_tables.torque_columns`), the worst v in closed form per
    joint and sign.

    Args:
        start: The path at the stop's start, with the set's torque columns.
        x: ``s'^2`` at the start (1/s^2).
        u: ``s''`` at the start (1/s^2).
        torque: (n,) the torque limits, N m.
        layout: The set's boxes among the columns.
    """
    assert start.torque is not None and start.torque_set is not None
    table = torque_columns(start.torque, start.torque_set, layout)
    ratio = _worst_ratios(table, x, u, torque_normals(torque)[1], layout)
    n = len(torque)
    worst = np.maximum(ratio[:n], ratio[n:])
    return np.asarray(torque, dtype=float) * np.maximum(1.0, (1.0 + 1e-9) * worst)


def _worst_ratios(
    table: PathCoefficients, x: float, u: float, normals: np.ndarray, layout: Layout
) -> np.ndarray:
    """(R,) each row's largest ``n_r . v`` over the set at ``table``'s one point."""
    rows = normals.shape[1]
    worst = worst_rows(
        table, np.zeros(1, dtype=np.int64), np.array([u]), np.array([x]), normals,
        layout, ranks=rows,
    )  # fmt: skip
    assert worst.ranked is not None
    values, ranked_rows, _ = (v[0] for v in worst.ranked)
    ratio = np.zeros(rows)
    valid = ranked_rows >= 0
    ratio[ranked_rows[valid]] = values[valid]
    return ratio


__all__ = ["set_slack", "set_torque_slack"]
