"""Realizability of a wrench by linear programming (independent of the H-rep).

A wrench w (``[torque; force]`` on the object, about and in the cup frame C,
N*m and N) is realizable when rim forces exist with

    sum_i G_i f_i + [0, 0, 0, 0, 0, -P A] = w,
    A_fric f_i <= 0,  0 <= (f_i)_z <= f_max       (the pyramid in H-form),

see :mod:`rt_drake.contact.cup`. The LP below (HiGHS, via scipy) finds the
smallest residual ``t = min ||sum_i G_i f_i + suction - w||_inf`` over those
forces: t = 0 exactly when w is realizable, and for a wrench at distance
delta outside W_c, ``t >= delta / sqrt(6)``. It uses the friction cone's
inequalities, not the vertex list of the Minkowski enumeration, so tests can
check one against the other.
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import block_diag
from scipy.optimize import linprog

from rt_drake.contact.cup import (
    CupParameters,
    friction_halfspaces,
    grasp_matrices,
    suction_wrench,
)
from rt_drake.errors import InputError

_HIGHS_OPTIONS = {
    "primal_feasibility_tolerance": 1e-10,
    "dual_feasibility_tolerance": 1e-10,
}


def lp_residual(wrenches: np.ndarray, cup: CupParameters) -> np.ndarray:
    """Return ``min ||sum_i G_i f_i + suction - w||_inf`` for each wrench.

    Args:
        wrenches: (..., 6) wrenches ``[torque; force]`` on the object in C.
        cup: The cup model.

    Returns:
        Residuals of shape ``wrenches.shape[:-1]``, in mixed N*m / N units.
    """
    wrenches = np.asarray(wrenches, dtype=float)
    if wrenches.shape[-1:] != (6,):
        raise InputError(f"{wrenches.shape=}: need (..., 6) wrenches")
    m = cup.points
    G = np.hstack(list(grasp_matrices(cup)))  # (6, 3m)
    A, _ = friction_halfspaces(cup)
    polygon = block_diag(*([A[: cup.sides]] * m))  # (k m, 3m)
    ones = np.ones((6, 1))
    A_ub = np.vstack(
        [
            np.hstack([polygon, np.zeros((len(polygon), 1))]),
            np.hstack([G, -ones]),
            np.hstack([-G, -ones]),
        ]
    )
    bounds = [(None, None), (None, None), (0.0, cup.max_normal_force)] * m
    bounds.append((0.0, None))
    cost = np.zeros(3 * m + 1)
    cost[-1] = 1.0
    flat = wrenches.reshape(-1, 6) - suction_wrench(cup)
    residuals = np.empty(len(flat))
    for row, target in enumerate(flat):
        b_ub = np.concatenate([np.zeros(len(polygon)), target, -target])
        result = linprog(
            cost,
            A_ub=A_ub,
            b_ub=b_ub,
            bounds=bounds,
            method="highs",
            options=_HIGHS_OPTIONS,
        )
        if result.status != 0:
            raise ArithmeticError(f"HiGHS failed on wrench {row}: {result.message}")
        residuals[row] = result.fun
    return residuals.reshape(wrenches.shape[:-1])


def is_realizable_lp(
    wrenches: np.ndarray, cup: CupParameters, tol: float = 1e-8
) -> np.ndarray:
    """Return whether each (..., 6) wrench is realizable, by :func:`lp_residual`.

    ``tol`` bounds the residual accepted as zero (N*m / N).
    """
    return lp_residual(wrenches, cup) <= tol
