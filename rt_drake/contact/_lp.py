"""Realizability of a wrench by linear programming (independent of the H-rep).

A wrench w (``[torque; force]`` on the object, about and in the cup frame C,
N*m and N) is realizable when rim forces exist with

    sum_i G_i f_i + [0, 0, 0, 0, 0, -P A] = w,
    A_fric f_i <= 0,  0 <= (f_i)_z <= f_max       (the pyramid in H-form),

see :mod:`rt_drake.contact._cup`. The LP below (HiGHS, via scipy) finds the
smallest residual ``t = min ||sum_i G_i f_i + suction - w||_inf`` over those
forces: t = 0 exactly when w is realizable, and for a wrench at distance
delta outside W_c, ``t >= delta / sqrt(6)``. It uses the friction cone's
inequalities, not the vertex list of the Minkowski enumeration, so tests can
check one against the other.

For a multi-cup tool (:mod:`rt_drake.contact.tool`) the same LP runs over
every rim force of every cup, each mapped to the tool frame T by its cup's
adjoint: ``w_T = sum_c Ad_c (sum_i G_ci f_ci + suction_c)``, with each f_ci
in its own cup's pyramid; w is then about T's origin, in T.
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import block_diag
from scipy.optimize import linprog

from rt_drake import arguments
from rt_drake.contact._cup import (
    CupParameters,
    contact_positions,
    contact_rotations,
    friction_halfspaces,
)
from rt_drake.contact.tool import ToolParameters

_HIGHS_OPTIONS = {
    "primal_feasibility_tolerance": 1e-10,
    "dual_feasibility_tolerance": 1e-10,
}


def _point_forces(
    source: CupParameters | ToolParameters,
) -> tuple[np.ndarray, np.ndarray, list[tuple[float | None, float | None]], np.ndarray]:
    """Return the LP's data over all rim forces (3 per rim point).

    Each rim point P (a cup's contact frame) is placed in the tool frame T by
    ``p_TP = p_TC + R_TC p_CP`` and ``R_TP = R_TC R_CP``; its force f (in P)
    gives the wrench ``[p_TP x (R_TP f); R_TP f]`` about T's origin, and the
    suction force ``-P A z_C`` acts at C's origin. A cup alone is a tool with
    C = T.

    Returns ``G`` (6, 3n): forces -> wrench, the friction polygons' rows
    ``A f <= 0`` (block diagonal), the bounds of every force component, and
    the constant suction wrench.
    """
    if isinstance(source, ToolParameters):
        mounts = [(m.cup, m.R_TC, m.p_TC) for m in source.cups]
    else:
        mounts = [(source, np.eye(3), np.zeros(3))]
    columns, polygons, bounds, suction = [], [], [], np.zeros(6)
    for cup, R_TC, p_TC in mounts:
        positions = p_TC + contact_positions(cup) @ R_TC.T
        for p_TP, R_TP in zip(positions, R_TC @ contact_rotations(cup), strict=True):
            columns.append(np.vstack([np.cross(p_TP, R_TP.T).T, R_TP]))
        A, _ = friction_halfspaces(cup)
        polygons += [A[: cup.sides]] * cup.points
        bounds += [(None, None), (None, None), (0.0, cup.max_normal_force)] * cup.points
        pull = -cup.suction_force * R_TC[:, 2]
        suction += np.concatenate([np.cross(p_TC, pull), pull])
    return np.hstack(columns), block_diag(*polygons), bounds, suction


def lp_residual(
    wrenches: np.ndarray, cup: CupParameters | ToolParameters
) -> np.ndarray:
    """Return ``min ||sum_i G_i f_i + suction - w||_inf`` for each wrench.

    Args:
        wrenches: (..., 6) wrenches ``[torque; force]`` on the object, in C
            for a cup, in T (about T's origin) for a tool.
        cup: The cup model, or a multi-cup tool (all its rim forces).

    Returns:
        Residuals of shape ``wrenches.shape[:-1]``, in mixed N*m / N units.

    Raises:
        InputError: a shape other than (..., 6), NaN or inf, a bad cup or tool.
    """
    return _residuals(wrenches, cup, springs=False)


def shared_load_residual(wrenches: np.ndarray, tool: ToolParameters) -> np.ndarray:
    """:func:`lp_residual` with the rims' normal forces split by equal springs.

    The LP of :func:`lp_residual` over every rim force of ``tool``, plus
    three free variables c (a rigid displacement of the object on the tool,
    times the springs' stiffness) and the equalities ``(f_i)_z = c_1 y_i -
    c_2 x_i + c_3``: each point's normal force is what its spring carries
    (:mod:`rt_drake.contact.load_sharing`). Independent of that module's
    rows: it uses the pyramids' H-form and no split matrix. Every cup must
    lie in T's z = 0 plane with its axis along T's z.
    """
    return _residuals(wrenches, tool, springs=True)


def _residuals(
    wrenches: np.ndarray, source: CupParameters | ToolParameters, springs: bool
) -> np.ndarray:
    """The residual LP of :func:`lp_residual`, with the spring rows if asked.

    Variables: every rim force, then (``springs``) the displacement c (3),
    then the residual t; ``springs`` adds ``(f_i)_z - A_i c = 0`` per point.
    """
    where = "shared_load_residual" if springs else "is_realizable_lp"
    wrenches = arguments.array(wrenches, "wrenches", ("...", 6), where=where)
    kinds = ToolParameters if springs else (CupParameters, ToolParameters)
    arguments.instance(source, "tool" if springs else "cup", kinds, where=where)
    source.validate()
    G, polygon, bounds, suction = _point_forces(source)
    forces = G.shape[1]
    extra = 3 if springs else 0
    A_eq, b_eq = None, None
    if springs:
        assert isinstance(source, ToolParameters)
        points = forces // 3
        xy = np.vstack(
            [
                m.p_TC[:2] + contact_positions(m.cup)[:, :2] @ m.R_TC[:2, :2].T
                for m in source.cups
            ]
        )
        A_eq = np.zeros((points, forces + extra + 1))
        A_eq[np.arange(points), 3 * np.arange(points) + 2] = 1.0
        A_eq[:, forces : forces + 3] = -np.column_stack(
            [xy[:, 1], -xy[:, 0], np.ones(points)]
        )
        b_eq = np.zeros(points)
    ones = np.ones((6, 1))
    free = np.zeros((6, extra))
    A_ub = np.vstack(
        [
            np.hstack([polygon, np.zeros((len(polygon), extra + 1))]),
            np.hstack([G, free, -ones]),
            np.hstack([-G, free, -ones]),
        ]
    )
    all_bounds = [*bounds, *[(None, None)] * extra, (0.0, None)]
    cost = np.zeros(forces + extra + 1)
    cost[-1] = 1.0
    flat = wrenches.reshape(-1, 6) - suction
    residuals = np.empty(len(flat))
    for row, target in enumerate(flat):
        b_ub = np.concatenate([np.zeros(len(polygon)), target, -target])
        result = linprog(
            cost,
            A_ub=A_ub,
            b_ub=b_ub,
            A_eq=A_eq,
            b_eq=b_eq,
            bounds=all_bounds,
            method="highs",
            options=_HIGHS_OPTIONS,
        )
        if result.status != 0:
            raise ArithmeticError(f"HiGHS failed on wrench {row}: {result.message}")
        residuals[row] = result.fun
    return residuals.reshape(wrenches.shape[:-1])


def is_realizable_lp(
    wrenches: np.ndarray, cup: CupParameters | ToolParameters, tol: float = 1e-8
) -> np.ndarray:
    """Return whether each (..., 6) wrench is realizable, by :func:`lp_residual`.

    ``tol`` bounds the residual accepted as zero (N*m / N).
    """
    arguments.number(tol, "tol", where="is_realizable_lp", low=0.0)
    return lp_residual(wrenches, cup) <= tol
