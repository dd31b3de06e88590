"""TOPP-RA's passes over Seidel's 2-variable LP, compiled with numba.

The same algorithm and numerics as toppra 0.6.10 (``cy_seidel_solverwrapper``
and ``toppra.algorithm.TOPPRA``), as one compiled loop over the stages
instead of a Python call per stage LP.

Stage ``i`` of N constrains ``(u, x) = (s'', s'^2)`` by the rows
``A[i, k] u + B[i, k] x + C[i, k] <= 0`` (the interpolation discretization:
the constraints at ``s_i`` and those at ``s_{i+1}`` with ``x_{i+1} = x + 2
ds_i u``) and the box ``lo[i] <= (u, x) <= hi[i]``. Rows 0 and 1 are left for
the controllable set of the next stage, ``x_next_min <= x + 2 ds_i u <=
x_next_max``, which the passes write before each LP (as toppra's wrapper
does).

:func:`lp2d` is Seidel's incremental algorithm with toppra's warm start (the
two rows active at the last optimum of the same objective are tried first)
and its tolerances, with two departures where toppra's absolute
tolerances made a feasible LP infeasible on rows of small coefficients (a
joint that barely moves): no bound of 1e10 on the variable of its 1-D
subproblems (the box bounds it), and rows are parallel to the line only if
the angle between them is below ``LP_TINY`` too, not ``|d . n_j|`` alone.
On every LP toppra's rules solve, the answer is unchanged to the bit.
:func:`lp1d` the one-variable LP of the forward pass,
where x is fixed. :func:`passes` runs the backward pass of controllable sets
K_i and the greedy forward pass with toppra's safeguards (see
:mod:`rt_drake.retiming.passes`).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from toppra.constants import MAX_TRIES
from toppra.constants import SMALL as PASS_SMALL  # the passes' safeguards
from toppra.constants import TINY as PASS_TINY

#: Tolerances of toppra's seidel solver (cy_seidel_solverwrapper.pyx).
LP_TINY = 1e-10
LP_SMALL = 1e-8


def kernel_array(values) -> np.ndarray:
    """``values`` as a writable C-contiguous float64 array (copied if needed).

    The one array type the kernels are compiled for (numba compiles again for
    read-only or non-contiguous arrays); cheaper than ``np.require``.
    """
    array = np.ascontiguousarray(values, dtype=np.float64)
    return array if array.flags.writeable else array.copy()


@njit(cache=True)
def lp1d(v0, a, b, count, low, high):  # noqa: D417
    """Maximise v0 t s.t. ``a[j] t + b[j] <= 0`` (j < count), low <= t <= high.

    Returns:
        (feasible, t, active row; -1 or -2 for the bound low or high).
    """
    cur_min, cur_max = low, high
    active_min, active_max = -1, -2
    for j in range(count):
        if a[j] > LP_TINY:
            t = -b[j] / a[j]
            if t < cur_max:
                cur_max = t
                active_max = j
        elif a[j] < -LP_TINY:
            t = -b[j] / a[j]
            if t > cur_min:
                cur_min = t
                active_min = j
    if cur_min > cur_max:
        return False, math.nan, -1
    if abs(v0) < LP_TINY or v0 < 0.0:
        return True, cur_min, active_min
    return True, cur_max, active_max


@njit(cache=True)
def lp2d(v0, v1, a, b, c, low, high, active, order):  # noqa: D417
    """Maximise ``v0 z0 + v1 z1`` s.t. ``a z0 + b z1 + c <= 0``, low <= z <= high.

    ``active`` (2 ints) holds the rows active at the last optimum of this
    objective; they are tried first and overwritten with the new ones.
    ``order`` is a scratch buffer of len(a) ints.

    Returns:
        (feasible, z0, z1).
    """
    rows = a.shape[0]
    if low[0] > high[0] or low[1] > high[1]:
        return False, math.nan, math.nan
    z0 = high[0] if v0 > LP_TINY else low[0]
    z1 = high[1] if v1 > LP_TINY else low[1]
    first, second = active[0], active[1]
    if 0 <= first < rows and 0 <= second < rows and first != second:
        order[0], order[1] = second, first
        k = 2
        for i in range(rows):
            if i != first and i != second:
                order[k] = i
                k += 1
    else:
        for i in range(rows):
            order[i] = i
    found0, found1 = -1, -3
    for k in range(rows):
        i = order[k]
        if a[i] * z0 + b[i] * z1 + c[i] < LP_TINY:
            continue
        # Optimum on the line a_i z0 + b_i z1 + c_i = 0: z = p + t d.
        norm2 = a[i] * a[i] + b[i] * b[i]
        p0 = -a[i] * c[i] / norm2
        p1 = -b[i] * c[i] / norm2
        d0, d1 = -b[i], a[i]
        # The 1-D LP in t over the earlier rows and the box (toppra's lp1d
        # on rows a_1d = +-1, b_1d = value / denom, written out). t is not
        # bounded beforehand: toppra bounds it by +-1e10, but d is not a
        # unit vector, and on a row with tiny coefficients (|d| = 1.8e-5
        # for a joint barely moving) the box is reached only at |t| of
        # 1e12 and more, so toppra cuts a feasible LP to nothing. The box
        # rows bound t wherever d is not parallel to them.
        t_min, t_max, hit_min, hit_max = -math.inf, math.inf, -1, -2
        for j in range(k + 4):
            if j == k:
                aj, bj, cj = -1.0, 0.0, low[0]
            elif j == k + 1:
                aj, bj, cj = 1.0, 0.0, -high[0]
            elif j == k + 2:
                aj, bj, cj = 0.0, -1.0, low[1]
            elif j == k + 3:
                aj, bj, cj = 0.0, 1.0, -high[1]
            else:
                row = order[j]
                aj, bj, cj = a[row], b[row], c[row]
            denom = d0 * aj + d1 * bj
            value = cj + p1 * bj + p0 * aj
            if denom > LP_TINY:
                t = -value / denom
                if t < t_max:
                    t_max, hit_max = t, j
            elif denom < -LP_TINY:
                t = -value / denom
                if t > t_min:
                    t_min, hit_min = t, j
            elif value > LP_SMALL:
                # toppra: row j is parallel to the line and excludes it. It
                # is parallel only if the angle is below LP_TINY too: rows
                # of small coefficients (|n| ~ 0.01) meet at angles of 1e-7
                # with |denom| ~ 1e-11, and bound t, far along the line.
                if denom * denom <= LP_TINY * LP_TINY * (d0 * d0 + d1 * d1) * (
                    aj * aj + bj * bj
                ):
                    return False, math.nan, math.nan
                t = -value / denom
                if denom > 0.0:
                    if t < t_max:
                        t_max, hit_max = t, j
                elif t > t_min:
                    t_min, hit_min = t, j
        if t_min > t_max:
            return False, math.nan, math.nan
        v_1d = d0 * v0 + d1 * v1
        if abs(v_1d) < LP_TINY or v_1d < 0.0:
            t, hit = t_min, hit_min
        else:
            t, hit = t_max, hit_max
        z0 = p0 + t * d0
        z1 = p1 + t * d1
        if hit < 0:  # unbounded along the line: toppra calls this infeasible
            return False, math.nan, math.nan
        found0 = i
        found1 = order[hit] if hit < k else -1 - (hit - k)
    active[0], active[1] = found0, found1
    return True, z0, z1


@njit(cache=True)
def _stage_lp(i, v0, v1, A, B, C, lo, hi, ds, nxt_lo, nxt_hi, ws):
    """The stage LP of toppra's ``solve_stagewise_optim`` (2-D, x free)."""
    active, order = ws
    _set_next(i, A, B, C, ds, nxt_lo, nxt_hi)
    return lp2d(v0, v1, A[i], B[i], C[i], lo[i], hi[i], active, order)


@njit(cache=True)
def _set_next(i, A, B, C, ds, nxt_lo, nxt_hi):
    """Rows 0, 1: ``nxt_lo <= x + 2 ds_i u <= nxt_hi``."""
    A[i, 0], B[i, 0], C[i, 0] = -2.0 * ds[i], -1.0, nxt_lo
    A[i, 1], B[i, 1], C[i, 1] = 2.0 * ds[i], 1.0, -nxt_hi


@njit(cache=True)
def passes(A, B, C, lo, hi, ds, sd_start, sd_end):  # noqa: D417
    """TOPP-RA: backward controllable sets, then the greedy forward pass.

    Args:
        A, B, C: (N+1, R) stage rows (rows 0, 1 are overwritten).
        lo, hi: (N+1, 2) boxes on (u, x).
        ds: (N,) grid steps.
        sd_start, sd_end: Path velocities at the ends (1/s).

    Returns:
        (x (N+1,), u (N,), K (N+1, 2), failed stage or -1).
    """
    stages = ds.shape[0]
    rows = A.shape[1]
    K = np.zeros((stages + 1, 2))
    x = np.zeros(stages + 1)
    u = np.zeros(stages)
    order = np.zeros(rows, np.int64)
    up = np.zeros(2, np.int64)
    down = np.zeros(2, np.int64)
    bx = np.zeros(rows)
    K[stages, 0] = K[stages, 1] = sd_end * sd_end
    for i in range(stages - 1, -1, -1):
        nxt_lo, nxt_hi = K[i + 1, 0], K[i + 1, 1]
        # max x (toppra's g = (1e-9, -1): the tiny weight on u breaks ties)
        ok, _, upper = _stage_lp(
            i, -1e-9, 1.0, A, B, C, lo, hi, ds, nxt_lo, nxt_hi,
            (up, order),
        )  # fmt: skip
        if not ok:  # retry from a cold start (no warm-start rows)
            up[0] = up[1] = -1
            ok, _, upper = _stage_lp(
                i, -1e-9, 1.0, A, B, C, lo, hi, ds, nxt_lo, nxt_hi,
                (up, order),
            )  # fmt: skip
        lower = 0.0
        if ok and nxt_lo > 0.0:
            ok, _, lower = _stage_lp(
                i, 1e-9, -1.0, A, B, C, lo, hi, ds, nxt_lo, nxt_hi,
                (down, order),
            )  # fmt: skip
            if not ok:
                down[0] = down[1] = -1
                ok, _, lower = _stage_lp(
                    i, 1e-9, -1.0, A, B, C, lo, hi, ds, nxt_lo, nxt_hi,
                    (down, order),
                )  # fmt: skip
        if not ok:
            K[: i + 1] = math.nan
            return x, u, K, i
        K[i, 0] = lower if lower > 0.0 else 0.0
        K[i, 1] = upper
    x[0] = sd_start * sd_start
    if x[0] + PASS_SMALL < K[0, 0] or K[0, 1] + PASS_SMALL < x[0]:
        return x, u, K, 0
    i = tries = 0
    while i < stages:
        x_i, nxt_lo, nxt_hi = x[i], K[i + 1, 0], K[i + 1, 1]
        # max u at x = x_i (toppra's 1-D LP when x_min == x_max)
        _set_next(i, A, B, C, ds, nxt_lo, nxt_hi)
        for r in range(rows):
            bx[r] = B[i, r] * x_i + C[i, r]
        ok, step, _ = lp1d(2.0 * ds[i], A[i], bx, rows, lo[i, 0], hi[i, 0])
        if not ok:
            if tries == MAX_TRIES:
                return x, u, K, i
            x[i] = max(x_i - PASS_TINY, 0.999 * x_i)
            tries += 1
            continue
        tries = 0
        u[i] = step
        x_next = x_i + 2.0 * ds[i] * step
        # max(x_next - TINY, 0.9999 x_next), clamped into K_{i+1}
        x_next = max(0.9999 * x_next, x_next - PASS_TINY)
        x[i + 1] = min(max(x_next, nxt_lo), nxt_hi)
        i += 1
    return x, u, K, -1


@njit(cache=True)
def project(a, b, c, F, g, ds, A, B, C, column):  # noqa: D417
    """Write ``F (a_i u + b_i x + c_i) <= g`` as stage rows (interpolation).

    Stage i < N gets, from ``column`` on, the k rows at s_i, ``(F a_i) u +
    (F b_i) x + F c_i - g <= 0``, then the k rows at s_{i+1} with ``x_{i+1} =
    x + 2 ds_i u``: ``(F a_{i+1} + 2 ds_i F b_{i+1}) u + (F b_{i+1}) x + F
    c_{i+1} - g <= 0`` (toppra's ``canlinear_colloc_to_interpolate``, with
    the products at each grid point computed once).

    Args:
        a, b, c: (N+1, m) coefficients; F: (k, m); g: (k,); ds: (N,).
        A, B, C: (N+1, R) stage rows, written in place.

    Returns:
        The next free column, ``column + 2 k``.
    """
    k, m = F.shape
    points = a.shape[0]
    here = np.empty((3, points, k))  # F a_i, F b_i, F c_i - g at every s_i
    for i in range(points):
        for r in range(k):
            sum_a = sum_b = sum_c = 0.0
            for j in range(m):
                sum_a += a[i, j] * F[r, j]
                sum_b += b[i, j] * F[r, j]
                sum_c += c[i, j] * F[r, j]
            here[0, i, r], here[1, i, r], here[2, i, r] = sum_a, sum_b, sum_c - g[r]
    for i in range(ds.shape[0]):
        step = 2.0 * ds[i]
        for r in range(k):
            A[i, column + r] = here[0, i, r]
            B[i, column + r] = here[1, i, r]
            C[i, column + r] = here[2, i, r]
            A[i, column + k + r] = here[0, i + 1, r] + step * here[1, i + 1, r]
            B[i, column + k + r] = here[1, i + 1, r]
            C[i, column + k + r] = here[2, i + 1, r]
    return column + 2 * k
