"""The steps every phase of the cycle planner takes, and its scene set-up.

:class:`PlannerSteps` is the base of :class:`~._cycle_planner.CyclePlanner`:
each planning call begins an :class:`~._connect.Attempt` (its seeded RNG and
stopwatch), checks its inputs (a configuration of the arm's size, finite;
a pose a finite RigidTransform: :class:`~._planning_errors.PlanningInputError`
naming phase and object), puts the scene's objects where the phase needs
them (:meth:`PlannerSteps.prepare`), checks its start and solves its goal
poses by IK (the collision-free solution nearest a configuration).
"""

from __future__ import annotations

import zlib

import numpy as np
from pydrake.math import RigidTransform, RotationMatrix

from rt_drake.errors import InputError
from rt_drake.model.scenario import Scenario
from rt_drake.planning._connect import Attempt, describe
from rt_drake.planning._geometry import face_under_cup
from rt_drake.planning._ik import CupIk, initial_guesses, nearest_valid_solution
from rt_drake.planning._planning_errors import (
    GoalInCollisionError,
    PlanningError,
    PlanningInputError,
    StartInCollisionError,
    UnreachablePoseError,
)
from rt_drake.planning.scene import PlanningScene
from rt_drake.types.phase import Phase

#: m, how far a grasped face is moved in so the cup may touch it.
TOUCH_ALLOWANCE = 0.002


class PlannerSteps:
    """Attempts, input checks, the scene's objects and IK of a cycle planner.

    Attributes (set by the planner): ``scenario``, ``seed``, ``budget_s``
    (s, of one call), ``scene``, ``ik``, ``q_home`` (rad) and
    ``object_poses`` (X_WO by name; None: not in the cell).
    """

    scenario: Scenario
    seed: int
    budget_s: float
    scene: PlanningScene
    ik: CupIk
    q_home: np.ndarray
    object_poses: dict[str, RigidTransform | None]

    def grasps(self, name: str) -> list[RigidTransform]:
        """The scenario's X_OC and its 180 deg yaw flip about z_C."""
        X_OC = self.scenario.object(name).grasp.GetDeterministicValue()
        return [X_OC, X_OC @ RigidTransform(RotationMatrix.MakeZRotation(np.pi))]

    # -- scene --------------------------------------------------------------

    def prepare(
        self,
        phase: Phase,
        name: str,
        q_start: np.ndarray,
        X_OC: RigidTransform | None = None,
    ) -> PlanningScene:
        """Set the scene's objects for ``phase`` of object ``name``.

        APPROACH: every object at its pose; REACH: the same, the grasped face
        of ``name`` moved in by ``TOUCH_ALLOWANCE``; MOVE: ``name`` carried
        at X_CO = X_OC^-1. In every phase an object the cup rests on at
        ``q_start`` gets the allowance on the face under the cup.
        """
        scene = self.scene
        if phase is Phase.MOVE:
            if X_OC is None:
                raise PlanningError(phase, name, "a MOVE needs the grasp X_OC")
            scene.attach(name, X_OC.inverse())
        else:
            scene.detach()
        X_WC = scene.cup_pose(q_start)
        for other in self.scenario.objects:
            X_WO = self.object_poses.get(other.name)
            if phase is Phase.MOVE and other.name == name:
                X_WO = None
            normal = None
            if X_WO is not None:
                normal = face_under_cup(other.model, X_WO, X_WC, TOUCH_ALLOWANCE)
                if phase is Phase.REACH and other.name == name and X_OC is not None:
                    normal = -X_OC.rotation().col(2)
            scene.set_object(other.name, X_WO, other.model, normal, TOUCH_ALLOWANCE)
        return scene

    # -- steps --------------------------------------------------------------

    def _begin(self, phase: Phase, name: str, check: bool = True) -> Attempt:
        if check:
            self.scenario.object(name)
        # The key names the phase in capitals: the seeds of every earlier run.
        key = zlib.crc32(f"{self.seed}:{phase.label}:{name}".encode())
        rng = np.random.default_rng(key)
        return Attempt(phase, name, self.budget_s, self.seed, rng)

    def _pose(self, attempt: Attempt) -> RigidTransform:
        X_WO = self.object_poses.get(attempt.name)
        if X_WO is None:
            raise PlanningError(
                attempt.phase, attempt.name, "the object is not in the cell"
            )
        return X_WO

    def _nearest_grasp(self, attempt: Attempt, X_WC: RigidTransform) -> RigidTransform:
        """The grasp (or its flip) whose cup orientation is nearest X_WC's."""
        R_WO = self._pose(attempt).rotation()
        return min(
            self.grasps(attempt.name),
            key=lambda X_OC: (
                X_WC.rotation()
                .InvertAndCompose(R_WO @ X_OC.rotation())
                .ToAngleAxis()
                .angle()
            ),
        )

    def _configuration(self, attempt: Attempt, q: object, name: str) -> np.ndarray:
        """``q`` (argument ``name``) as (n,) joint positions; PlanningInputError if not.

        Wrong size, NaN or inf are refused before any query sees them.
        """
        n = self.scene.plant.num_positions()
        try:
            array = np.asarray(q, dtype=float)
        except (TypeError, ValueError):
            array = None
        if array is None or array.shape != (n,) or not np.all(np.isfinite(array)):
            shown = (
                f"{array.size} values {np.array2string(array, precision=4)}"
                if array is not None
                else repr(q)
            )
            raise PlanningInputError(
                attempt.phase,
                attempt.name,
                f"configuration {name} must be {n} finite joint positions (rad), "
                f"got {shown}",
            )
        return array

    def _valid(self, q: np.ndarray) -> bool:
        return self.scene.within_limits(q) and self.scene.is_free(q)

    def _check_start(self, attempt: Attempt, q: np.ndarray) -> None:
        if not self._valid(q):
            raise StartInCollisionError(
                attempt.phase, attempt.name, describe(self.scene, q, "start")
            )

    def _solve(self, attempt, what, targets, q_near) -> tuple[int, np.ndarray]:
        guesses = initial_guesses(
            q_near, self.q_home, self.scene.lower, self.scene.upper, attempt.rng
        )
        outcome = nearest_valid_solution(self.ik, targets, q_near, guesses, self._valid)
        if outcome.q is not None:
            return outcome.target, outcome.q
        if outcome.in_collision is not None:  # reached, but only in collision
            detail = describe(self.scene, outcome.in_collision, "goal")
            raise GoalInCollisionError(attempt.phase, attempt.name, detail)
        p = np.round(targets[0].translation(), 3).tolist()
        raise UnreachablePoseError(
            attempt.phase,
            attempt.name,
            f"{what} pose unreachable (cup at {p} m; "
            f"IK failed from {outcome.attempts} initial guesses)",
        )

    def _optional(self, X_WC: RigidTransform, q_near: np.ndarray) -> np.ndarray | None:
        q = self.ik.solve(X_WC, q_near, q_near)
        return q if q is not None and self._valid(q) else None


def pose_key(X_WO: RigidTransform | None) -> bytes | None:
    """A hashable key of a pose (its 3x4 matrix, bit for bit)."""
    return None if X_WO is None else X_WO.GetAsMatrix34().tobytes()


def check_pose(X: RigidTransform, what: str, attempt: Attempt | None = None) -> None:
    """Refuse a pose that is not a finite RigidTransform."""
    finite = isinstance(X, RigidTransform) and np.all(np.isfinite(X.GetAsMatrix4()))
    if finite:
        return
    detail = f"{what} must be a finite RigidTransform, got {X}"
    if attempt is None:
        raise InputError(detail)
    raise PlanningInputError(attempt.phase, attempt.name, detail)


__all__ = ["PlannerSteps", "TOUCH_ALLOWANCE", "check_pose", "pose_key"]
