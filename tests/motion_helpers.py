"""A simple MotionSource for tests: IK waypoints joined by minimum-jerk moves.

Not a planner: it ignores obstacles, so tests use it only where straight
joint-space moves between IK solutions are known to be clear.
"""

from __future__ import annotations

import numpy as np
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.multibody.inverse_kinematics import InverseKinematics
from pydrake.solvers import Solve
from pydrake.trajectories import PiecewisePolynomial

from rt_drake.model.plant import (
    CUP_FRAME,
    make_arm_plant,
)
from rt_drake.simulation import Motion, PhasePart, PlanTimes
from rt_drake.types.phase import Phase


def min_jerk(
    waypoints: list[np.ndarray], durations: list[float]
) -> PiecewisePolynomial:
    """Minimum-jerk segments through ``waypoints`` (rest at each one)."""
    tau = np.linspace(0.0, 1.0, 21)
    s = 10 * tau**3 - 15 * tau**4 + 6 * tau**5
    times, values = [0.0], [waypoints[0]]
    t0 = 0.0
    for q_a, q_b, duration in zip(
        waypoints[:-1], waypoints[1:], durations, strict=True
    ):
        for tk, sk in zip(tau[1:], s[1:], strict=True):
            times.append(t0 + duration * tk)
            values.append(q_a + sk * (q_b - q_a))
        t0 += duration
    return PiecewisePolynomial.CubicWithContinuousSecondDerivatives(
        times,
        np.column_stack(values),
        np.zeros(len(waypoints[0])),
        np.zeros(len(waypoints[0])),
    )


class IkMotions:
    """APPROACH, REACH, MOVE as IK waypoints joined by minimum-jerk moves."""

    def __init__(self, scenario, approach_s=1.0, reach_s=0.6, move_s=(0.6, 1.0, 0.6)):
        self._plant = make_arm_plant(scenario)
        self._cup = self._plant.GetFrameByName(CUP_FRAME)
        self._q_home = np.array(scenario.robot.home)
        self._approach_s, self._reach_s, self._move_s = approach_s, reach_s, move_s

    def ik(self, X_WC: RigidTransform, seed: np.ndarray) -> np.ndarray:
        """Cup at X_WC, closest to ``seed``; retried from a few fixed starts."""
        home = self._q_home
        for start in (
            seed,
            home,
            home + [0.5, 0, 0, 0, 0, 0],
            home + [0, -0.3, -0.5, 0, 0, 0],
        ):
            q = self._ik_from(X_WC, start, seed)
            if q is not None:
                return q
        raise AssertionError(f"no IK solution for {X_WC}")

    def ik_first(self, targets: list[RigidTransform], seed: np.ndarray) -> np.ndarray:
        """IK of the first reachable target (a straight joint move from high up
        clears the table obstacle; a lower one may drag the object into it)."""
        for X_WC in targets[:-1]:
            try:
                return self.ik(X_WC, seed)
            except AssertionError:
                continue
        return self.ik(targets[-1], seed)

    def _ik_from(self, X_WC, start, seed):
        ik = InverseKinematics(self._plant)
        p = X_WC.translation()
        ik.AddPositionConstraint(self._cup, [0, 0, 0], self._plant.world_frame(), p, p)
        ik.AddOrientationConstraint(
            self._cup,
            RotationMatrix(),
            self._plant.world_frame(),
            X_WC.rotation(),
            1e-4,
        )
        ik.prog().SetInitialGuess(ik.q(), start)
        ik.prog().AddQuadraticErrorCost(np.eye(len(seed)), seed, ik.q())
        result = Solve(ik.prog())
        return result.GetSolution(ik.q()) if result.is_success() else None

    @staticmethod
    def grasp(obj, which="start") -> RigidTransform:
        return (
            getattr(obj, which).GetDeterministicValue()
            @ obj.grasp.GetDeterministicValue()
        )

    @staticmethod
    def raised(X: RigidTransform, dz: float) -> RigidTransform:
        return RigidTransform(X.rotation(), X.translation() + [0, 0, dz])

    def pick(self, q_start, obj, retreat=False):
        """Approach (at rest above the object), then reach: one motion."""
        q_up = self.ik(self.raised(self.grasp(obj), obj.approach_offset), q_start)
        q = self.ik(self.grasp(obj), q_up)
        durations = [self._approach_s, self._reach_s]
        parts = (
            PhasePart(Phase.APPROACH, self._approach_s, PlanTimes()),
            PhasePart(Phase.REACH, sum(durations), PlanTimes()),
        )
        return Motion(min_jerk([q_start, q_up, q], durations), parts=parts)

    def move(self, q_start, obj, pick=None):
        q_up = self.ik(self.raised(self.grasp(obj), obj.approach_offset), q_start)
        X_goal = self.grasp(obj, "goal")
        q_above = self.ik_first(
            [self.raised(X_goal, obj.approach_offset), self.raised(X_goal, 0.06)], q_up
        )
        q_goal = self.ik(X_goal, q_above)
        return Motion(min_jerk([q_start, q_up, q_above, q_goal], list(self._move_s)))
