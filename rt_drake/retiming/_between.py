"""What a retimed profile does between two grid points, and how to hold it.

Within segment i (from ``s_i`` to ``s_{i+1}``, inside one cubic piece of the
path, see :mod:`.grid`) the motion has the constant path acceleration ``u_i``
and ``x(s) = x_i + 2 u_i (s - s_i)``. At the point ``s = s_i + theta ds_i``
the constraints read, in the stage's own variables (u_i, x_i),

- joint velocity ``q'_j(s)^2 (x_i + 2 theta ds_i u_i) <= v_j^2``,
- joint acceleration ``|(q'_j(s) + 2 theta ds_i q''_j(s)) u_i + q''_j(s) x_i|
  <= a_j``,
- joint torque ``|a_j(s) u_i + b_j(s) x(s) + c_j(s)| <= tau_j``,
- grasp ``F_k (a(s) u_i + b(s) x(s) + c(s)) <= g_k``,

all linear in (u_i, x_i). TOPP-RA enforces them at the grid points only;
between, they can be exceeded (by several percent at 100 grid points). So:

- :func:`interior_rows` adds, from the start, the joint velocities and
  accelerations at theta = 1/4, 1/2, 3/4 of every segment (exact, from the
  spline), and
  :func:`grasp_midpoint_rows` the grasp rows in force at the midpoints;
- after solving, :func:`joint_cuts` evaluates the joint limits exactly at
  the sub-points; where one still exceeds its limit by more than the
  tolerance, its row at the worst sub-point becomes a cut (solve again, no
  new grid point); if the cuts do not converge, :func:`joint_split_points`
  splits those segments in two;
- :func:`refinement_points` evaluates torques and grasp at the sub-points;
  a segment exceeding a limit by ``e`` is split into ``ceil(sqrt(e /
  tolerance))`` equal parts (an overshoot shrinks with the square of the
  step), up to :data:`MAX_SPLIT`: the retimer evaluates Drake at the new grid
  points and solves again.

The segments and their sub-points are :mod:`._segments` (torque and wrench
coefficients there by Lagrange interpolation), the joint limits' rows and
cuts :mod:`._joint_cuts`; this module holds the grasp's midpoint rows and
the refinement of the grid. Grasp rows are looked at
between grid points if they come within :data:`ROW_SCREEN` of their bound at
a grid point (further away, a row cannot reach its bound inside a segment:
overshoots measured at 100 grid points stay below 3 %).
"""

from __future__ import annotations

import numpy as np

from rt_drake.dynamics.wrench import PathCoefficients
from rt_drake.retiming import _between_kernels as K
from rt_drake.retiming._samples import PathSamples
from rt_drake.retiming._segments import MIDDLE, Segments
from rt_drake.retiming.limits import JointLimits
from rt_drake.retiming.passes import StageRows
from rt_drake.retiming.seidel import kernel_array

#: Grasp rows with ``max_i F_k w_i / g_k`` above ``1 - ROW_SCREEN`` at the grid
#: points are evaluated between them.
ROW_SCREEN = 0.1
#: Parts a segment is split into, at most, per refinement.
MAX_SPLIT = 8


def grasp_midpoint_rows(
    segments: Segments, wrench: PathCoefficients, F: np.ndarray, g: np.ndarray
) -> StageRows:
    """Grasp rows at every segment's midpoint, as rows of its stage's LP.

    ``F_k (a(m) u_i + b(m) (x_i + ds_i u_i) + c(m)) <= g_k`` at
    ``m = s_i + ds_i / 2``, the coefficients interpolated: this quarters the
    overshoot between grid points before :func:`refinement_points` looks
    for it, so that few paths need a refinement.

    Args:
        segments: The grid's segments.
        wrench: Wrench coefficients at the grid points.
        F: (R, 6) the rows in force.
        g: (R,) their bounds.
    """
    shape = (len(segments.ds), len(g))
    A, B, C = np.empty(shape), np.empty(shape), np.empty(shape)
    K.midpoint_rows(
        *(kernel_array(v) for v in wrench),
        kernel_array(F),
        kernel_array(g),
        segments.s,
        segments.weights,
        segments.index,
        MIDDLE,
        A,
        B,
        C,
    )
    return StageRows(A, B, C)


def refinement_points(
    segments: Segments,
    samples: PathSamples,
    x: np.ndarray,
    u: np.ndarray,
    limits: JointLimits,
    normals: np.ndarray | None,
    row_max: np.ndarray | None,
    tolerance: float,
    grasp_ratio: np.ndarray | None = None,
) -> np.ndarray:
    """Grid points to add where torque or grasp is exceeded in a segment.

    Args:
        segments: The grid's segments.
        samples: The path at the grid points.
        x: (G,) ``s'^2`` at the grid points.
        u: (G-1,) ``s''`` per segment.
        limits: Joint limits.
        normals: (6, R) grasp rows ``F / g`` (transposed), or None.
        row_max: (R,) each grasp row's largest ``F_k w / g_k`` over the
            wrenches the stage LPs enforced (from the exactness check; exact
            where above ``1 - ROW_SCREEN``), or None.
        tolerance: Relative excess allowed.
        grasp_ratio: For a set of objects, (N, K) its worst object's largest
            ``F_k w / g_k`` and torque ratio at the sub-points (from
            :meth:`._robust_grasp.SetRows.between`; the samples' torques are
            then the arm's alone and not checked here), or None.

    Returns:
        Sorted new s values (empty: nothing exceeded).
    """
    checks: list[tuple[PathCoefficients, np.ndarray, bool]] = []
    if (
        samples.torque is not None
        and limits.torque is not None
        and samples.torque_set is None  # a set's torques come with its grasp
    ):
        checks.append((samples.torque, np.diag(1.0 / limits.torque), True))
    if samples.wrench is not None and normals is not None and row_max is not None:
        rows = np.flatnonzero(row_max > 1.0 - ROW_SCREEN)
        if rows.size:
            checks.append((samples.wrench, normals[:, rows], False))
    if not checks and grasp_ratio is None:
        return np.zeros(0)
    excess = np.full(len(u), -np.inf)
    if grasp_ratio is not None:
        excess = grasp_ratio.max(axis=1) - 1.0
    part = np.empty(len(u))
    x, u = kernel_array(x), kernel_array(u)
    for (a, b, c), rows_map, absolute in checks:
        K.affine_excess(
            segments.weights,
            segments.index,
            kernel_array(a),
            kernel_array(b),
            kernel_array(c),
            segments.step,
            x,
            u,
            kernel_array(rows_map),
            absolute,
            part,
        )
        np.maximum(excess, part, out=excess)
    split = np.flatnonzero(excess > tolerance)
    if not split.size:
        return np.zeros(0)
    parts = np.clip(np.ceil(np.sqrt(excess[split] / tolerance)), 2, MAX_SPLIT)
    s, ds = segments.s, segments.ds
    points = [
        s[i] + ds[i] * np.arange(1, k) / k
        for i, k in zip(split, parts.astype(int), strict=True)
    ]
    return np.sort(np.concatenate(points))


__all__ = [
    "MAX_SPLIT",
    "ROW_SCREEN",
    "grasp_midpoint_rows",
    "refinement_points",
]
