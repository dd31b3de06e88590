"""Compile (or load from numba's cache) the optimiser's kernels ahead of time.

As the retimer's ``rt_drake.retiming.warm_up``: the first call of a numba
kernel compiles it (seconds); :func:`warm_up` makes that call on tiny inputs
of the types the optimiser uses, so that the first timed MOVE costs what the
others cost. It also imports the search's ``cmaes`` (which loads
``scipy.stats``: about 1.5 s, once per process), imported lazily by
:func:`~._search.cma_search` so that processes which never shape a path do
not pay for it, and which would otherwise land in the first timed MOVE's plan.
"""

from __future__ import annotations

import functools
import importlib

import numpy as np

from rt_drake.dynamics import chain_kernels as _chain_kernels
from rt_drake.retiming import warm_up as warm_up_retimer
from rt_drake.shaping import _pose_kernels as _fk
from rt_drake.shaping._clearance import _clearance
from rt_drake.shaping._finish import _thin
from rt_drake.shaping._spline import evaluate_splines
from rt_drake.shaping._surrogate import _batch_durations


@functools.cache
def warm_up() -> None:
    """Compile every kernel of the optimiser (and the retimer's) once per process."""
    warm_up_retimer()
    importlib.import_module("cmaes")
    n, points = 2, 3
    q = np.zeros((points, n))
    steps = np.tile(np.eye(4), (n, 1, 1))
    index = np.arange(n, dtype=np.int64)
    axis = np.tile([0.0, 0.0, 1.0], (n, 1))
    z, o = np.empty((points, n, 3)), np.empty((points, n, 3))
    R, p = np.empty((points, 3, 3)), np.empty((points, 3))
    _chain_kernels.frames(q, steps, steps, index, axis, np.eye(4), z, o, R, p)
    _fk.solve_poses(
        q.copy(), R.copy(), p.copy(), steps, steps, index, axis, np.eye(4), index, 2,
        1e-10, np.empty(points),
    )  # fmt: skip
    out = np.empty((4, points, 3))
    _chain_kernels.accelerations(z, o, R, p, q, q, np.zeros(3), out)
    dq, ddq = evaluate_splines(np.arange(6.0).reshape(1, 3, 2), np.linspace(0, 1, 3))[
        1:
    ]
    wrench = np.ones((1, points, 6))
    F = np.vstack([np.eye(6), -np.eye(6)])
    _batch_durations(
        dq, ddq, wrench, 0.0 * wrench, -0.1 * wrench, np.ones(n),
        np.vstack([np.eye(n), -np.eye(n)]), np.ones(2 * n), F, np.ones(12),
        np.ascontiguousarray(F.T), np.ones(12, dtype=np.bool_), np.full((1, 2), 0.5),
        np.inf, np.empty(1), np.zeros(1, dtype=np.bool_),
        np.zeros((1, 12), dtype=np.bool_), np.zeros((1, points)),
    )  # fmt: skip
    _thin(np.linspace(0.0, 1.0, points), 0.01)
    boxes = np.ones((1, 3))
    _clearance(
        R, p, np.zeros((1, 3)), np.ones(1), np.eye(3)[None], boxes, boxes, 1.0, 0.1,
        np.empty(points),
    )  # fmt: skip


__all__ = ["warm_up"]
