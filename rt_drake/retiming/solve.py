"""Time-optimal retiming of a joint path under grasp stability: :func:`retime`.

:func:`retime` finds the fastest time scaling s(t) of a path ``q(s)`` (the
planner's clamped spline) such that, rest to rest,

- ``|q'(s) s'| <= v_max`` and ``|q'(s) s'' + q''(s) s'^2| <= qdd_max``;
- optionally ``|tau| <= tau_max`` (inverse dynamics with the held object);
- optionally the grasp ``F (a(s) s'' + b(s) s'^2 + c(s)) <= g``, the object
  wrench of :mod:`rt_drake.dynamics` in the grasp polytope of
  :mod:`rt_drake.contact` (paper eqs 1, 6, 20),

by TOPP-RA on a uniform grid with toppra's interpolation discretization and
its seidel LP, compiled (:mod:`.passes`).

Exactness of the grasp rows: the polytope has hundreds of rows (834 for the
paper's cup) and only a few dozen bound the (u, x) slices along a path. The
stage LPs get the rows that ray shooting picks along the path
(:func:`rt_drake.retiming.rows.rest_and_candidates`); then every row is
evaluated at every (u, x) the LPs enforced (both interpolation blocks,
:func:`rt_drake.retiming.rows.wrench_ratios`), and any violated row is added
and the passes rerun (``repairs``). The returned profile is then admissible
for the full constraint and, as TOPP-RA's pointwise-maximal profile of a
relaxation of it, the very profile TOPP-RA computes with all rows (the tests
compare with toppra on all rows).

The robot must be able to stop anywhere on the path: the object must be held
by gravity's wrench alone (``F c(s) < g``) and the arm's gravity torques must
be within limits at every grid point, else a typed error says where.
"""

from __future__ import annotations

import dataclasses
from typing import Any, NamedTuple

import numpy as np
import toppra
from pydrake.multibody.plant import MultibodyPlant
from pydrake.systems.framework import Context
from toppra.constraint import LinearConstraint

from rt_drake.dynamics import (
    PathCoefficients,
    path_torque_coefficients,
    path_wrench_coefficients,
)
from rt_drake.retiming import rows as R
from rt_drake.retiming.at_rest import check_grasp_at_rest, check_torque_at_rest
from rt_drake.retiming.errors import (
    PathNotControllableError,
    RetimeInputError,
    RetimeStatus,
)
from rt_drake.retiming.limits import GraspConstraint, JointLimits
from rt_drake.retiming.passes import AffineConstraint, XBound, reachability
from rt_drake.retiming.path import path_spline, toppra_path
from rt_drake.retiming.timed_path import TimedPath

#: Grasp rows violated by more than this (N or N m) are added and re-solved.
ROW_TOLERANCE = 1e-9
#: Most grid points accepted (the dynamics and the passes are linear in
#: them: 100 000 take about 4 s and 0.6 GB with the grasp constraint).
MAX_GRIDPOINTS = 100_000


@dataclasses.dataclass(frozen=True, eq=False)
class RetimeResult:
    """A retimed path.

    Attributes:
        trajectory: q(t) (Drake ``Trajectory``; q', q'' by ``EvalDerivative``).
        duration: s.
        gridpoints: (N+1,) grid s_i.
        sd: (N+1,) path velocity ``s'(s_i)``, 1/s (the s'(s) profile).
        sdd: (N,) constant path acceleration ``s''`` on each segment, 1/s^2.
        margin: (N+1,) smallest relative slack of all constraints at each grid
            point (1 - |value| / limit; for the grasp ``min (g - F w) / g``),
            taking the acceleration of the segment that starts there.
        margins: The same per constraint ("velocity", "acceleration",
            "torque", "grasp"), for those in force.
        status: Always ``RetimeStatus.OK`` (failures raise ``RetimeError``).
        grasp_rows: Rows of the grasp polytope the stage LPs used (of
            ``len(grasp.g)``).
        repairs: Times the exactness check added rows and solved again.
    """

    trajectory: TimedPath
    duration: float
    gridpoints: np.ndarray
    sd: np.ndarray
    sdd: np.ndarray
    margin: np.ndarray
    margins: dict[str, np.ndarray]
    status: RetimeStatus
    grasp_rows: int
    repairs: int


def retime(
    plant: MultibodyPlant,
    path: Any,
    limits: JointLimits,
    grasp: GraspConstraint | None = None,
    gridpoints: int | np.ndarray = 100,
    *,
    sd_start: float = 0.0,
    sd_end: float = 0.0,
    start_time: float = 0.0,
    context: Context | None = None,
    engine: str = "compiled",
) -> RetimeResult:
    """Retime ``path`` time-optimally under ``limits`` and ``grasp``.

    Args:
        plant: Finalized plant of the arm and tool only (objects welded or
            left out); positions = the path's joints; frame ``suction_cup``.
        path: ``GeometricPath`` (``.waypoints``, ``.knots``) or (K, n)
            waypoints (chord-length knots).
        limits: Joint limits (torques limited if ``limits.torque``).
        grasp: Held object and grasp polytope; None: no object.
        gridpoints: Number of uniform grid points in s (>= 2), or the grid.
        sd_start: Path velocity ds/dt at the start (1/s; 0 = rest).
        sd_end: Path velocity ds/dt at the end (1/s; 0 = rest).
        start_time: Time (s) at which the trajectory starts.
        context: Scratch context of ``plant``.
        engine: "compiled" or "toppra" (see :mod:`rt_drake.retiming.passes`).

    Raises:
        RetimeInputError: malformed path, limits or grid, or ``sd_start``,
            ``sd_end`` not finite and >= 0, ``start_time`` not finite.
        GraspUnstableAtRestError: gravity alone breaks the grasp somewhere.
        TorqueLimitAtRestError: holding the arm still exceeds a torque limit.
        PathNotControllableError: no admissible speed reaches the end.
    """
    _check_arguments(sd_start, sd_end, start_time)
    spline = path_spline(path)  # checks the path
    n = spline.c.shape[2]
    if n != plant.num_positions() or n != limits.num_joints:
        raise RetimeInputError(
            f"path has {n} joints but {plant.num_positions()=} and {limits.num_joints=}"
        )
    s = _grid(gridpoints)
    ds = np.diff(s)
    q, dq, ddq = spline(s), spline(s, 1), spline(s, 2)
    context = context or plant.CreateDefaultContext()
    with np.errstate(divide="ignore"):
        x_cap = np.min(limits.velocity**2 / dq**2, axis=1)
    box = np.vstack([np.eye(n), -np.eye(n)])
    fixed = [
        XBound(np.column_stack([np.zeros_like(s), x_cap])),
        AffineConstraint(
            dq, ddq, np.zeros_like(dq), box, np.tile(limits.acceleration, 2)
        ),
    ]
    tau = terms = None
    if limits.torque is not None:
        held = grasp.held if grasp is not None else None
        tau = path_torque_coefficients(plant, q, dq, ddq, held, context)
        check_torque_at_rest(s, tau.c, limits.torque)
        fixed.append(AffineConstraint(*tau, box, np.tile(limits.torque, 2)))
    if grasp is not None:
        wrench = path_wrench_coefficients(plant, grasp.held, q, dq, ddq, context)
        terms = _GraspTerms(grasp, wrench, R.normalised_rows(grasp.F, grasp.g))
        rest, rows = R.rest_and_candidates(*wrench, terms.normals, x_cap)
        check_grasp_at_rest(s, rest, wrench.c, grasp)
    else:
        rows = np.zeros(0, dtype=int)
    # The compiled passes do not need the path; toppra's TOPPRA class does.
    toppra_spline = toppra_path(path) if engine == "toppra" else None
    profile = _solve_exact(
        fixed, terms, rows, toppra_spline, s, sd_start, sd_end, engine
    )
    trajectory = TimedPath(spline, s, profile.x, start_time)
    u = (profile.x[1:] - profile.x[:-1]) / (2.0 * ds)
    margins = _margins(limits, dq, ddq, profile.x, u, tau)
    if profile.ratio is not None:
        margins["grasp"] = 1.0 - profile.ratio
    return RetimeResult(
        trajectory=trajectory,
        duration=trajectory.duration,
        gridpoints=s,
        sd=np.sqrt(np.maximum(profile.x, 0.0)),
        sdd=u,
        margin=np.min(np.vstack(list(margins.values())), axis=0),
        margins=margins,
        status=RetimeStatus.OK,
        grasp_rows=len(profile.rows),
        repairs=profile.repairs,
    )


class _GraspTerms(NamedTuple):
    """The grasp constraint along the path: ``F (a u + b x + c) <= g``."""

    grasp: GraspConstraint
    wrench: PathCoefficients  # a, b, c at the grid points
    normals: np.ndarray  # (6, R) F / g, transposed


class _Profile(NamedTuple):
    """The passes' profile with the grasp rows it needed.

    Attributes:
        x: (N+1,) ``s'^2`` at the grid points; u: (N,) ``s''`` per segment.
        rows: The grasp rows the stage LPs used; repairs: how often the
            exactness check added rows.
        ratio: With a grasp, ``max_k F_k w / g_k`` (N+1,) at each grid point
            (the acceleration of the segment that starts there; the last
            point takes the last one); else None.
    """

    x: np.ndarray
    u: np.ndarray
    rows: np.ndarray
    repairs: int
    ratio: np.ndarray | None


def _solve_exact(
    fixed: list[LinearConstraint],
    terms: _GraspTerms | None,
    rows: np.ndarray,
    spline: toppra.SplineInterpolator | None,
    s: np.ndarray,
    sd_start: float,
    sd_end: float,
    engine: str,
) -> _Profile:
    """TOPP-RA with the selected grasp rows, adding missed rows until none."""
    repairs = 0
    while True:
        constraints = list(fixed)
        if terms is not None:
            F, g = terms.grasp.F, terms.grasp.g
            constraints.append(AffineConstraint(*terms.wrench, F[rows], g[rows]))
        solution = reachability(constraints, spline, s, sd_start, sd_end, engine)
        if solution.x is None or solution.u is None:
            if terms is not None and len(rows) < len(terms.grasp.g):
                rows = np.arange(len(terms.grasp.g))  # confirm with every row
                repairs += 1
                continue
            where = float(s[solution.failed_stage or 0])
            raise PathNotControllableError(
                f"path not controllable from s = {where:.3f}: no admissible path "
                f"velocity there reaches the end at s' = {sd_end:g} 1/s within the "
                "limits",
                s=where,
            )
        if terms is None:
            return _Profile(solution.x, solution.u, rows, repairs, None)
        ratio, violated = R.wrench_ratios(
            _enforced_wrenches(terms.wrench, solution.x, solution.u, np.diff(s)),
            terms.normals,
            terms.grasp.g,
            ROW_TOLERANCE,
        )
        missed = np.setdiff1d(violated, rows) if violated.size else violated
        if not missed.size:
            return _Profile(solution.x, solution.u, rows, repairs, ratio[: len(s)])
        rows = np.union1d(rows, missed)
        repairs += 1


def _enforced_wrenches(
    wrench: PathCoefficients, x: np.ndarray, u: np.ndarray, ds: np.ndarray
) -> np.ndarray:
    """The (2N+1, 6) wrenches ``w = a u + b x + c`` the stage LPs enforced.

    Stage i (i < N) enforced ``s_i`` at ``(u_i, x_i)`` (rows 0..N-1) and
    ``s_{i+1}`` at ``(u_i, x_i + 2 ds_i u_i)`` (rows N+1..2N). Row N is the
    end point at ``(u_{N-1}, x_N)``, for its margin.
    """
    a, b, c = wrench
    u_at = np.append(u, u[-1])[:, None]
    x_next = (x[:-1] + 2.0 * ds * u)[:, None]
    here = a * u_at + b * x[:, None] + c
    following = a[1:] * u[:, None] + b[1:] * x_next + c[1:]
    return np.vstack([here, following])


def _check_arguments(sd_start: float, sd_end: float, start_time: float) -> None:
    """Refuse NaN, inf or negative path velocities and a NaN start time."""
    for name, value in (("sd_start", sd_start), ("sd_end", sd_end)):
        if not (isinstance(value, (int, float, np.number)) and np.isfinite(value)):
            raise RetimeInputError(f"{name} must be a finite number, got {value!r}")
        if value < 0.0:
            raise RetimeInputError(f"{name} must be >= 0 (1/s), got {value!r}")
    if not (
        isinstance(start_time, (int, float, np.number)) and np.isfinite(start_time)
    ):
        raise RetimeInputError(f"start_time must be finite, got {start_time!r}")


def _grid(gridpoints: int | np.ndarray) -> np.ndarray:
    if np.ndim(gridpoints) == 0:
        if isinstance(gridpoints, bool) or not isinstance(
            gridpoints, (int, np.integer)
        ):
            raise RetimeInputError(f"gridpoints must be an integer, got {gridpoints!r}")
        count = int(gridpoints)
        if not 2 <= count <= MAX_GRIDPOINTS:
            raise RetimeInputError(
                f"gridpoints must be an integer in [2, {MAX_GRIDPOINTS}], "
                f"got {gridpoints!r}"
            )
        return np.linspace(0.0, 1.0, count)
    s = np.asarray(gridpoints, dtype=float)
    if (
        s.ndim != 1
        or s.size < 2
        or s.size > MAX_GRIDPOINTS
        or s[0] != 0.0
        or s[-1] != 1.0
        or np.any(np.diff(s) <= 0)
    ):
        raise RetimeInputError(
            f"gridpoints must be 2 to {MAX_GRIDPOINTS} values increasing strictly "
            f"from 0 to 1, got {s.size} values"
        )
    return s


def _margins(
    limits: JointLimits,
    dq: np.ndarray,
    ddq: np.ndarray,
    x: np.ndarray,
    u: np.ndarray,
    tau: PathCoefficients | None,
) -> dict[str, np.ndarray]:
    """Relative slack of the joint constraints at the grid points.

    See RetimeResult; the grasp's comes from the exactness check.
    """
    u = np.append(u, u[-1])[:, None]
    xc = x[:, None]
    out = {
        "velocity": 1.0 - np.max(np.abs(dq) * np.sqrt(xc) / limits.velocity, axis=1),
        "acceleration": 1.0
        - np.max(np.abs(dq * u + ddq * xc) / limits.acceleration, axis=1),
    }
    if tau is not None:
        torque = tau.a * u + tau.b * xc + tau.c
        out["torque"] = 1.0 - np.max(np.abs(torque) / limits.torque, axis=1)
    return out


__all__ = ["MAX_GRIDPOINTS", "ROW_TOLERANCE", "RetimeResult", "retime"]
