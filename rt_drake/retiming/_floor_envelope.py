"""The jerk-limited floor of one joint whose end states are bounded: its envelope.

One joint moves by ``d >= 0`` (rad, toward its goal) in time ``T`` (s) under
``|v| <= V`` (rad/s), ``|a| <= A`` (rad/s^2) and ``|jerk| <= J`` (rad/s^3).
Its ends are known only by bounds, toward the goal: at the start
``v(0) <= u0`` and ``a(0) <= alpha0``; at the end ``v(T) <= u1`` and
``a(T) >= -alpha1`` (its braking at most ``alpha1``). At rest: ``u = alpha =
0``; free: ``u = V``, ``alpha = A``.

**The envelope.** From a start ``(u, alpha)`` the greedy profile raises its
acceleration at ``J`` up to ``A`` and lowers it at ``J`` just in time to
reach ``V`` with zero acceleration: ``a_g(t) = min(A, alpha + J t)`` until
``v_g + a_g^2 / (2 J)`` reaches ``V`` at ``t_s`` (at once, from
``a_s = sqrt(2 J (V - u))``, if ``u + alpha^2 / (2 J) >= V``), then
``a_g = a_s - J (t - t_s)`` down to 0, then ``v_g = V``.

*Every motion has* ``v(t) <= g(t) = v_g(t)``. Before ``t_s``: ``a(t) <=
min(A, alpha0 + J t)``, so ``v(t) <= u0 + integral of it = v_g(t)``. After:
suppose ``v(t) > v_g(t) = V - a_g(t)^2 / (2 J)``. Lowering ``a(t) >= 0``
to 0 at rate ``J`` at most adds ``a(t)^2 / (2 J)`` to ``v``, which never
exceeds ``V``, so ``a(t) < a_g(t)``; going back in time ``a`` grows at
most at ``J``, so ``a(s) <= a(t) + J (t - s) < a_g(s)`` on ``[t_s, t]`` and
``v(t) < v(t_s) + v_g(t) - v_g(t_s) <= v_g(t)``: a contradiction.

Read backward from the end, ``z(s) = -x(T - s)`` is a motion with
``z'(0) = v(T) <= u1`` and ``z''(0) = -a(T) <= alpha1``, so also ``v(t) <=
g1(T - t)`` (the envelope of ``(u1, alpha1)``). Hence

    d = integral_0^T v dt <= integral_0^T min(g0(t), g1(T - t)) dt
      <= G0(c) + G1(T - c)   for every c in [0, T]   (G: the integral of g)

and the bound ``D(T) = min_c [G0(c) + G1(T - c)]`` (c on a grid: any c is
an upper bound) grows with ``T``. Every ``T`` with ``D(T) < d`` is too
short; :func:`envelope_floor` returns the largest such ``T`` that its
search finds, a lower bound on the time. It is exact where the ends' envelopes
meet at ``V`` (a long move: the double-S's time from rest to rest) and
where one end is free (the greedy profile itself is a motion); where they
meet below ``V`` it lies under the true time (by at most 9 %, rest to rest
under jerk alone, where :func:`~rt_drake.retiming.rest_to_rest_jerk` is
exact).
"""

from __future__ import annotations

import numpy as np

#: Points of the split ``c`` on ``[0, T]`` per evaluation of ``D(T)``.
SPLITS = 49
#: Times ``T`` tried at once per round of the search, and its rounds: the
#: bracket shrinks ``TRIES`` times per round.
TRIES, ROUNDS = 16, 8


def envelope_floor(
    d: np.ndarray,
    limits: tuple[np.ndarray, np.ndarray, np.ndarray],
    start: tuple[np.ndarray, np.ndarray],
    end: tuple[np.ndarray, np.ndarray],
    upper: np.ndarray,
) -> np.ndarray:
    """Lower bound (s) on the time of each joint's move (module docstring).

    Args:
        d: (n,) displacements, rad, ``>= 0``.
        limits: ``(V, A, J)``, each (n,) and ``> 0``.
        start: ``(u0, alpha0)`` (n,) each, ``>= 0`` (``inf``: free).
        end: ``(u1, alpha1)`` (n,) each, ``>= 0``.
        upper: (n,) a time at which the move is possible (e.g. the double-S
            from rest to rest, whose ends lie in every set): the search's top.

    The search keeps ``low``, a time shown too short (``D(low) < d``), and
    a ``high`` above it; each round tries ``TRIES`` times between them and
    keeps the last one shown too short.
    """
    g0 = _Envelope(*limits, *start)
    g1 = _Envelope(*limits, *end)
    fractions = np.linspace(0.0, 1.0, SPLITS)
    steps = np.arange(1, TRIES + 1) / TRIES
    low, high = np.zeros_like(d), np.asarray(upper, float)
    rows = np.arange(len(d))
    for _ in range(ROUNDS):
        T = low[:, None] + (high - low)[:, None] * steps  # (n, TRIES)
        c = T[..., None] * fractions  # (n, TRIES, SPLITS)
        reach = np.min(g0.distance(c) + g1.distance(T[..., None] - c), axis=-1)
        short = reach < d[:, None]
        last = TRIES - 1 - np.argmax(short[:, ::-1], axis=1)  # last too short
        found = short[rows, last]
        low = np.where(found, T[rows, last], low)
        above = np.minimum(last + 1, TRIES - 1)
        high = np.where(found & (last + 1 < TRIES), T[rows, above], high)
        high = np.where(found, high, T[:, 0])
    return np.where(d > 0.0, low, 0.0)


class _Envelope:
    """The greedy profile ``v_g`` from ``(u, alpha)`` and its distance.

    Its parameters are held as (n, 1, 1) arrays, one row per joint, to
    broadcast against times of shape (n, k, m).
    """

    def __init__(
        self,
        V: np.ndarray,
        A: np.ndarray,
        J: np.ndarray,
        u: np.ndarray,
        alpha: np.ndarray,
    ) -> None:
        V, A, J, u, alpha = (np.asarray(x, float)[:, None, None] for x in (
            V, A, J, u, alpha))  # fmt: skip
        u, alpha = np.minimum(u, V), np.minimum(alpha, A)
        self.V, self.A, self.J, self.u, self.alpha = V, A, J, u, alpha
        self.t1 = (A - alpha) / J  # acceleration reaches A
        self.v1, self.x1 = self._rise(self.t1)
        at_once = u + alpha**2 / (2 * J) >= V
        t_rise = (np.sqrt(alpha**2 / 2 + J * np.maximum(V - u, 0.0)) - alpha) / J
        in_rise = t_rise <= self.t1
        t_hold = self.t1 + (V - self.v1 - A**2 / (2 * J)) / A
        self.ts = np.select([at_once, in_rise], [0.0 * V, t_rise], t_hold)
        self.a_s = np.select(
            [at_once, in_rise],
            [np.sqrt(2 * J * np.maximum(V - u, 0.0)), alpha + J * t_rise],
            A,
        )
        self.vs, self.xs = self._before_taper(self.ts)
        taper = self.a_s / J
        self.te = self.ts + taper
        self.xe = self.xs + self.vs * taper + self.a_s * taper**2 / 2 - J * taper**3 / 6

    def _rise(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(v, x) while ``a = alpha + J t``."""
        u, alpha, J = self.u, self.alpha, self.J
        return u + alpha * t + J * t**2 / 2, u * t + alpha * t**2 / 2 + J * t**3 / 6

    def _before_taper(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(v, x) at ``t <= t_s``: rising, then holding ``A`` after ``t1``."""
        v_rise, x_rise = self._rise(np.minimum(t, self.t1))
        hold = np.maximum(t - self.t1, 0.0)
        rising = t <= self.t1
        v = np.where(rising, v_rise, self.v1 + self.A * hold)
        x = np.where(rising, x_rise, self.x1 + self.v1 * hold + self.A * hold**2 / 2)
        return v, x

    def distance(self, t: np.ndarray) -> np.ndarray:
        """``G(t) = integral_0^t v_g`` (rad) at times ``t`` (n, k, m), ``>= 0``."""
        _, x_before = self._before_taper(np.minimum(t, self.ts))
        tau = np.clip(t - self.ts, 0.0, self.te - self.ts)
        x_taper = self.xs + self.vs * tau + self.a_s * tau**2 / 2 - self.J * tau**3 / 6
        x_after = self.xe + self.V * np.maximum(t - self.te, 0.0)
        return np.select([t <= self.ts, t <= self.te], [x_before, x_taper], x_after)


__all__ = ["envelope_floor"]
