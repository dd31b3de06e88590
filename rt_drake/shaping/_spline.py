"""Many clamped chord-length cubic splines at once (compiled with numba).

The planner's path convention (:class:`rt_drake.types.path.GeometricPath`,
the retimer's ``CubicSpline(knots, waypoints, bc_type="clamped")``) for a
batch of candidate paths: knots ``t_i = L_i / L_{K-1}`` from the cumulative
joint-space chord lengths ``L_i`` (rad), slopes ``m_i = q'(t_i)`` from the C2
conditions at the interior knots::

    h_i m_{i-1} + 2 (h_{i-1} + h_i) m_i + h_{i-1} m_{i+1}
        = 3 (h_i d_{i-1} + h_{i-1} d_i),     m_0 = m_{K-1} = 0

(``h_i = t_{i+1} - t_i``, ``d_i = (q_{i+1} - q_i) / h_i``), and cubic Hermite
pieces between knots. The same spline as scipy's, to rounding (tested).
"""

from __future__ import annotations

import numpy as np
from numba import njit


def chord_knots_batch(waypoints: np.ndarray) -> np.ndarray:
    """Normalised cumulative chord-length knots (P, K) of waypoints (P, K, n)."""
    chords = np.linalg.norm(np.diff(waypoints, axis=-2), axis=-1)
    knots = np.concatenate(
        [np.zeros((*chords.shape[:-1], 1)), np.cumsum(chords, -1)], -1
    )
    knots /= knots[..., -1:]
    return knots


def evaluate_splines(
    waypoints: np.ndarray, s: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """q, q' and q'' (each (P, M, n)) of P clamped splines at the M parameters s.

    Args:
        waypoints: (P, K, n) joint waypoints (rad), no two consecutive equal.
        s: (M,) nondecreasing parameters in [0, 1], shared by the P paths, or
            (P, M): each path's own.
    """
    # writeable C-ordered float64, the layout warm_up compiles (no other)
    waypoints = np.require(waypoints, float, ("C", "W"))
    knots = np.require(chord_knots_batch(waypoints), float, ("C", "W"))
    s = np.require(np.atleast_2d(s), float, ("C", "W"))
    count, _, n = waypoints.shape
    out = np.empty((3, count, s.shape[1], n))
    _splines(waypoints, knots, s, out)
    return out[0], out[1], out[2]


@njit(cache=True)
def _splines(W, t, s, out):  # noqa: D417
    """Fill out[0..2] with q, q', q'' of each clamped spline p at s[p] (or s[0])."""
    count, K, n = W.shape
    m = np.zeros((K, n))
    diag = np.empty(K)
    rhs = np.empty((K, n))
    for p in range(count):
        # Thomas algorithm on the interior knots 1..K-2 (m_0 = m_{K-1} = 0).
        for i in range(K):
            for j in range(n):
                m[i, j] = 0.0
        for i in range(1, K - 1):
            h0 = t[p, i] - t[p, i - 1]
            h1 = t[p, i + 1] - t[p, i]
            diag[i] = 2.0 * (h0 + h1)
            for j in range(n):
                d0 = (W[p, i, j] - W[p, i - 1, j]) / h0
                d1 = (W[p, i + 1, j] - W[p, i, j]) / h1
                rhs[i, j] = 3.0 * (h1 * d0 + h0 * d1)
        # forward sweep: row i couples m_{i-1} (coef h1_i) and m_{i+1} (h0_i)
        for i in range(2, K - 1):
            lower = t[p, i + 1] - t[p, i]  # h_i, coefficient of m_{i-1}
            upper_prev = t[p, i - 1] - t[p, i - 2]  # h_{i-2}: m_i in row i-1
            factor = lower / diag[i - 1]
            diag[i] -= factor * upper_prev
            for j in range(n):
                rhs[i, j] -= factor * rhs[i - 1, j]
        for i in range(K - 2, 0, -1):
            upper = t[p, i] - t[p, i - 1]  # h_{i-1}, coefficient of m_{i+1}
            for j in range(n):
                value = rhs[i, j]
                if i + 1 < K - 1:
                    value -= upper * m[i + 1, j]
                m[i, j] = value / diag[i]
        k = 0
        row = p if s.shape[0] > 1 else 0
        for r in range(s.shape[1]):
            while k < K - 2 and s[row, r] > t[p, k + 1]:
                k += 1
            h = t[p, k + 1] - t[p, k]
            tau = (s[row, r] - t[p, k]) / h
            tau2 = tau * tau
            tau3 = tau2 * tau
            h00, h10 = 2 * tau3 - 3 * tau2 + 1, tau3 - 2 * tau2 + tau
            h01, h11 = -2 * tau3 + 3 * tau2, tau3 - tau2
            g00, g10 = 6 * tau2 - 6 * tau, 3 * tau2 - 4 * tau + 1
            g01, g11 = -6 * tau2 + 6 * tau, 3 * tau2 - 2 * tau
            f00, f10 = 12 * tau - 6, 6 * tau - 4
            f01, f11 = -12 * tau + 6, 6 * tau - 2
            for j in range(n):
                y0, y1 = W[p, k, j], W[p, k + 1, j]
                s0, s1 = h * m[k, j], h * m[k + 1, j]
                out[0, p, r, j] = h00 * y0 + h10 * s0 + h01 * y1 + h11 * s1
                out[1, p, r, j] = (g00 * y0 + g10 * s0 + g01 * y1 + g11 * s1) / h
                out[2, p, r, j] = (f00 * y0 + f10 * s0 + f01 * y1 + f11 * s1) / (h * h)


__all__ = ["chord_knots_batch", "evaluate_splines"]
