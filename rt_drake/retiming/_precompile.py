"""Compile the retimer's numba kernels before anything is timed.

numba compiles a kernel at its first call (about 7 s for all of them on the
2-core benchmark machine) and caches the machine code beside the module, so
later processes only load it (about 0.3 s). :func:`warm_up` makes that first
call on a three-point problem with the argument types the retimer uses, so
that the first real retime of a process (e.g. the first MOVE of a simulated
cycle, whose planning time Table II reports) costs what the others cost.
"""

from __future__ import annotations

import functools

import numpy as np
from scipy import sparse

from rt_drake.dynamics import chain_kernels as _chain_kernels
from rt_drake.dynamics.wrench import PathCoefficients
from rt_drake.retiming import _between as between
from rt_drake.retiming import _joint_cuts as joint_cuts
from rt_drake.retiming import _segments as sub_points
from rt_drake.retiming import (
    stage_rows as rows,
)
from rt_drake.retiming._band_lp import BandLP
from rt_drake.retiming._between_kernels import position_excess
from rt_drake.retiming._jerk_kernels import (
    acceleration_ratios,
    grasp_screen,
    jerk_ratios,
    joint_ratios,
    row_max,
)
from rt_drake.retiming._jerk_row_kernels import csr_product, csr_rows
from rt_drake.retiming._jerk_rows import Band, affine_rows, jerk_rows
from rt_drake.retiming._jerk_timed_path import quadrature_duration
from rt_drake.retiming._joint_path import as_joint_path
from rt_drake.retiming._robust_rows import (
    Layout,
    worst_rows,
)
from rt_drake.retiming._samples import PathSamples
from rt_drake.retiming.limits import JointLimits
from rt_drake.retiming.passes import AffineConstraint, XBound, reachability


@functools.cache
def warm_up() -> None:
    """Compile (or load from the cache) every kernel once per process."""
    grid = np.linspace(0.0, 1.0, 3)
    ones, zeros = np.ones((3, 1)), np.zeros((3, 1))
    # -1 <= u + x <= 1 and 0 <= x <= 1 at every grid point.
    band = AffineConstraint(ones, ones, zeros, np.array([[1.0], [-1.0]]), np.ones(2))
    x_bound = XBound(np.column_stack([np.zeros(3), np.ones(3)]))
    reachability([x_bound, band], None, grid)
    F = np.vstack([np.eye(6), -np.eye(6)])
    normals = rows.normalised_rows(F, np.ones(12))
    wrench = np.full((3, 6), 0.1)
    rows.rest_and_candidates(wrench, wrench, 0.0 * wrench, normals, grid + 1.0)
    rows.wrench_ratios(wrench, normals, np.ones(12), 1e-9)
    # A set of objects (robust grasp): one box of four columns, and one for
    # torques (another row dimension).
    layout = Layout(np.array([[0, 1, 2, 2, 3, 4]]), np.array([[1.0, 2.0]]))
    for dims in (6, 5):
        part = np.full((3, 4, dims), 0.1)
        worst_rows(
            (part, part, part), np.arange(3), grid, grid, np.ones((dims, 2)), layout
        )
    # Between grid points: one joint, torques and a wrench.
    path = np.column_stack([grid**2])
    coefficients = PathCoefficients(wrench, wrench, 0.0 * wrench)
    torque = PathCoefficients(path, path, path)
    samples = PathSamples(
        grid, path, 2 * grid[:, None], 2 + 0 * path, grid, torque, coefficients
    )
    limits = JointLimits(np.ones(1), np.ones(1), np.ones(1))
    segments = sub_points.Segments(samples, grid[[0, -1]], as_joint_path(path))
    joint_cuts.interior_rows(segments, limits)
    x, u = np.full(3, 0.5), np.zeros(2)
    joint_cuts.joint_cuts(segments, x, u, limits, 1e-3)
    between.refinement_points(
        segments, samples, x, u, limits, normals, np.ones(12), 1e-3
    )
    segments.enforced_wrenches(coefficients, x, u)
    between.grasp_midpoint_rows(segments, coefficients, F, np.ones(12))
    position_excess(grid, path, path, path, -np.ones(1), np.ones(1), 1e-9)
    # The jerk-limited retimer's grasp screen: three points, twelve rows.
    over = np.zeros((3, 12), dtype=bool)
    every = np.arange(3, dtype=np.int64)
    grasp_screen(
        wrench, wrench, wrench, grid, grid, normals, 0.5, every, over, np.empty(3)
    )
    # Its jerk ratios: three points on one segment (z = [x_0, x_1, u_0, u_1]).
    cols = np.array([[0, 2, 3]] * 3, dtype=np.int64)
    entries = np.zeros((3, 3))
    jerk_ratios(cols, entries, entries, entries, np.ones(4), path, path, path,
                np.ones(1), np.ones(3, dtype=bool), np.empty((3, 1)))  # fmt: skip
    # Their velocity and acceleration ratios, and the largest per point.
    joint_ratios(cols, entries, entries, np.ones(4), path, path, np.ones(3),
                 np.ones(1), np.empty(3))  # fmt: skip
    acceleration_ratios(cols, entries, entries, np.ones(4), path, path, np.ones(1),
                        every, np.empty((3, 1)))  # fmt: skip
    row_max(path, np.empty(3))
    # Its LP rows (jerk, affine) and its duration by quadrature.
    kinds = np.zeros(2, dtype=int)
    jerk_band = Band.of(grid, kinds, np.zeros(3, dtype=np.int64), grid)
    jerk_rows(jerk_band, every, 7, (path, path, path), np.ones(3), np.ones(1),
              np.ones((3, 1), dtype=bool))  # fmt: skip
    affine_rows(jerk_band, every, 2, zeros, ones, ones)
    quadrature_duration(grid, np.ones(3), np.zeros(3))
    # Its LPs' sparse rows (scipy's int32 indices).
    matrix = sparse.csr_matrix(np.eye(3))
    csr_product(matrix.indptr, matrix.indices, matrix.data, grid)
    csr_rows(matrix.indptr, matrix.indices, matrix.data, every)
    # Its LP solver: one segment, z = [x_0, x_1, u_0, u_1], continuity and
    # x_1 <= 1; from a guess (the crash), then warm.
    solver = BandLP()
    solver.guess(np.array([0.0, 0.5, 0.0, 0.0]))
    continuity = sparse.csr_matrix(np.array([[-1.0, 1.0, -0.5, -0.5]]))
    cap = sparse.csr_matrix(np.array([[0.0, 1.0, 0.0, 0.0]]))
    box = np.array([[0.0, 0.0], [0.0, np.inf], [-1.0, 1.0], [-1.0, 1.0]])
    for _ in range(2):
        solver.solve(-grid[[0, 1, 2, 2]], cap, np.ones(1), np.zeros(1, dtype=np.int64),
                   continuity, np.zeros(1), box)  # fmt: skip
    # The object wrench on a serial chain (rt_drake.dynamics.chain): two joints.
    q, steps = np.zeros((3, 2)), np.tile(np.eye(4), (2, 1, 1))
    z, o = np.empty((3, 2, 3)), np.empty((3, 2, 3))
    R, p = np.empty((3, 3, 3)), np.empty((3, 3))
    index, axis = np.arange(2, dtype=np.int64), np.tile([0.0, 0.0, 1.0], (2, 1))
    _chain_kernels.frames(q, steps, steps, index, axis, np.eye(4), z, o, R, p)
    motion = np.empty((4, 3, 3))
    _chain_kernels.accelerations(z, o, R, p, q, q, np.zeros(3), motion)
    a_w, b_w, c_w = (np.empty((3, 6)) for _ in range(3))
    _chain_kernels.wrench_terms(
        R, motion, 1.0, np.zeros(3), np.eye(3), np.zeros(3), a_w, b_w, c_w
    )


__all__ = ["warm_up"]
