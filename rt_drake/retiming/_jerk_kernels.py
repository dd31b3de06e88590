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


__all__ = ["grasp_screen"]
