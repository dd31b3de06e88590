"""A straight joint-space line from rest to rest, time-optimal under jerk limits.

Between ``q_a`` and ``q_b`` (rad) with every joint limited by
``|q'_j| <= v_j``, ``|q''_j| <= a_j`` and ``|q'''_j| <= j_j`` (rad/s,
rad/s^2, rad/s^3; the jerk unbounded when the limits give none), Ruckig
(Berscheid and Kroeger, RSS 2021) computes each joint's time-optimal
seven-phase profile and synchronises them in phase
(``Synchronization.Phase``): every joint follows the same normalised
profile ``h(t)`` scaled by its distance, ``q(t) = q_a + h(t) (q_b - q_a)``,
so the motion stays on the straight line the planner checked, ends in the
slowest joint's least time, and starts and ends at rest (zero velocity and
acceleration). Rest to rest, phase synchronisation always exists. It costs
well under a millisecond: the cycle's first APPROACH needs no retimer.
"""

from __future__ import annotations

import numpy as np
from pydrake.trajectories import Trajectory
from ruckig import InputParameter, Result, Ruckig, RuckigError, Synchronization
from ruckig import Trajectory as RuckigTrajectory

from rt_drake.retiming import JointLimits


class LineMotion(Trajectory):
    """q(t) of a Ruckig trajectory, t in [0, duration], as a Drake Trajectory.

    Derivatives up to the second (q', q''); the jerk is piecewise constant
    (Ruckig's profile) and is not evaluated here.
    """

    def __init__(self, motion: RuckigTrajectory, dofs: int) -> None:
        Trajectory.__init__(self)
        self._motion = motion
        self._dofs = dofs

    def _at(self, t: float) -> tuple:
        return self._motion.at_time(min(max(t, 0.0), self._motion.duration))

    def sample(self, times: np.ndarray, order: int = 2) -> list[np.ndarray]:
        """``[q, q', ..., q^(order)]`` at ``times`` (s), each (M, n); order <= 2."""
        if not 0 <= order <= 2:
            raise NotImplementedError(f"LineMotion: order {order} (0 to 2 only)")
        states = [self._at(t) for t in np.asarray(times, dtype=float)]
        return [
            np.array([state[d] for state in states]).reshape(len(states), self._dofs)
            for d in range(order + 1)
        ]

    def do_value(self, t: float) -> np.ndarray:  # noqa: D102
        return np.array(self._at(t)[0]).reshape(self._dofs, 1)

    def do_has_derivative(self) -> bool:  # noqa: D102
        return True

    def DoEvalDerivative(self, t: float, derivative_order: int) -> np.ndarray:  # noqa: D102, N802
        if not 0 <= derivative_order <= 2:
            raise NotImplementedError(
                f"LineMotion: derivative order {derivative_order} (0 to 2 only)"
            )
        return np.array(self._at(t)[derivative_order]).reshape(self._dofs, 1)

    def do_rows(self) -> int:  # noqa: D102
        return self._dofs

    def do_cols(self) -> int:  # noqa: D102
        return 1

    def do_start_time(self) -> float:  # noqa: D102
        return 0.0

    def do_end_time(self) -> float:  # noqa: D102
        return float(self._motion.duration)

    def Clone(self) -> LineMotion:  # noqa: D102, N802
        return LineMotion(self._motion, self._dofs)  # Ruckig's is never changed

    def __deepcopy__(self, memo: dict) -> LineMotion:
        return self.Clone()


def line_motion(
    q_a: np.ndarray, q_b: np.ndarray, limits: JointLimits
) -> LineMotion | None:
    """The time-optimal motion from rest at ``q_a`` to rest at ``q_b`` on the line.

    Under ``limits``' velocity, acceleration and (if given) jerk limits; its
    torque limits are not applied (the caller uses this only without them).
    None if Ruckig finds no trajectory.
    """
    q_a, q_b = np.asarray(q_a, dtype=float), np.asarray(q_b, dtype=float)
    dofs = len(q_a)
    setup = InputParameter(dofs)
    setup.current_position, setup.target_position = q_a, q_b
    setup.max_velocity = limits.velocity
    setup.max_acceleration = limits.acceleration
    setup.max_jerk = np.full(dofs, np.inf) if limits.jerk is None else limits.jerk
    setup.synchronization = Synchronization.Phase
    motion = RuckigTrajectory(dofs)
    try:
        result = Ruckig(dofs).calculate(setup, motion)
    except RuckigError:
        return None
    if result not in (Result.Working, Result.Finished):
        return None
    return LineMotion(motion, dofs)


__all__ = ["LineMotion", "line_motion"]
