"""Dense verification of a timed joint trajectory against the retimer's limits.

:func:`check_trajectory` samples q, q', q'' at 1 kHz (and at the end) and,
independently of the retimer's path coefficients, evaluates at each sample:

- velocity and acceleration ratios ``|v_j| / v_max_j``, ``|vdot_j| / a_max_j``;
- joint torques by Drake inverse dynamics with the held object
  (:func:`rt_drake.dynamics.joint_torques`), ratio ``|tau_j| / tau_max_j``;
- the object wrench from the cup frame's spatial acceleration (Jacobian and
  bias at the sampled state) and Newton-Euler
  (:func:`rt_drake.dynamics.object_wrench`), and its g-scaled excess
  ``max_k (F_k w - g_k) / g_k`` (the Minkowski gauge of W about 0, minus 1).

Each is reported as the worst relative excess (``ratio - 1``; negative means
inside the limit by that fraction) with its time.

Tolerance: TOPP-RA enforces the constraints at the grid points only (both
ends of each segment, interpolation discretization); in between, where the
constant-s'' profile switches from accelerating to braking, joint
accelerations, torques and the wrench overshoot by an amount that shrinks
with the grid step. Measured on 48 random MOVE-like paths with 100 grid
points (4 objects): median excess 0.2 % (acceleration) and 0.01 % (grasp),
maximum 2.7 % of the acceleration limit and 2.1 % of g; with 400 grid points
the maximum fell to 0.6 %. :data:`DEFAULT_TOLERANCE` is 5 % (for 100 grid
points); use more grid points where less is needed.
"""

from __future__ import annotations

import dataclasses

import numpy as np
from pydrake.multibody.plant import MultibodyPlant
from pydrake.systems.framework import Context
from pydrake.trajectories import Trajectory

from rt_drake.dynamics import joint_torques, object_wrench
from rt_drake.retiming.limits import GraspConstraint, JointLimits

#: Allowed relative excess over a limit (and over g for the grasp), see above.
DEFAULT_TOLERANCE = 0.05


@dataclasses.dataclass(frozen=True)
class Excess:
    """Worst relative excess of one constraint over the samples.

    Attributes:
        value: ``max(ratio) - 1`` (<= 0: within the limit).
        time: When it occurs, s.
        index: The joint (0-based) or grasp row it occurs at.
    """

    value: float
    time: float
    index: int


@dataclasses.dataclass(frozen=True, eq=False)
class TrajectoryCheck:
    """Result of :func:`check_trajectory`.

    ``excess`` maps each constraint name ("velocity", "acceleration", and
    "torque", "grasp" when checked) to its :class:`Excess`.
    """

    times: np.ndarray
    excess: dict[str, Excess]

    def worst(self) -> float:
        """Largest relative excess over all constraints."""
        return max(e.value for e in self.excess.values())

    def passed(self, tolerance: float = DEFAULT_TOLERANCE) -> bool:
        """Whether every excess is at most ``tolerance``."""
        return self.worst() <= tolerance

    def summary(self) -> str:
        """One line per constraint: name, worst excess in %, time, index."""
        return "\n".join(
            f"{name}: {100 * e.value:+.3f} % at t = {e.time:.4f} s (#{e.index})"
            for name, e in self.excess.items()
        )


def check_trajectory(
    plant: MultibodyPlant,
    trajectory: Trajectory,
    limits: JointLimits,
    grasp: GraspConstraint | None = None,
    rate_hz: float = 1000.0,
    context: Context | None = None,
) -> TrajectoryCheck:
    """Sample ``trajectory`` at ``rate_hz`` and measure every limit's excess.

    Args:
        plant: The retimer's plant (arm and tool; objects welded or absent).
        trajectory: q(t) with derivatives (any Drake ``Trajectory``).
        limits: Joint limits; torques checked if ``limits.torque``.
        grasp: Held object and grasp polytope; None: not checked.
        rate_hz: Sampling rate, Hz.
        context: Scratch context of ``plant``.
    """
    t0, t1 = trajectory.start_time(), trajectory.end_time()
    times = np.append(np.arange(t0, t1, 1.0 / rate_hz), t1)
    q, v, vdot = _sample(trajectory, times)
    context = context or plant.CreateDefaultContext()
    excess = {
        "velocity": _worst(np.abs(v) / limits.velocity, times),
        "acceleration": _worst(np.abs(vdot) / limits.acceleration, times),
    }
    held = grasp.held if grasp is not None else None
    if limits.torque is not None:
        tau = joint_torques(plant, q, v, vdot, held, context)
        excess["torque"] = _worst(np.abs(tau) / limits.torque, times)
    if grasp is not None:
        w = object_wrench(plant, grasp.held, q, v, vdot, context)
        excess["grasp"] = _worst((w @ grasp.F.T) / grasp.g, times)
    return TrajectoryCheck(times=times, excess=excess)


def _sample(trajectory: Trajectory, times: np.ndarray) -> list[np.ndarray]:
    """q, q', q'' at ``times``, each (M, n)."""
    if hasattr(trajectory, "sample"):
        return trajectory.sample(times, order=2)
    series = [trajectory, trajectory.MakeDerivative(1), trajectory.MakeDerivative(2)]
    return [np.array([d.value(t).reshape(-1) for t in times]) for d in series]


def _worst(ratio: np.ndarray, times: np.ndarray) -> Excess:
    sample, index = np.unravel_index(int(np.argmax(ratio)), ratio.shape)
    return Excess(float(ratio[sample, index] - 1.0), float(times[sample]), int(index))


__all__ = ["DEFAULT_TOLERANCE", "Excess", "TrajectoryCheck", "check_trajectory"]
