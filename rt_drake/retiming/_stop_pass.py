"""The shortest stop along a path: controllable sets from rest, then maximal braking.

From the state ``(s_0, x_0)`` (``x = s'^2``, 1/s^2) at the first grid point
``s_0 < s_1 < ... < s_N`` of the rest of a path, :func:`stop_pass` finds the
first grid point at which the robot can be at rest, under the constraints
TOPP-RA enforces at the grid points (its interpolation discretization: at
each stage i, the rows at ``s_i`` with ``(u_i, x_i)`` and those at
``s_{i+1}`` with ``x_{i+1} = x_i + 2 ds_i u_i``):

- joint velocity ``x_i <= min_j v_j^2 / q'_j(s_i)^2``;
- joint acceleration ``|q'(s_i) u + q''(s_i) x| <= a``;
- joint torques ``|a_tau(s_i) u + b_tau(s_i) x + c_tau(s_i)| <= tau`` (if
  limited);
- the grasp ``F (a(s_i) u + b(s_i) x + c(s_i)) <= g`` with every row of the
  polytope (one held object).

1. The backward pass (TOPP-RA's, :func:`rt_drake.retiming.seidel.passes`)
   computes the controllable sets ``K_i`` from rest at ``s_N``: the x from
   which rest is reachable. Every grid point holds the robot at rest, so
   ``0 in K_i`` and rest at any ``s_i`` is reachable from ``K_i`` too.
2. The greedy forward pass brakes as hard as the constraints allow: at each
   stage the smallest admissible ``u_i`` with ``x_{i+1} in K_{i+1}`` (so
   ``x_{i+1} >= 0``), until ``x_{i+1} = 0``. Each step keeps the smallest
   reachable x at the next grid point, so the first grid point at rest is
   the nearest one any admissible profile reaches at rest.

Between grid points nothing is enforced here: the stop's profile comes from
the retimer on the sub-path that ends at the point found (:mod:`._stop`),
which holds every limit between grid points too.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from rt_drake.retiming._samples import PathSamples
from rt_drake.retiming.limits import JointLimits
from rt_drake.retiming.passes import (
    AffineConstraint,
    XBound,
    stage_rows,
)
from rt_drake.retiming.seidel import lp1d, passes

#: Relative tolerance on x when the start state is checked against K_0
#: (the retimer's own profile lies on the boundary of its controllable
#: sets, computed on another grid).
START_TOLERANCE = 1e-6
#: A path velocity squared below this (1/s^2) is rest.
REST_X = 1e-12


class StopPass(NamedTuple):
    """The maximal-braking profile on the grid.

    Attributes:
        stop_index: Index of the first grid point at rest (None: the start
            state is outside ``K_0``, so no stop to rest within the path).
        x: (stop_index + 1,) ``s'^2`` at the grid points up to there.
        u: (stop_index,) path acceleration ``s''`` per segment, 1/s^2.
        K: (N+1, 2) controllable sets from rest at the last grid point.
    """

    stop_index: int | None
    x: np.ndarray
    u: np.ndarray
    K: np.ndarray


def grid_constraints(
    samples: PathSamples,
    limits: JointLimits,
    F: np.ndarray | None,
    g: np.ndarray | None,
) -> list[AffineConstraint | XBound]:
    """The grid-point constraints of the module docstring, as toppra objects.

    ``F, g``: the grasp polytope's rows (None: no grasp); the samples then
    carry the wrench coefficients. Torques are limited if ``limits.torque``
    is set and the samples carry torque coefficients.
    """
    s, dq, ddq = samples.s, samples.dq, samples.ddq
    n = dq.shape[1]
    box = np.vstack([np.eye(n), -np.eye(n)])
    constraints: list[AffineConstraint | XBound] = [
        XBound(np.column_stack([np.zeros_like(s), samples.x_cap])),
        AffineConstraint(
            dq, ddq, np.zeros_like(dq), box, np.tile(limits.acceleration, 2)
        ),
    ]
    if samples.torque is not None and limits.torque is not None:
        constraints.append(
            AffineConstraint(*samples.torque, box, np.tile(limits.torque, 2))
        )
    if F is not None and g is not None and samples.wrench is not None:
        constraints.append(AffineConstraint(*samples.wrench, F, g))
    return constraints


def stop_pass(
    constraints: list[AffineConstraint | XBound], s: np.ndarray, x_start: float
) -> StopPass:
    """Brake from ``x_start`` at ``s[0]`` to the first grid point at rest.

    Args:
        constraints: From :func:`grid_constraints` on the grid ``s``.
        s: (N+1,) grid, strictly increasing.
        x_start: ``s'^2`` at ``s[0]`` (1/s^2), >= 0.

    Returns:
        The profile (see :class:`StopPass`); ``stop_index`` None when
        ``x_start`` exceeds ``max K_0`` by more than :data:`START_TOLERANCE`.
    """
    ds = np.diff(s)
    lps = stage_rows(list(constraints), ds)
    A, B, C, lo, hi = lps
    _, _, K, failed = passes(A, B, C, lo, hi, ds, 0.0, 0.0)
    if failed > 0 or not np.isfinite(K[0]).all():
        return StopPass(None, np.zeros(0), np.zeros(0), K)
    top = K[0, 1]
    if x_start > top * (1.0 + START_TOLERANCE) + REST_X:
        return StopPass(None, np.zeros(0), np.zeros(0), K)
    x = [min(float(x_start), float(top))]
    u: list[float] = []
    rows = A.shape[1]
    for i in range(len(ds)):
        if x[-1] <= REST_X:
            x[-1] = 0.0
            break
        # Rows 0, 1: K_{i+1} lower <= x_i + 2 ds_i u <= K_{i+1} upper.
        A[i, 0], B[i, 0], C[i, 0] = -2.0 * ds[i], -1.0, K[i + 1, 0]
        A[i, 1], B[i, 1], C[i, 1] = 2.0 * ds[i], 1.0, -K[i + 1, 1]
        shifted = B[i] * x[-1] + C[i]
        ok, step, _ = lp1d(-1.0, A[i], shifted, rows, lo[i, 0], hi[i, 0])
        if not ok:  # x_i in K_i: only rounding can get here
            return StopPass(None, np.zeros(0), np.zeros(0), K)
        u.append(float(step))
        x.append(max(x[-1] + 2.0 * ds[i] * step, 0.0))
    if x[-1] > REST_X:
        return StopPass(None, np.zeros(0), np.zeros(0), K)
    x[-1] = 0.0
    return StopPass(len(u), np.asarray(x), np.asarray(u), K)


__all__ = ["REST_X", "START_TOLERANCE", "StopPass", "grid_constraints", "stop_pass"]
