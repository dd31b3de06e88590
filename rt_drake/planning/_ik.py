"""Inverse kinematics of the cup frame with Drake's ``InverseKinematics``.

For a target pose X_WC of the cup frame C the program is::

    min_q  ||q - q_near||^2
    s.t.   p_WP(q) = X_WC p_CP   for P in {C origin, 0.1 x_C, 0.1 z_C}
           q_lower <= q <= q_upper

Three points of C pinned (to ``tolerance`` m) fix its pose exactly without
the poorly conditioned ``theta_bound = 0`` of an orientation constraint. The
cost keeps the solution on the branch nearest ``q_near`` (the configuration
the robot comes from); SNOPT from a given initial guess is deterministic.

:func:`nearest_valid_solution` tries several target poses (e.g. the cup's
symmetric yaw flip) and several initial guesses (``q_near`` first, then a
seeded list) and keeps the collision-free solution nearest ``q_near``.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence

import numpy as np
from pydrake.math import RigidTransform
from pydrake.multibody.inverse_kinematics import InverseKinematics
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import Frame
from pydrake.solvers import SnoptSolver, SolverOptions

#: m, the three points' position tolerance.
TOLERANCE = 1e-6
#: SNOPT's optimality tolerance: the cost only picks the branch nearest
#: q_near; the default (1e-6) can take 60 ms where 1e-4 takes 1 ms.
OPTIMALITY_TOLERANCE = 1e-4
#: random IK initial guesses after q_near, its yaw flips and home.
NUM_GUESSES = 6
#: m, points of C that pin its pose: origin, along x_C, along z_C.
_POINTS_C = np.array([[0.0, 0.0, 0.0], [0.1, 0.0, 0.0], [0.0, 0.0, 0.1]])


class CupIk:
    """Solve for q with the cup frame at a given pose, nearest a given q."""

    def __init__(self, plant: MultibodyPlant, cup_frame: Frame) -> None:
        self._plant = plant
        self._cup = cup_frame
        self._solver = SnoptSolver()
        self._options = SolverOptions()
        self._options.SetOption(
            SnoptSolver.id(), "Major optimality tolerance", OPTIMALITY_TOLERANCE
        )
        self._context = plant.CreateDefaultContext()
        # One program, its bounds and cost updated per solve (building it
        # costs about as much as SNOPT's solve); the same program as a
        # fresh one, so the same solution.
        self._ik = InverseKinematics(plant, self._context, with_joint_limits=True)
        world = plant.world_frame()
        self._points = [
            self._ik.AddPositionConstraint(
                cup_frame, p_CP, world, np.zeros(3), np.zeros(3)
            )
            for p_CP in _POINTS_C
        ]
        n = plant.num_positions()
        self._cost = self._ik.prog().AddQuadraticErrorCost(
            np.eye(n), np.zeros(n), self._ik.q()
        )

    def solve(
        self, X_WC: RigidTransform, q_near: np.ndarray, q_guess: np.ndarray
    ) -> np.ndarray | None:
        """Return q (rad) with the cup at X_WC nearest ``q_near``, or None.

        Args:
            X_WC: target pose of the cup frame in W.
            q_near: the cost's reference configuration.
            q_guess: the solver's initial guess.
        """
        q = self._ik.q()
        world = self._plant.world_frame()
        for p_CP, binding in zip(_POINTS_C, self._points, strict=True):
            p_WP = X_WC.multiply(p_CP)
            binding.evaluator().set_bounds(p_WP - TOLERANCE, p_WP + TOLERANCE)
        # ||q - q_near||^2 as Drake's AddQuadraticErrorCost writes it:
        # 0.5 q' (2 I) q - 2 q_near' q + q_near' q_near.
        q_near = np.asarray(q_near, dtype=float)
        identity = np.eye(len(q_near))
        self._cost.evaluator().UpdateCoefficients(
            2.0 * identity, -2.0 * identity @ q_near, q_near.dot(identity @ q_near)
        )
        prog = self._ik.prog()
        prog.SetInitialGuess(q, q_guess)
        result = self._solver.Solve(prog, None, self._options)
        if not result.is_success():
            return None
        solution = result.GetSolution(q)
        self._plant.SetPositions(self._context, solution)
        X_error = self._plant.CalcRelativeTransform(
            self._context, world, self._cup
        ).InvertAndCompose(X_WC)
        if np.linalg.norm(X_error.translation()) > 10 * TOLERANCE or (
            X_error.rotation().ToAngleAxis().angle() > 1e-4
        ):
            return None
        return solution


def initial_guesses(
    q_near: np.ndarray,
    q_home: np.ndarray,
    lower: np.ndarray,
    upper: np.ndarray,
    rng: np.random.Generator,
    count: int = NUM_GUESSES,
) -> list[np.ndarray]:
    """IK initial guesses to try after q_near, in order.

    q_near with its last joint (the cup's yaw, for an in-line tool) turned by
    +-pi where the limits allow, then home, then ``count`` samples uniform in
    the joint limits (deterministic for the rng's state).
    """
    flips = []
    for turn in (np.pi, -np.pi):
        q = np.array(q_near, dtype=float)
        q[-1] += turn
        if lower[-1] <= q[-1] <= upper[-1]:
            flips.append(q)
    samples = rng.uniform(lower, upper, (count, len(lower)))
    return flips + [np.asarray(q_home, float)] + list(samples)


@dataclasses.dataclass(frozen=True)
class IkOutcome:
    """What :func:`nearest_valid_solution` found.

    Attributes:
        q: the collision-free solution nearest ``q_near`` (None if none).
        target: index of the target pose q reaches.
        reached: some target was reached (collision-free or not).
        in_collision: the nearest solution that collided, if no q.
        attempts: number of IK solves.
    """

    q: np.ndarray | None
    target: int
    reached: bool
    in_collision: np.ndarray | None
    attempts: int


def nearest_valid_solution(
    ik: CupIk,
    targets: Sequence[RigidTransform],
    q_near: np.ndarray,
    guesses: Sequence[np.ndarray],
    is_valid: Callable[[np.ndarray], bool],
) -> IkOutcome:
    """Collision-free IK solution nearest ``q_near`` over targets and guesses.

    First every target from the guess ``q_near``: the valid solution nearest
    ``q_near`` wins. If none is valid, the other ``guesses`` in order, every
    target each; the first valid solution wins. Deterministic.
    """
    attempts = 0
    colliding: list[tuple[float, np.ndarray]] = []
    for round_guesses in ([q_near], list(guesses)):
        for guess in round_guesses:
            valid: list[tuple[float, int, np.ndarray]] = []
            for index, X_WC in enumerate(targets):
                attempts += 1
                q = ik.solve(X_WC, q_near, guess)
                if q is None:
                    continue
                distance = float(np.linalg.norm(q - q_near))
                if is_valid(q):
                    valid.append((distance, index, q))
                else:
                    colliding.append((distance, q))
            if valid:
                _, index, q = min(valid, key=lambda item: item[0])
                return IkOutcome(q, index, True, None, attempts)
    nearest = min(colliding, key=lambda item: item[0])[1] if colliding else None
    return IkOutcome(None, -1, bool(colliding), nearest, attempts)


__all__ = [
    "CupIk",
    "IkOutcome",
    "NUM_GUESSES",
    "TOLERANCE",
    "initial_guesses",
    "nearest_valid_solution",
]
