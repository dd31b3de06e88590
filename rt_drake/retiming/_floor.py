"""The floor: the least time any motion between two configurations can take.

A lower bound from the arm's own limits alone (no grasp, no path): joint j
moves by ``d_j = |q_to,j - q_from,j|`` (rad) under ``|qdot_j| <= v_j``
(rad/s), ``|qddot_j| <= a_j`` (rad/s^2) and, where given, ``|qdddot_j| <=
j_j`` (rad/s^3). Its least time, by the ends at which it is at rest:

- both ends at rest (velocity and acceleration limits: the trapezoid):
  ``d / v + v / a`` if ``d >= v^2 / a``, else ``2 sqrt(d / a)``;
- both ends at rest, with a jerk limit (the double-S profile, Biagiotti
  and Melchiorri, *Trajectory Planning for Automatic Machines and Robots*,
  3.4): see :func:`rest_to_rest_jerk`;
- one end at rest, the other free: ``d / v + v / (2 a)`` if ``d >= v^2 /
  (2 a)``, else ``sqrt(2 d / a)``;
- neither end at rest: ``d / v``;
- with a jerk limit and each end's speed and acceleration bounded (at
  rest, free, or by a line): the velocity envelope of
  :mod:`._floor_envelope` (its docstring holds the proof), exact where the
  motion reaches full speed and where one end is free.

A joint that is not at rest at an end but cannot be faster there than u
(rad/s, toward its goal) saves at most ``u / a`` on the at-rest time: a
braking or speeding-up ramp of ``u / a`` s added at that end turns its
motion into an at-rest one over at least the same distance. Its floor is
the largest of ``d / v`` and the at-rest times less ``u / a`` per such end
(each end also taken as free).
A motion's floor is the largest of its joints' times: every joint must
complete its own move.

Between a vertical line and the next (or the previous) move, the joints'
velocities at the junction are the line's tangent ``delta`` times one speed
``lambda >= 0`` (the path parameter's), with ``|delta_k lambda| <= v_k``:
joint j is at most ``u_j = |delta_j| min_k v_k / |delta_k|`` fast toward
the move's goal if ``delta_j`` points there, and at rest for the bound (0)
if it points away (starting against the displacement only takes longer) --
:func:`junction_speeds`. Its acceleration there is bounded likewise by
the line's tangent and bend (:func:`junction_accelerations`). A joint that
hardly moves on the line (J1 on this arm's vertical lines) thus counts as
nearly at rest, and under a jerk limit it must ramp its acceleration up
from nearly 0 as from rest.
"""

from __future__ import annotations

import numpy as np

from rt_drake import arguments
from rt_drake.retiming._floor_envelope import envelope_floor
from rt_drake.retiming._retime_errors import RetimeInputError
from rt_drake.retiming.limits import JointLimits


def rest_to_rest_jerk(
    d: np.ndarray, v: np.ndarray, a: np.ndarray, j: np.ndarray
) -> np.ndarray:
    """Least time (s) to move by ``d`` from rest to rest under v, a and jerk j.

    The double-S profile (times per joint, all arrays of one shape):

    - cruise reached: ``Ta = a / j + v / a`` if ``v j >= a^2`` else
      ``Ta = 2 sqrt(v / j)``; if ``d >= v Ta``: ``T = d / v + Ta``;
    - else, the acceleration limit reached (``d >= 2 a^3 / j^2``): the peak
      speed ``vp = (a / 2) (sqrt(a^2 / j^2 + 4 d / a) - a / j)`` and
      ``T = 2 (a / j + vp / a)``;
    - else jerk alone: ``T = 4 (d / (2 j))^(1/3)``.
    """
    where = "rest_to_rest_jerk"
    d = np.abs(arguments.array(d, "d", ("...",), where=where, error=RetimeInputError))
    limits = []
    for name, value in (("v", v), ("a", a), ("j", j)):
        value = arguments.array(
            value, name, ("...",), where=where, error=RetimeInputError
        )
        if not np.all(value > 0.0):
            raise RetimeInputError(f"{where}: {name} must be > 0, got {value.tolist()}")
        limits.append(np.broadcast_to(value, d.shape))
    v, a, j = limits
    ta = np.where(v * j >= a * a, a / j + v / a, 2.0 * np.sqrt(v / j))
    cruise = d / v + ta
    vp = 0.5 * a * (np.sqrt((a / j) ** 2 + 4.0 * d / a) - a / j)
    accel = 2.0 * (a / j + vp / a)
    jerk_only = 4.0 * np.cbrt(d / (2.0 * j))
    return np.select([d >= v * ta, d >= 2.0 * a**3 / j**2], [cruise, accel], jerk_only)


def joint_floor(
    d: np.ndarray,
    limits: JointLimits,
    speed_from: np.ndarray | float,
    speed_to: np.ndarray | float,
    jerk: np.ndarray | None = None,
    accel_from: np.ndarray | float | None = None,
    accel_to: np.ndarray | float | None = None,
) -> np.ndarray:
    """Least time (s) of each joint to move by ``d`` (rad), its end states bounded.

    Args:
        d: (n,) joint displacements, rad.
        limits: Velocity and acceleration limits (n,).
        speed_from: (n,) largest speed (rad/s) each joint may have toward its
            goal at the start: 0 at rest, ``inf`` free.
        speed_to: (n,) the same at the end.
        jerk: (n,) jerk limits (rad/s^3), or None (the bounds without it
            hold with it).
        accel_from: (n,) largest acceleration (rad/s^2) toward the goal at
            the start, used with ``jerk``; None: 0 where ``speed_from`` is 0
            (at rest), free elsewhere.
        accel_to: (n,) largest braking (rad/s^2) at the end, likewise.
    """
    where = "joint_floor"
    arguments.instance(
        limits, "limits", JointLimits, where=where, error=RetimeInputError
    )
    v, a = limits.velocity, limits.acceleration
    n = len(v)
    d = np.abs(arguments.array(d, "d", (n,), where=where, error=RetimeInputError))
    u_from, u_to = (_bounds(u, n, "end speeds") for u in (speed_from, speed_to))
    both = np.where(d >= v * v / a, d / v + v / a, 2.0 * np.sqrt(d / a))
    one = np.where(d >= v * v / (2 * a), d / v + v / (2 * a), np.sqrt(2.0 * d / a))
    bounded_from, bounded_to = np.isfinite(u_from), np.isfinite(u_to)
    ramp_from = np.where(bounded_from, u_from, 0.0) / a
    ramp_to = np.where(bounded_to, u_to, 0.0) / a
    candidates = [
        d / v,
        np.where(bounded_from, one - ramp_from, 0.0),  # the end taken as free
        np.where(bounded_to, one - ramp_to, 0.0),  # the start taken as free
        np.where(bounded_from & bounded_to, both - ramp_from - ramp_to, 0.0),
    ]
    if jerk is not None:
        jerk = arguments.array(jerk, "jerk", (n,), where=where, error=RetimeInputError)
        if not np.all(jerk > 0.0):
            raise RetimeInputError(
                f"joint_floor: jerk limits must be > 0, got {jerk.tolist()}"
            )
        alpha_from, alpha_to = (
            np.where(u == 0.0, 0.0, np.inf)
            if alpha is None
            else _bounds(alpha, n, "end accelerations")
            for u, alpha in ((u_from, accel_from), (u_to, accel_to))
        )
        double_s = rest_to_rest_jerk(d, v, a, jerk)
        at_rest = (u_from == 0.0) & (u_to == 0.0) & (alpha_from == 0.0)
        candidates.append(np.where(at_rest & (alpha_to == 0.0), double_s, 0.0))
        candidates.append(
            envelope_floor(
                d, (v, a, jerk), (u_from, alpha_from), (u_to, alpha_to), double_s
            )
        )
    return np.max(candidates, axis=0)


def _bounds(value: np.ndarray | float, n: int, name: str) -> np.ndarray:
    """(n,) end bounds from one value or n, each ``>= 0`` (``inf``: free)."""
    bounds = np.broadcast_to(np.asarray(value, float), (n,))
    if not np.all(bounds >= 0.0):  # NaN fails too
        raise RetimeInputError(f"joint_floor: {name} must be >= 0 (inf: free)")
    return bounds


def segment_floor(
    q_from: np.ndarray,
    q_to: np.ndarray,
    limits: JointLimits,
    speed_from: np.ndarray | float,
    speed_to: np.ndarray | float,
    jerk: np.ndarray | None = None,
    accel_from: np.ndarray | float | None = None,
    accel_to: np.ndarray | float | None = None,
) -> float:
    """Least time (s) of any motion from ``q_from`` to ``q_to`` (rad).

    The largest of :func:`joint_floor`'s times (``speed_*``, ``accel_*``:
    per joint, or one value for all: 0 at rest, ``inf`` free).
    """
    arguments.instance(
        limits, "limits", JointLimits, where="segment_floor", error=RetimeInputError
    )
    q_from, q_to = (
        arguments.array(
            q, name, (len(limits.velocity),), where="segment_floor",
            error=RetimeInputError,
        )
        for q, name in ((q_from, "q_from"), (q_to, "q_to"))
    )  # fmt: skip
    times = joint_floor(
        q_to - q_from, limits, speed_from, speed_to, jerk, accel_from, accel_to
    )
    return float(times.max(initial=0.0))


def junction_speeds(
    line_step: np.ndarray, displacement: np.ndarray, limits: JointLimits
) -> np.ndarray:
    """(n,) largest joint speeds (rad/s) toward a move's goal where a line meets it.

    ``line_step``: the line's joint motion at the junction, in its direction
    of travel (rad; e.g. its last step when the line ends there); the move's
    ``displacement`` (rad) starts there (for a line that starts where the
    move ends, reverse the signs of both). ``u_j = |delta_j| min_k v_k /
    |delta_k|`` where ``delta_j`` points along the displacement, else 0
    (module docstring).
    """
    arguments.instance(
        limits, "limits", JointLimits, where="junction_speeds", error=RetimeInputError
    )
    n = len(limits.velocity)
    delta, displacement = (
        arguments.array(x, name, (n,), where="junction_speeds", error=RetimeInputError)
        for x, name in ((line_step, "line_step"), (displacement, "displacement"))
    )
    moving = np.abs(delta) > 0.0
    if not np.any(moving):
        return np.zeros_like(delta)
    speed = np.min(limits.velocity[moving] / np.abs(delta[moving]))
    toward = np.sign(delta) * np.sign(displacement) > 0
    return np.where(toward, np.abs(delta) * speed, 0.0)


def junction_accelerations(line_end: np.ndarray, limits: JointLimits) -> np.ndarray:
    """(n,) largest joint accelerations (rad/s^2) where a line meets a move.

    ``line_end``: (3, n) points of the line at equal steps of its parameter
    ``s``, the last at the junction (rad; either direction of travel). On
    the line ``qdot = q' sdot`` and ``qddot = q'' sdot^2 + q' sddot``, with
    ``q'`` and ``q''`` the one-sided differences at the junction
    (``(3 p2 - 4 p1 + p0) / 2``, ``p2 - 2 p1 + p0``). Every joint's limits
    bound the path speed, ``|sdot| <= S = min_k v_k / |q'_k|``, and its
    acceleration, ``|q'_k sddot| <= a_k + |q''_k| S^2``; hence ``|qddot_j|
    <= |q''_j| S^2 + |q'_j| min_k (a_k + |q''_k| S^2) / |q'_k|`` (at most
    ``a_j``). Acceleration is continuous under a jerk limit, so the move has
    it at the junction too. A joint that does not turn on the line (J1 on a
    vertical line of this arm) thus starts the move nearly at rest.
    """
    where = "junction_accelerations"
    arguments.instance(
        limits, "limits", JointLimits, where=where, error=RetimeInputError
    )
    v, a = limits.velocity, limits.acceleration
    p0, p1, p2 = arguments.array(
        line_end, "line_end", (3, len(v)), where=where, error=RetimeInputError
    )
    slope = np.abs(1.5 * p2 - 2.0 * p1 + 0.5 * p0)
    bend = np.abs(p2 - 2.0 * p1 + p0)
    moving = slope > 0.0
    if not np.any(moving):
        return np.where(bend > 0.0, a, 0.0)
    speed = np.min(v[moving] / slope[moving])
    path_accel = np.min((a + bend * speed**2)[moving] / slope[moving])
    return np.minimum(a, bend * speed**2 + slope * path_accel)


__all__ = [
    "joint_floor",
    "junction_accelerations",
    "junction_speeds",
    "rest_to_rest_jerk",
    "segment_floor",
]
