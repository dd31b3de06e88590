"""First guesses of a jerk-limited stop's distance: 1-D stops along the path.

Two guesses: :func:`path_stop_distance`, in closed form, frozen at the
state at t; :func:`braking_distance`, simulated along the path under the
grid's own rows (grasp included) and the joint jerk.

The closed form:

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
from rt_drake.retiming._samples import PathSamples
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


#: s: time step of :func:`braking_distance`'s simulation.
STEP = 2e-3
#: s: the longest stop :func:`braking_distance` simulates.
LONGEST = 2.0


def braking_distance(
    samples: PathSamples,
    d3q: np.ndarray,
    limits: JointLimits,
    F: np.ndarray | None,
    g: np.ndarray | None,
    sd: float,
    sdd: float,
) -> float:
    """A jerk-limited stop simulated along the path from ``samples.s[0]``.

    The state ``(s, v = s', u = s'')`` is stepped by :data:`STEP` with the
    path jerk ``w``: the smallest the joint jerk allows, ``|q' w + 3 q'' v
    u + q^(3) v^3| <= J`` (per joint), with ``u`` kept at or above the grid
    rows' smallest path acceleration at ``(s, v^2)`` (``alpha u + beta x +
    gamma <= 0`` with ``alpha < 0``: joint accelerations, torques, grasp
    rows as :func:`._stop_pass.grid_constraints`, linear in s between grid
    points); once ``v <= u^2 / (2 w_up)`` (``w_up``: the largest path jerk
    allowed), ``w = w_up`` (the final ramp to rest, as in the closed
    form). A guess, not a bound: the rows hold only at the grid points and
    the ramps are greedy.

    Args:
        samples: The path at the grid from ``s_t`` on (torques and wrench
            coefficients as the rows need).
        d3q: (G, n) the path's third derivative in s at those points.
        limits: With ``jerk`` set.
        F: The grasp rows' normals (R, 6), or None.
        g: Their offsets (R,), or None.
        sd: ``s'_t`` (1/s).
        sdd: ``s''_t`` (1/s^2).

    Returns:
        The distance in s to rest (to the grid's end if it gets there
        first; where q' = 0, the distance so far).
    """
    assert limits.jerk is not None
    alpha, beta, gamma = _rows(samples, limits, F, g)
    s_grid = samples.s
    last = len(s_grid) - 2
    s, v, u = float(s_grid[0]), float(sd), float(sdd)
    for _ in range(int(LONGEST / STEP)):
        if v <= 0.0 or s >= s_grid[-1]:
            break
        k = min(max(int(np.searchsorted(s_grid, s, side="right")) - 1, 0), last)
        weight = (s - s_grid[k]) / (s_grid[k + 1] - s_grid[k])
        dq, ddq, dddq, a_k, b_k, c_k = (
            (1.0 - weight) * values[k] + weight * values[k + 1]
            for values in (samples.dq, samples.ddq, d3q, alpha, beta, gamma)
        )
        rest = 3.0 * ddq * v * u + dddq * v**3
        moving = np.abs(dq) > 1e-9
        if not moving.any():  # q' = 0: no path jerk bound to brake with
            break
        low = (-limits.jerk - rest)[moving] / dq[moving]
        high = (limits.jerk - rest)[moving] / dq[moving]
        w_low = float(np.max(np.minimum(low, high)))
        w_high = float(np.min(np.maximum(low, high)))
        down = a_k < 0.0
        u_min = -np.inf
        if down.any():
            u_min = float(np.max(-(b_k[down] * v * v + c_k[down]) / a_k[down]))
        if u < 0.0 and w_high > 0.0 and v <= u * u / (2.0 * w_high):
            w = w_high
        else:
            w = min(w_low, 0.0)
        s += v * STEP + u * STEP**2 / 2.0 + w * STEP**3 / 6.0
        v += u * STEP + w * STEP**2 / 2.0
        u = max(u + w * STEP, min(u_min, 0.0))
    return min(s, float(s_grid[-1])) - float(s_grid[0])


def _rows(
    samples: PathSamples,
    limits: JointLimits,
    F: np.ndarray | None,
    g: np.ndarray | None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``alpha u + beta x + gamma <= 0`` per grid point: (G, R) each."""
    dq, ddq = samples.dq, samples.ddq
    bound = np.broadcast_to(limits.acceleration, dq.shape)
    parts = [(dq, ddq, -bound), (-dq, -ddq, -bound)]
    if samples.torque is not None and limits.torque is not None:
        a, b, c = samples.torque
        parts += [(a, b, c - limits.torque), (-a, -b, -c - limits.torque)]
    if F is not None and g is not None and samples.wrench is not None:
        a, b, c = samples.wrench
        parts.append((a @ F.T, b @ F.T, c @ F.T - g))
    alpha, beta, gamma = (np.hstack([part[i] for part in parts]) for i in range(3))
    return alpha, beta, gamma


__all__ = [
    "LONGEST",
    "STEP",
    "axis_stop_distance",
    "braking_distance",
    "path_stop_distance",
]
