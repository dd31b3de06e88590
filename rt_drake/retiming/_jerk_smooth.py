"""The jerk-limited retimer's input check: a path with continuous q' and q''.

Where q' or q'' of the path q(s) jumps at a break, the joint acceleration
``q' s'' + q'' s'^2`` jumps unless the motion stops there, so no jerk limit
can hold (:mod:`._jerk`).
"""

from __future__ import annotations

import numpy as np

from rt_drake.retiming._joint_path import JointPath
from rt_drake.retiming._retime_errors import RetimeInputError


def _taylor(
    spline: JointPath, s: np.ndarray, order: int, h: float, third: np.ndarray
) -> np.ndarray:
    """``q^(order)(s + h)`` by Taylor's series at ``s`` up to ``third`` = q'''(s).

    ``q'(s) + h q''(s) + h^2 / 2 q'''(s)`` for order 1, ``q''(s) + h
    q'''(s)`` for order 2: exact inside a cubic piece.
    """
    value = spline(s, order)
    if order == 1:
        return value + h * spline(s, 2) + 0.5 * h * h * third
    return value + h * third


def check_smooth(spline: JointPath) -> None:
    """Refuse a path whose q' or q'' jumps at a break.

    There the joint acceleration ``q' s'' + q'' s'^2`` jumps unless the
    motion stops, so no jerk limit can hold; the motion's pieces
    (:mod:`._jerk_timed_path`) stop only at the ends.

    Raises:
        RetimeInputError: naming the joint, the jump and s.
    """
    inner = spline.breaks[1:-1]
    if not inner.size:
        return
    step = 1e-9
    third = {side: spline(inner + side * step, 3) for side in (-1.0, 1.0)}
    for order in (1, 2):
        # Each side extrapolated to the break by its Taylor series up to the
        # third derivative (exact inside a cubic piece), so that a steep but
        # continuous q' or q'' (a short spline piece) is no jump: with the
        # next derivative alone, a last piece 3e-7 of the path long made q'
        # "jump" by 6e-6 (the step^2 / 2 q''' term left out).
        right, left = (
            _taylor(spline, inner + side * step, order, -side * step, third[side])
            for side in (1.0, -1.0)
        )
        jump = right - left
        scale = max(1.0, float(np.max(np.abs(spline(spline.breaks, order)))))
        if np.max(np.abs(jump)) > 1e-6 * scale:
            i, j = np.unravel_index(int(np.argmax(np.abs(jump))), jump.shape)
            name = "q'" if order == 1 else "q''"
            raise RetimeInputError(
                f"jerk limits need a path with continuous q' and q'': {name} of "
                f"joint {j + 1} jumps by {jump[i, j]:.4g} at s = {inner[i]:.4f} "
                "(a break of the path), where the joint acceleration would jump; "
                "give waypoints (the clamped cubic spline) or retime without "
                "jerk limits",
                s=float(inner[i]),
            )


__all__ = ["check_smooth"]
