"""A grid for the jerk-limited retime, refined where its profile's s'^2 moves.

The jerk-limited retime (:mod:`rt_drake.retiming._jerk`) holds the path
acceleration ``u = s''`` linear in s on each grid segment, so ``k = du/ds``
is constant there and the jerk of a joint on a straight line is

    q'''_j = q'_j k sqrt(x),     x = s'^2,

largest at the segment's end where x is largest. Held at the limit there,
the jerk at the segment's other end is only ``sqrt(x_i / x_{i+1})`` of it:
the retime ramps the acceleration slower than the limit allows wherever x
changes by a large factor within a segment (the ramps from and to rest,
and into and out of every dip of the speed at a turn). On a straight joint
line from rest to rest, on 100 uniform points, the ramps at its two ends
left the retime 1.2-3.0 % (7 ms) longer than Ruckig's time-optimal
double-S.

:func:`jerk_grid` splits each segment of a jerk-limited profile whose
``|ln(x_{i+1} / x_i)|`` exceeds ``step`` at equal steps of ``ln x`` (with
``x`` linear in s between the profile's points), so that across each part
the jerk can stay within about ``exp(-step / 2)`` of its limit. The first
and last segments of the grid the profile was retimed on keep no point
inside (the retimer's own halving points there are dropped: it adds them
again); at an end at rest they are halved ``end_halvings`` times instead,
so that the retimer's halving points and closed-form end piece
(:mod:`rt_drake.retiming._jerk_timed_path`) start that much deeper, where
the ramp from rest is. On the default cycle's picks and MOVEs that gave
the most (BENCHMARKS.md); on a straight joint line the end piece is the
exact constant-jerk ramp, and neither refinement shortens it.
"""

from __future__ import annotations

import numpy as np

#: Largest |ln(x_{i+1} / x_i)| a segment keeps unsplit (x = s'^2).
JERK_GRID_STEP = 0.05
#: Parts a segment is split into, at most.
MAX_PARTS = 16
#: Points halving each end segment at rest towards the end (module doc).
END_HALVINGS = 6


def jerk_grid(
    s: np.ndarray,
    sd: np.ndarray,
    base: np.ndarray,
    step: float = JERK_GRID_STEP,
    end_halvings: int = END_HALVINGS,
) -> np.ndarray:
    """The grid ``s`` with its segments split where ``x = sd^2`` moves (module doc).

    Args:
        s: (M,) the grid of a jerk-limited retime (``RetimeResult.gridpoints``),
            0 to 1, increasing.
        sd: (M,) its path velocity s' there (1/s), >= 0.
        base: the grid that retime was asked for (its first and last
            segments are kept whole, the points inside them dropped).
        step: the largest ``|ln(x_{i+1} / x_i)|`` of a segment kept whole, > 0.
        end_halvings: points halving ``base``'s end segment towards each end
            at rest (``sd`` 0 there), so the retimer's own halving points
            and closed-form end piece start that many halvings deeper.

    Returns:
        The refined grid, 0 to 1, increasing; ``s``'s points (less those
        inside ``base``'s end segments) and the splitting points.
    """
    s = np.asarray(s, dtype=float)
    sd = np.asarray(sd, dtype=float)
    if not step > 0.0:
        raise ValueError(f"jerk_grid: step must be > 0, got {step}")
    if s.shape != sd.shape or s.ndim != 1 or len(s) < 2:
        raise ValueError(
            f"jerk_grid: s {s.shape} and sd {sd.shape} must be (M,), M >= 2"
        )
    base = np.asarray(base, dtype=float)
    inner = (s >= base[1]) & (s <= base[-2]) if len(base) >= 4 else s < 0.0
    if inner.sum() < 2:
        return base
    s, x = s[inner], sd[inner] ** 2
    inside = [
        _log_steps(a, b, x_a, x_b, step)
        for a, b, x_a, x_b in zip(s[:-1], s[1:], x[:-1], x[1:], strict=True)
    ]
    halves = 0.5 ** np.arange(end_halvings, 0, -1)
    head = s[0] * halves if sd[0] == 0.0 else np.zeros(0)
    tail = 1.0 - (1.0 - s[-1]) * halves[::-1] if sd[-1] == 0.0 else np.zeros(0)
    return np.concatenate([[0.0], head, *inside, [s[-1]], tail, [1.0]])


def _log_steps(a: float, b: float, x_a: float, x_b: float, step: float) -> np.ndarray:
    """``a`` and the points splitting ``[a, b]`` at equal steps of ``ln x``.

    ``x`` linear from ``x_a`` at ``a`` to ``x_b`` at ``b``; ``n = ceil(|ln(x_b
    / x_a)| / step)`` parts (at most :data:`MAX_PARTS`), the k-th point where
    ``x = x_a (x_b / x_a)^(k / n)``. A segment with ``x = 0`` at an end is
    kept whole.
    """
    if not (x_a > 0.0 and x_b > 0.0) or x_a == x_b:
        return np.array([a])
    change = np.log(x_b / x_a)
    parts = min(int(np.ceil(abs(change) / step)), MAX_PARTS)
    x = x_a * np.exp(change * np.arange(parts) / parts)
    return a + (b - a) * (x - x_a) / (x_b - x_a)
