"""Dense verification of a timed joint trajectory against the retimer's limits.

:func:`check_trajectory` samples q, q', q'' at 1 kHz (and at the end) and,
independently of the retimer's path coefficients, evaluates at each sample:

- velocity and acceleration ratios ``|v_j| / v_max_j``, ``|vdot_j| / a_max_j``;
- the plant's joint position limits, as the ratio ``|q_j - m_j| / h_j`` of
  the distance from the middle ``m_j`` of joint j's range to half its width
  ``h_j`` (1 on a limit; joints without finite limits are not checked);
- with jerk limits, the jerk over each sampling step, ``|vdot_j(t_k+1) -
  vdot_j(t_k)| / dt``, against ``jerk_j``: by the mean value theorem it is at
  most the largest jerk in the step, and a jump of the acceleration (TOPP-RA's
  bang-bang profile) shows as ``jump / dt``;
- the object wrench by another route than the retimer's: the cup body's
  spatial acceleration from Drake's ``CalcSpatialAccelerationsFromVdot`` and
  Newton-Euler (:func:`rt_drake.dynamics.newton_euler.reference_object_wrench`; no
  Jacobian, bias or gravity shortcut of :mod:`rt_drake.dynamics.wrench`), and its
  ratio ``max_k F_k w / g_k`` (the Minkowski gauge of W about 0);
- joint torques by Drake inverse dynamics plus ``J_Coᵀ w`` for that wrench,
  ratio ``|tau_j| / tau_max_j``.

Each is reported as its smallest margin ``1 - ratio`` with its time, in the
retimer's sign convention (:attr:`RetimeResult.margins
<rt_drake.retiming._solve.RetimeResult>`): positive is room left, negative is
over the limit by that fraction. :meth:`TrajectoryCheck.summary` says which
in words.

Tolerance: the retimer holds every limit between its grid points too
(:mod:`._between`), to within 5e-4 at its sub-points; sampled at 1 kHz the
margin stays above ``-DEFAULT_TOLERANCE`` = -1e-3 (the contract; tests
check it on random paths).

The report's types are :mod:`._check_report`; ``DEFAULT_TOLERANCE`` and
``Margin`` stay importable from here.
"""

from __future__ import annotations

import dataclasses

import numpy as np
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import JacobianWrtVariable, MultibodyForces
from pydrake.systems.framework import Context
from pydrake.trajectories import Trajectory

from rt_drake import arguments
from rt_drake.dynamics.cup_frame import CupFrame
from rt_drake.dynamics.newton_euler import reference_object_wrench
from rt_drake.retiming._check_report import (
    DEFAULT_TOLERANCE,
    Margin,
    TrajectoryCheck,
    WorstMargin,
)
from rt_drake.retiming.limits import GRASP_ATTRIBUTES, GraspConstraint, JointLimits


def check_trajectory(
    plant: MultibodyPlant,
    trajectory: Trajectory,
    limits: JointLimits,
    grasp: GraspConstraint | None = None,
    rate_hz: float = 1000.0,
    context: Context | None = None,
    cup: CupFrame | None = None,
) -> TrajectoryCheck:
    """Sample ``trajectory`` at ``rate_hz`` and measure every limit's excess.

    Args:
        plant: The retimer's plant (arm and tool; objects welded or absent).
        trajectory: q(t) with derivatives (any Drake ``Trajectory``).
        limits: Joint limits; torques checked if ``limits.torque``, jerk if
            ``limits.jerk``. The positions are checked against the plant's
            position limits.
        grasp: Held object and grasp polytope; None: not checked.
        rate_hz: Sampling rate, Hz.
        context: Scratch context of ``plant``.
        cup: The cup frame C (default: the plant's ``suction_cup``).
    """
    where = "check_trajectory"
    arguments.instance(plant, "plant", MultibodyPlant, where=where)
    arguments.instance(trajectory, "trajectory", Trajectory, where=where)
    arguments.instance(limits, "limits", JointLimits, where=where)
    if grasp is not None:
        arguments.having(
            grasp, "grasp", "GraspConstraint", GRASP_ATTRIBUTES, where=where
        )
    arguments.number(rate_hz, "rate_hz", where=where, above=0.0)
    if context is not None:
        arguments.instance(context, "context", Context, where=where)
    if cup is not None:
        arguments.instance(cup, "cup", CupFrame, where=where)
    t0, t1 = trajectory.start_time(), trajectory.end_time()
    times = np.append(np.arange(t0, t1, 1.0 / rate_hz), t1)
    q, v, vdot = _sample(trajectory, times)
    context = context or plant.CreateDefaultContext()
    names = _joint_names(plant)
    margins = {
        Margin.VELOCITY: _worst(np.abs(v) / limits.velocity, times),
        Margin.ACCELERATION: _worst(np.abs(vdot) / limits.acceleration, times),
        Margin.POSITION: _position_margin(plant, q, times, names),
    }
    if limits.jerk is not None and len(times) > 1:
        dt = np.diff(times)[:, None]
        jerk = np.diff(vdot, axis=0) / dt
        worst = _worst(np.abs(jerk) / limits.jerk, times[:-1])
        sample, j = int(np.searchsorted(times, worst.time)), worst.index
        detail = (
            f"joint {j + 1} ({names[j]}): {jerk[sample, j]:.4g} rad/s^3 from "
            f"t = {times[sample]:.4f} to {times[sample + 1]:.4f} s, limit "
            f"{limits.jerk[j]:.4g} rad/s^3"
        )
        margins[Margin.JERK] = dataclasses.replace(worst, detail=detail)
    cup = cup or CupFrame.of(plant)
    w = None
    if grasp is not None:
        w = reference_object_wrench(plant, grasp.held, cup, q, v, vdot, context)
        margins[Margin.GRASP] = _worst((w @ grasp.F.T) / grasp.g, times)
    if limits.torque is not None:
        tau = _torques(plant, cup, q, v, vdot, w, context)
        margins[Margin.TORQUE] = _worst(np.abs(tau) / limits.torque, times)
    return TrajectoryCheck(times=times, margins=margins)


def _torques(
    plant: MultibodyPlant,
    cup: CupFrame,
    q: np.ndarray,
    v: np.ndarray,
    vdot: np.ndarray,
    w: np.ndarray | None,
    context: Context,
) -> np.ndarray:
    """Inverse dynamics (gravity as applied force) plus ``J_Coᵀ w`` per sample."""
    forces = MultibodyForces(plant)
    frame, world = cup.frame, plant.world_frame()
    tau = np.empty_like(q)
    for i in range(len(q)):
        plant.SetPositionsAndVelocities(context, np.concatenate([q[i], v[i]]))
        plant.CalcForceElementsContribution(context, forces)
        tau[i] = plant.CalcInverseDynamics(context, vdot[i], forces)
        if w is not None:
            J_Co = plant.CalcJacobianSpatialVelocity(
                context, JacobianWrtVariable.kV, frame, np.zeros(3), world, frame
            )
            tau[i] += J_Co.T @ w[i]
    return tau


def _position_margin(
    plant: MultibodyPlant, q: np.ndarray, times: np.ndarray, names: list[str]
) -> WorstMargin:
    """Margin ``1 - |q_j - m_j| / h_j`` of the plant's position limits.

    ``m_j``, ``h_j``: the middle and half width of joint j's range; joints
    without two finite limits have ratio 0. The detail names the joint, its
    value and the limit it is nearest to.
    """
    lower = plant.GetPositionLowerLimits()
    upper = plant.GetPositionUpperLimits()
    finite = np.isfinite(lower) & np.isfinite(upper) & (upper > lower)
    lower_f, upper_f = np.where(finite, lower, -1.0), np.where(finite, upper, 1.0)
    middle = 0.5 * (lower_f + upper_f)  # 0 for an unlimited joint
    half = 0.5 * (upper_f - lower_f)
    ratio = np.where(finite, np.abs(q - middle) / half, 0.0)
    worst = _worst(ratio, times)
    sample = int(np.searchsorted(times, worst.time))
    j = worst.index
    value = float(q[sample, j])
    limit = lower[j] if value < middle[j] else upper[j]
    detail = f"joint {j + 1} ({names[j]}): {value:.4f} rad, limit {limit:.4f} rad"
    return dataclasses.replace(worst, detail=detail)


def _joint_names(plant: MultibodyPlant) -> list[str]:
    """The name of the joint of each position (``position k`` if none)."""
    names = [f"position {k}" for k in range(plant.num_positions())]
    for index in plant.GetJointIndices():
        joint = plant.get_joint(index)
        for k in range(joint.num_positions()):
            names[joint.position_start() + k] = joint.name()
    return names


def _sample(trajectory: Trajectory, times: np.ndarray) -> list[np.ndarray]:
    """q, q', q'' at ``times``, each (M, n)."""
    if hasattr(trajectory, "sample"):
        return trajectory.sample(times, order=2)
    series = [trajectory, trajectory.MakeDerivative(1), trajectory.MakeDerivative(2)]
    return [np.array([d.value(t).reshape(-1) for t in times]) for d in series]


def _worst(ratio: np.ndarray, times: np.ndarray) -> WorstMargin:
    """The smallest margin ``1 - ratio`` over (M, k) ratios, with where."""
    sample, index = np.unravel_index(int(np.argmax(ratio)), ratio.shape)
    return WorstMargin(
        float(1.0 - ratio[sample, index]), float(times[sample]), int(index)
    )


__all__ = [
    "DEFAULT_TOLERANCE",
    "Margin",
    "check_trajectory",
]
