"""What :func:`~._solve.retime` returns: :class:`RetimeResult`, and its assembly.

From the TOPP-RA profile (``x = s'^2`` at the grid points s_i, constant
``u = s''`` per segment, ``u_i = (x_{i+1} - x_i) / (2 ds_i)``) or from the
jerk-limited profile of :mod:`._jerk`; with the relative slack of each
constraint at the grid points, ``1 - |value| / limit`` (:func:`joint_margins`).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from rt_drake.dynamics.wrench import PathCoefficients
from rt_drake.retiming._check_report import Margin
from rt_drake.retiming._exact_solve import Profile
from rt_drake.retiming._grasp_rows import ObjectRows
from rt_drake.retiming._jerk import JerkProfile
from rt_drake.retiming._jerk_timed_path import JerkTimedPath
from rt_drake.retiming._joint_path import JointPath
from rt_drake.retiming._retime_errors import RetimeStatus
from rt_drake.retiming._robust_grasp import SetRows
from rt_drake.retiming._samples import PathSamples
from rt_drake.retiming._timed_path import TimedPath
from rt_drake.retiming.limits import JointLimits


@dataclasses.dataclass(frozen=True, eq=False)
class RetimeResult:
    """A retimed path.

    Attributes:
        trajectory: q(t) (Drake ``Trajectory``; q', q'' by ``EvalDerivative``);
            with jerk limits a :class:`~._jerk_timed_path.JerkTimedPath`.
        duration: s.
        gridpoints: (N+1,) grid s_i.
        sd: (N+1,) path velocity ``s'(s_i)``, 1/s (the s'(s) profile).
        sdd: (N,) constant path acceleration ``s''`` on each segment, 1/s^2;
            with jerk limits its mean over s, ``(x_{i+1} - x_i) / (2 ds_i)``.
        margin: (N+1,) smallest relative slack of all constraints at each grid
            point (1 - |value| / limit; for the grasp ``min (g - F w) / g``),
            taking the acceleration of the segment that starts there:
            positive is room left, negative over the limit (as
            :class:`~._check.TrajectoryCheck`).
        margins: The same per constraint in force (:attr:`Margin.VELOCITY`,
            :attr:`Margin.ACCELERATION`, and :attr:`Margin.TORQUE`,
            :attr:`Margin.GRASP` when limited).
        status: Always ``RetimeStatus.OK`` (failures raise ``RetimeError``).
        grasp_rows: Rows of the grasp polytope the stage LPs used (of
            ``len(grasp.g)``); for a set of objects, (row, vertex) pairs.
        repairs: Times the exactness check added rows and solved again (in
            the last solve).
        refinements: Times points were added to the grid where the torque or
            grasp was exceeded between grid points.
        grasp_objects: Objects whose rows the stage LPs used: 1 for one
            object, the vertex objects of a set (0 without a grasp).
        cuts: Rounds of cuts between grid points (joint limits; for a set of
            objects also its grasp and torques).
        path_acceleration: With jerk limits, (N+1,) ``s''(s_i)`` (continuous,
            linear in s between grid points; :mod:`._jerk_timed_path`);
            else None.
        jerk_lps: With jerk limits, the LPs solved after TOPP-RA (0 without).
    """

    trajectory: TimedPath | JerkTimedPath
    duration: float
    gridpoints: np.ndarray
    sd: np.ndarray
    sdd: np.ndarray
    margin: np.ndarray
    margins: dict[Margin, np.ndarray]
    status: RetimeStatus
    grasp_rows: int
    repairs: int
    refinements: int = 0
    grasp_objects: int = 1
    cuts: int = 0
    path_acceleration: np.ndarray | None = None
    jerk_lps: int = 0


def jerk_result(
    jerk: JerkProfile,
    family: ObjectRows | SetRows | None,
    refinements: int,
    cuts: int,
) -> RetimeResult:
    """The result of a jerk-limited retiming (``sdd``: the mean s'' per segment)."""
    margins = jerk.margins
    return RetimeResult(
        trajectory=jerk.trajectory,
        duration=jerk.trajectory.duration,
        gridpoints=jerk.s,
        sd=np.sqrt(jerk.x),
        sdd=np.diff(jerk.x) / (2.0 * np.diff(jerk.s)),
        margin=np.min(np.vstack(list(margins.values())), axis=0),
        margins=margins,
        status=RetimeStatus.OK,
        grasp_rows=jerk.grasp_rows,
        repairs=0 if family is None else family.repairs,
        refinements=refinements,
        grasp_objects=0 if family is None else family.object_count,
        cuts=cuts,
        path_acceleration=jerk.u,
        jerk_lps=jerk.lps,
    )


def profile_result(
    spline: JointPath,
    samples: PathSamples,
    profile: Profile,
    limits: JointLimits,
    family: ObjectRows | SetRows | None,
    start_time: float,
    refinements: int,
    cuts: int,
) -> RetimeResult:
    """The result of TOPP-RA's profile ``x`` on the grid ``samples.s``.

    ``u = (x_{i+1} - x_i) / (2 ds_i)``; the margins of the joint limits
    (:func:`joint_margins`; a set's torques from its rows), and of the grasp
    ``1 - max_k F_k w / g_k`` from the exactness check.
    """
    s = samples.s
    trajectory = TimedPath(spline, s, profile.x, start_time)
    u = (profile.x[1:] - profile.x[:-1]) / (2.0 * np.diff(s))
    robust = isinstance(family, SetRows)
    margins = joint_margins(
        limits,
        samples.dq,
        samples.ddq,
        profile.x,
        u,
        None if robust else samples.torque,
    )
    if robust:
        assert isinstance(family, SetRows)
        torque_margin = family.torque_margin(samples, profile.x, u)
        if torque_margin is not None:
            margins[Margin.TORQUE] = torque_margin
    if profile.ratio is not None:
        margins[Margin.GRASP] = 1.0 - profile.ratio
    return RetimeResult(
        trajectory=trajectory,
        duration=trajectory.duration,
        gridpoints=s,
        sd=np.sqrt(np.maximum(profile.x, 0.0)),
        sdd=u,
        margin=np.min(np.vstack(list(margins.values())), axis=0),
        margins=margins,
        status=RetimeStatus.OK,
        grasp_rows=0 if family is None else family.row_count,
        repairs=0 if family is None else family.repairs,
        refinements=refinements,
        grasp_objects=0 if family is None else family.object_count,
        cuts=cuts,
    )


def joint_margins(
    limits: JointLimits,
    dq: np.ndarray,
    ddq: np.ndarray,
    x: np.ndarray,
    u: np.ndarray,
    tau: PathCoefficients | None,
) -> dict[Margin, np.ndarray]:
    """Relative slack of the joint constraints at the grid points.

    See RetimeResult; the grasp's comes from the exactness check.
    """
    u = np.append(u, u[-1])[:, None]
    xc = x[:, None]
    out = {
        Margin.VELOCITY: 1.0
        - np.max(np.abs(dq) * np.sqrt(xc) / limits.velocity, axis=1),
        Margin.ACCELERATION: 1.0
        - np.max(np.abs(dq * u + ddq * xc) / limits.acceleration, axis=1),
    }
    if tau is not None:
        torque = tau.a * u + tau.b * xc + tau.c
        out[Margin.TORQUE] = 1.0 - np.max(np.abs(torque) / limits.torque, axis=1)
    return out
