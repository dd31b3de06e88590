"""The robot must be able to stop anywhere on the path: checks at rest.

With s' = s'' = 0 the object wrench is gravity's, ``c(s)``, and the joint
torques hold the arm and object against gravity. Each check raises a typed
error naming s (the first grid point that fails) and the cause.
"""

from __future__ import annotations

import numpy as np

from rt_drake.retiming._retime_errors import (
    GraspUnstableAtRestError,
    TorqueLimitAtRestError,
)
from rt_drake.retiming.limits import GraspConstraint, JointLimits
from rt_drake.uncertainty.inertial_set import SetVertex


def check_grasp_at_rest(
    s: np.ndarray, rest: np.ndarray, c: np.ndarray, grasp: GraspConstraint
) -> None:
    """Raise if the object cannot be held at rest at some grid point.

    Args:
        s: (G,) grid.
        rest: (G,) ``max_k F_k c(s) / g_k``; held at rest iff < 1.
        c: (G, 6) the wrench at rest, ``[p x (-m g_C); -m g_C]``.
        grasp: The grasp (for the message).
    """
    if np.all(rest < 1.0):
        return
    i = int(np.flatnonzero(~(rest < 1.0))[0])
    excess = float(np.max(grasp.F @ c[i] - grasp.g))
    g_C = -c[i, 3:] / grasp.held.mass
    tilt = np.degrees(np.arccos(np.clip(g_C[2] / np.linalg.norm(g_C), -1.0, 1.0)))
    raise GraspUnstableAtRestError(
        f"object slips even at rest at s = {s[i]:.3f}: gravity alone exceeds the "
        f"grasp constraint ({grasp.describe()}, cup axis {tilt:.0f} deg from "
        f"pointing down; worst row exceeded by {excess:.3g} N or N m)",
        s=float(s[i]),
    )


def set_grasp_at_rest(
    s: float, c: np.ndarray, worst: SetVertex, grasp: GraspConstraint
) -> None:
    """Raise: the worst object of the set slips at rest at ``s``.

    Args:
        s: Where.
        c: (6,) the worst object's wrench at rest there.
        worst: The worst object of the set (a vertex of its outer set).
        grasp: The constraint (for the message).
    """
    excess = float(np.max(grasp.F @ c - grasp.g))
    tilt = _tilt(-c[3:] / worst.mass)
    p_mm = ", ".join(f"{1e3 * v:.1f}" for v in worst.p_CoScm_C)
    raise GraspUnstableAtRestError(
        f"object slips even at rest at s = {s:.3f}: gravity alone exceeds the "
        f"grasp constraint for the worst object of the set ({worst.mass:.3g} kg, "
        f"centre of mass at ({p_mm}) mm in the cup frame; {grasp.describe()}), "
        f"cup axis {tilt:.0f} deg from pointing down; worst row exceeded by "
        f"{excess:.3g} N or N m",
        s=float(s),
    )


def set_torque_at_rest(
    s: float, row: int, ratio: float, worst: SetVertex, limits: JointLimits
) -> None:
    """Raise: holding the arm with the worst object exceeds a torque limit.

    Args:
        s: Where.
        row: The torque row (j: +tau_j, n + j: -tau_j).
        ratio: ``|tau_j| / tau_max_j`` there.
        worst: The worst object of the set.
        limits: The joint limits.
    """
    assert limits.torque is not None
    j = row % len(limits.torque)
    raise TorqueLimitAtRestError(
        f"holding the arm at rest at s = {s:.3f} with the worst object of the set "
        f"({worst.mass:.3g} kg) needs {ratio * limits.torque[j]:.3g} N m at joint "
        f"{j + 1}, above its limit {limits.torque[j]:.3g} N m",
        s=float(s),
    )


def _tilt(g_C: np.ndarray) -> float:
    """Angle (deg) between the cup's +z and gravity."""
    return float(
        np.degrees(np.arccos(np.clip(g_C[2] / np.linalg.norm(g_C), -1.0, 1.0)))
    )


def check_torque_at_rest(
    s: np.ndarray, tau_rest: np.ndarray, limit: np.ndarray
) -> None:
    """Raise if the arm cannot be held still at some grid point.

    Args:
        s: (G,) grid.
        tau_rest: (G, n) joint torques at rest (gravity, object included), N m.
        limit: (n,) torque limits, N m.
    """
    ratio = np.abs(tau_rest) / limit
    if np.all(ratio < 1.0):
        return
    i, j = (int(k[0]) for k in np.nonzero(ratio >= 1.0))
    raise TorqueLimitAtRestError(
        f"holding the arm at rest at s = {s[i]:.3f} needs {abs(tau_rest[i, j]):.3g} "
        f"N m at joint {j + 1}, above its limit {limit[j]:.3g} N m",
        s=float(s[i]),
    )


__all__ = [
    "check_grasp_at_rest",
    "check_torque_at_rest",
    "set_grasp_at_rest",
    "set_torque_at_rest",
]
