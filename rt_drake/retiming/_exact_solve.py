"""One TOPP-RA solve on a grid, exact for every grasp row: :func:`solve_exact`.

The stage LPs get the joint limits (:func:`joint_constraints`: ``|q' s'| <=
v_max`` as a bound on ``x = s'^2``, ``|q' u + q'' x| <= qdd_max``, torques
``|a u + b x + c| <= tau_max``, and rows inside the segments) and the grasp
rows ``F (a u + b x + c) <= g`` the family selected; the profile is then
checked against every row and the passes rerun until none is violated
(:mod:`._grasp_rows`, :mod:`._robust_grasp`).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import toppra
from toppra.constraint import LinearConstraint

from rt_drake.retiming._grasp_rows import ObjectRows
from rt_drake.retiming._joint_cuts import interior_rows
from rt_drake.retiming._retime_errors import PathNotControllableError
from rt_drake.retiming._robust_grasp import SetRows
from rt_drake.retiming._samples import PathSamples
from rt_drake.retiming._segments import Segments
from rt_drake.retiming.limits import JointLimits
from rt_drake.retiming.passes import (
    AffineConstraint,
    Engine,
    StageRows,
    XBound,
    reachability,
    stage_rows,
)


class Profile(NamedTuple):
    """The passes' profile, checked against every grasp row.

    Attributes:
        x: (N+1,) ``s'^2`` at the grid points; u: (N,) ``s''`` per segment.
        ratio: With a grasp, ``max_k F_k w / g_k`` (N+1,) at each grid point
            (the acceleration of the segment that starts there; the last
            point takes the last one; for a set, the worst object's); else
            None.
        screen: With a grasp, what tells the grasp rows where to look between
            grid points (:class:`~._grasp_rows.Check`); else None.
    """

    x: np.ndarray
    u: np.ndarray
    ratio: np.ndarray | None
    screen: np.ndarray | None


def joint_constraints(
    samples: PathSamples, segments: Segments, limits: JointLimits
) -> list[LinearConstraint]:
    """The joint limits: at the grid points, and inside segments.

    Velocity and acceleration at the grid points, torques, and the rows of
    :func:`~._between.interior_rows` inside the segments.
    """
    s, dq, ddq = samples.s, samples.dq, samples.ddq
    n = dq.shape[1]
    box = np.vstack([np.eye(n), -np.eye(n)])
    constraints: list[LinearConstraint] = [
        XBound(np.column_stack([np.zeros_like(s), samples.x_cap])),
        AffineConstraint(
            dq, ddq, np.zeros_like(dq), box, np.tile(limits.acceleration, 2)
        ),
        interior_rows(segments, limits),
    ]
    if (
        samples.torque is not None
        and limits.torque is not None
        and samples.torque_set is None  # a set's torques: with its grasp rows
    ):
        constraints.append(
            AffineConstraint(*samples.torque, box, np.tile(limits.torque, 2))
        )
    return constraints


def solve_exact(
    samples: PathSamples,
    segments: Segments,
    fixed: list[LinearConstraint],
    family: ObjectRows | SetRows | None,
    spline: toppra.SplineInterpolator | None,
    sd_start: float,
    sd_end: float,
    engine: Engine,
) -> Profile:
    """TOPP-RA with the grasp rows selected, adding missed rows until none.

    ``fixed``: every other constraint (:func:`joint_constraints`, cuts);
    ``family``: the grasp rows (:mod:`._grasp_rows`, :mod:`._robust_grasp`).
    With a grasp the compiled engine projects ``fixed`` once for all the
    solves.
    """
    s = samples.s
    base = None
    if family is not None:
        family.begin()
        if engine is Engine.COMPILED:
            base = stage_rows(fixed, np.diff(s))
    while True:
        constraints = [] if base is not None else list(fixed)
        if family is not None:
            constraints += family.constraints(samples, segments)
        solution = reachability(constraints, spline, s, sd_start, sd_end, engine, base)
        if solution.x is None or solution.u is None:
            if family is not None and family.widen():
                continue
            where = float(s[solution.failed_stage or 0])
            raise PathNotControllableError(
                f"path not controllable from s = {where:.3f}: no admissible path "
                f"velocity there reaches the end at s' = {sd_end:g} 1/s within the "
                "limits",
                s=where,
            )
        if family is None:
            return Profile(solution.x, solution.u, None, None)
        check = family.check(samples, segments, solution.x, solution.u)
        if not check.added:
            return Profile(solution.x, solution.u, check.ratio, check.screen)


def stacked_cuts(first: StageRows, second: StageRows) -> StageRows:
    """Both sets of cuts (side by side)."""
    return StageRows(
        *(np.hstack([a, b]) for a, b in zip(first.rows, second.rows, strict=True))
    )
