"""A first guess of a jerk-limited stop's distance: a 1-D stop along the path.

Frozen at the state at t (``s_t``, ``v = s'_t``, ``a_0 = s''_t``), the path
acceleration and jerk each joint allows are ``|q'_j(s_t)| |s''| <= A_j``
and ``|q'_j(s_t)| |s'''| <= J_j`` (the terms in ``q''`` and ``q'''`` and
the grasp left out), so ``a = min_j A_j / |q'_j|`` and ``j = min_j J_j /
|q'_j|`` (1/s^2, 1/s^3). The 1-D stop with those bounds (Ruckig's
velocity-control stop, one axis) is:

1. jerk ``-j`` from ``a_0`` down to ``-a_p``;
2. ``s'' = -a_p`` held for ``t_2 >= 0``;
3. jerk ``+j`` from ``-a_p`` up to 0, reaching ``s' = 0`` with it.

Phases 1 and 3 change the speed by ``(a_0^2 - a_p^2) / (2 j)`` and ``-a_p^2
/ (2 j)``; ``a_p = a`` when that leaves ``t_2 >= 0``, else ``a_p = sqrt(j v
+ a_0^2 / 2)`` (no phase 2). The distance is the sum of each phase's ``v t
+ a t^2 / 2 + jerk t^3 / 6``. It is only where the search over the stop
distance (:func:`._jerk_stop.jerk_stop`) starts: the grasp and the dropped
terms can lengthen the stop, a path whose tangent turns can shorten it.
"""

from __future__ import annotations

import numpy as np

from rt_drake.retiming._joint_path import JointPath
from rt_drake.retiming.limits import JointLimits


def axis_stop_distance(v: float, a0: float, a: float, j: float) -> float:
    """Distance of the 1-D jerk-limited stop of the module docstring.

    Args:
        v: Speed at the start.
        a0: Acceleration at the start (|a0| <= a expected; clipped).
        a: Deceleration bound (> 0).
        j: Jerk bound (> 0).

    Returns:
        The distance (0 at rest, ``v <= 0``). From a state that cannot stop
        without reversing (``a0 < 0``, ``v < a0^2 / (2 j)``) it is that of
        a profile that reverses, clipped at 0: only a guess.
    """
    if v <= 0.0:
        return 0.0
    a0 = float(np.clip(a0, -a, a))
    peak = a
    if v + (a0 * a0 - a * a) / (2.0 * j) < a * a / (2.0 * j):
        peak = max(np.sqrt(j * v + 0.5 * a0 * a0), -a0)
    phases = [((a0 + peak) / j, -j)]
    speed_after = v + (a0 * a0 - peak * peak) / (2.0 * j)
    phases.append((max(speed_after - peak * peak / (2.0 * j), 0.0) / peak, 0.0))
    phases.append((peak / j, j))
    distance, speed, acceleration = 0.0, v, a0
    for duration, jerk in phases:
        distance += (
            speed * duration
            + acceleration * duration**2 / 2.0
            + jerk * duration**3 / 6.0
        )
        speed += acceleration * duration + jerk * duration**2 / 2.0
        acceleration = -peak if jerk < 0.0 else acceleration + jerk * duration
    return max(distance, 0.0)


def path_stop_distance(
    spline: JointPath, limits: JointLimits, s: float, sd: float, sdd: float
) -> float:
    """The guess of the module docstring: a stop distance in s from ``s``.

    Args:
        spline: The path q(s).
        limits: With ``jerk`` set (rad/s^2, rad/s^3 per joint).
        s: ``s_t``.
        sd: ``s'_t`` (1/s).
        sdd: ``s''_t`` (1/s^2).
    """
    assert limits.jerk is not None
    tangent = np.abs(spline(s, 1))
    tangent = np.maximum(tangent, 1e-12)
    a = float(np.min(limits.acceleration / tangent))
    j = float(np.min(limits.jerk / tangent))
    return axis_stop_distance(sd, sdd, a, j)


__all__ = ["axis_stop_distance", "path_stop_distance"]
