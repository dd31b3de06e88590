"""Compiled (numba) loops of the jerk-limited retimer: one pass, no temporaries.

:func:`grasp_screen`: at every dense point p the object wrench ``w_p = a_p
u_p + b_p x_p + c_p`` (N, N m, in the cup frame of :mod:`._samples`) and
each grasp row's ratio ``F_r w_p / g_r`` (``scaled = F / g``), reduced as it
is made to the largest ratio per point and the (point, row) pairs at or
above a threshold. The (P, R) ratios are never stored: with numpy they
were three (P, R) temporaries per call. Arrays are C-contiguous float64.
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def grasp_screen(a, b, c, x, u, scaled_t, threshold, over, largest):  # noqa: D417
    """``over[p, r] = F_r w_p / g_r >= threshold``; ``largest[p]`` the max over r.

    ``a``, ``b``, ``c``: (P, 6); ``x``, ``u``: (P,); ``scaled_t``: (6, R),
    ``(F / g)`` transposed (the loop over rows innermost, vectorised);
    ``over``: (P, R) bool and ``largest``: (P,), written in place.
    """
    rows = scaled_t.shape[1]
    ratio = np.empty(rows)
    for p in range(a.shape[0]):
        ratio[:] = 0.0
        for k in range(a.shape[1]):
            w = a[p, k] * u[p] + b[p, k] * x[p] + c[p, k]
            for r in range(rows):
                ratio[r] += w * scaled_t[k, r]
        most = -np.inf
        for r in range(rows):
            over[p, r] = ratio[r] >= threshold
            most = max(most, ratio[r])
        largest[p] = most


@njit(cache=True)
def jerk_ratios(cols, X, U, K, z, dq, ddq, dddq, jerk, inner, out):  # noqa: D417
    """``|q'''_j| / J_j`` at every point, 0 off the interior pieces, in place.

    At point p, ``x``, ``u``, ``k`` are ``band . z[cols[p]]`` (``cols``, ``X``,
    ``U``, ``K``: (P, 3), :class:`._jerk_rows.Band`, summed in the order of
    the sparse maps' rows), ``x`` clipped at 0, and the joint jerk ``sqrt(x)
    (q'_j k + 3 q''_j u + q'''_j x)`` (1/s^3 times rad). ``dq``, ``ddq``,
    ``dddq``, ``out``: (P, n); ``jerk``: (n,); ``inner``: (P,) bool.
    """
    for p in range(cols.shape[0]):
        if not inner[p]:
            for j in range(out.shape[1]):
                out[p, j] = 0.0
            continue
        x, u, k = 0.0, 0.0, 0.0
        for e in range(3):
            value = z[cols[p, e]]
            x += X[p, e] * value
            u += U[p, e] * value
            k += K[p, e] * value
        x = max(x, 0.0)
        root = np.sqrt(x)
        for j in range(out.shape[1]):
            bracket = dq[p, j] * k + 3.0 * ddq[p, j] * u + dddq[p, j] * x
            out[p, j] = abs(root * bracket / jerk[j])


__all__ = ["grasp_screen", "jerk_ratios"]
