"""The cycle's KinematicTrajectoryOptimizations: a pick's, and a MOVE's under jerk.

:class:`PickKto`, the pick's: minimum time between its lines.

The pick (no object held) of the cycle, as :mod:`rt_drake.planning._pick`
plans it: from rest at ``q0`` (the place configuration of the object just
released, or home) up the retreat line to its top, a free transit to the
approach pose, and down the descent line to rest at the grasp ``q1``. The
KTO (the module docstring of ``tools/kto_reference.py`` for the B-spline
and its solve) finds q(t) = r(t / T) with

- r(0) = q0, r(1) = q1, r'(0) = r'(1) = 0;
- r(tau_up) = the retreat's top, r(tau_down) = the approach pose (the
  blended pick's own configurations there; tau their normalised times on
  the initial guess); no retreat from home (tau_up = 0);
- on each line, at samples (one per cm of line, at least
  :data:`~kto_reference.VERTICAL_SAMPLES`), the cup's horizontal distance
  from the line within :data:`DRIFT` (m) and its orientation within
  :data:`TURN` (rad, each component of ``vee(R_line^T R_WC)``'s skew part),
  R_WC and p_WC from the arm's serial chain (the cup frame C in world W);
- joint position, velocity, acceleration and, if given, jerk bounds on the
  control points (``AddJerkBounds``: sufficient, so conservative); with
  jerk bounds also r''(0) = r''(1) = 0 (from and to rest, as the
  jerk-limited retime and the floor's double-S);
- with ``collision_samples``, a ``MinimumDistanceLowerBoundConstraint`` on
  the planner's checker (the REACH scene of the pick) at that many samples
  of the transit, between the lines' tops.

The cost is T alone (``AddDurationCost``). The initial guess is the blended
pick retimed under the acceleration limits (adaptive grid), fitted by
least squares.

The lines are held much tighter than the planner's 1 mm and 0.5 deg
(:data:`DRIFT`, :data:`TURN`, a sample per :data:`SAMPLE_SPACING`): with
the planner's tolerance at five samples a line, SNOPT wound J1 up on each
2 cm line within 0.7 mm of drift and crossed the line's top at 0.25 rad/s,
where any motion exactly on the line has J1 at rest, as the floor counts it.

:class:`JerkKto`, the MOVE's of ``tools/kto_reference.py`` with the
grasp-constrained motion's jerk bounds and r''(0) = r''(1) = 0 added.
"""

from __future__ import annotations

import numpy as np
from kto_reference import VERTICAL_SAMPLES, Kto
from pydrake.autodiffutils import ExtractGradient, ExtractValue, InitializeAutoDiff
from pydrake.planning import KinematicTrajectoryOptimization

from rt_drake.planning import PlannedPick
from rt_drake.retiming import RetimeResult
from rt_drake.shaping.cup_chain import CupChain

#: m: the cup's horizontal distance from a line allowed at its samples (the
#: planner accepts 1 mm between any two points: ``LINE_TOLERANCE_M``).
DRIFT = 5e-5
#: rad: each component of the cup's rotation from the line's orientation
#: (the planner accepts 0.5 deg of angle).
TURN = np.radians(0.02)
#: Relative step of the central differences in r.
STEP = 1e-6
#: m: line length per sample.
SAMPLE_SPACING = 0.004


def _vee_skew(R: np.ndarray) -> np.ndarray:
    """(S, 3) vee of the skew part of each (S, 3, 3) rotation: sin(angle) * axis."""
    return 0.5 * np.stack(
        [R[:, 2, 1] - R[:, 1, 2], R[:, 0, 2] - R[:, 2, 0], R[:, 1, 0] - R[:, 0, 1]],
        axis=1,
    )


def _from_and_to_rest(kto: KinematicTrajectoryOptimization, jerk: np.ndarray) -> None:
    """Jerk bounds (rad/s^3) and zero acceleration at both ends."""
    kto.AddJerkBounds(-jerk, jerk)
    zero = np.zeros(len(jerk))
    kto.AddPathAccelerationConstraint(zero, zero, 0.0)
    kto.AddPathAccelerationConstraint(zero, zero, 1.0)


class JerkKto(Kto):
    """The MOVE's KTO (``kto_reference.Kto``) with ``setup.limits.jerk`` too."""

    def program(self, setup, scene, guess, collision):  # noqa: ANN001, ANN201
        """:meth:`Kto.program` with jerk bounds and rest at both ends."""
        kto, prog = super().program(setup, scene, guess, collision)
        if setup.limits.jerk is not None:
            _from_and_to_rest(kto, setup.limits.jerk)
        return kto, prog


class PickKto(Kto):
    """One pick's KTO (module docstring); solved by :meth:`Kto.solve`.

    Args:
        chain: the arm's serial chain (cup poses in W).
        pick: the blended pick the planner gives (its lines and line tops).
        profile: that pick's path retimed (the initial guess and the lines' times
            initial guess and the lines' times tau).
        retreat: whether the pick starts with a retreat line.
        limits: the joint limits (velocity, acceleration, jerk or None).
        args: the KTO's options (``kto_reference.add_kto_arguments``).
    """

    def __init__(
        self,
        chain: CupChain,
        pick: PlannedPick,
        profile: RetimeResult,
        retreat: bool,
        limits,  # noqa: ANN001 - JointLimits
        args,  # noqa: ANN001 - argparse.Namespace
    ) -> None:
        self.chain, self.args, self.limits = chain, args, limits
        self.n = chain.num_joints
        path = pick.path.path
        self.q0, self.q1 = path.waypoints[0], path.waypoints[-1]
        self.retreat = retreat
        self.q_up = path.value(pick.s_retreat).ravel()
        self.q_down = path.value(pick.s_approach).ravel()
        self.T0 = profile.duration
        dt = 2 * np.diff(profile.gridpoints) / (profile.sd[:-1] + profile.sd[1:])
        t_grid = np.concatenate([[0.0], np.cumsum(dt)])
        self.tau_up = float(np.interp(pick.s_retreat, profile.gridpoints, t_grid))
        self.tau_up /= self.T0
        self.tau_down = float(np.interp(pick.s_approach, profile.gridpoints, t_grid))
        self.tau_down /= self.T0
        times = np.linspace(0.0, self.T0, 600)
        self.q_guess = np.array([profile.trajectory.value(t).ravel() for t in times])
        self.tau_guess = times / self.T0
        R, p = chain.cup_pose(np.array([self.q0, self.q1]))
        self.lines = {"up": (R[0], p[0]), "down": (R[1], p[1])}
        down = chain.gravity_W / np.linalg.norm(chain.gravity_W)
        self.horizontal = np.linalg.svd(np.eye(3) - np.outer(down, down))[0][:, :2]
        self.samples: list[tuple[float, str | None]] = []
        spans = [(self.tau_down, 1.0, "down")]
        if retreat:
            spans.insert(0, (0.0, self.tau_up, "up"))
        for lo, hi, side in spans:
            q_top = self.q_up if side == "up" else self.q_down
            length = np.linalg.norm(
                chain.cup_pose(q_top[None])[1][0] - self.lines[side][1]
            )
            count = max(VERTICAL_SAMPLES, int(np.ceil(length / SAMPLE_SPACING)))
            inner = np.linspace(lo, hi, count + 2)[1:-1]
            self.samples += [(float(tau), side) for tau in inner]
        self.rows = [np.zeros(0, int) for _ in self.samples]
        self.collision_taus: list[float] = []

    def cell_rows(self, traj, share: float, rows) -> list[np.ndarray]:  # noqa: ANN001
        """No grasp rows: nothing held (so :meth:`Kto.solve` runs one round)."""
        return [np.zeros(0, int) for _ in self.samples]

    def add_sample(self, prog, cp, T, tau: float, side, rows) -> None:  # noqa: ANN001
        """The line's drift and turn at tau (module docstring)."""
        active, (B0, _, _) = self.sample_terms(tau)
        variables = cp[:, active].T.ravel()
        k, n = len(active), self.n
        R_line, p_line = self.lines[side]

        def values(q: np.ndarray) -> np.ndarray:
            R, p = self.chain.cup_pose(q)
            turn = _vee_skew(np.einsum("ji,sjk->sik", R_line, R))
            return np.column_stack([(p - p_line) @ self.horizontal, turn])

        def evaluate(x):  # noqa: ANN001, ANN202
            autodiff = x.dtype == object
            xv = ExtractValue(x).ravel() if autodiff else np.asarray(x, float)
            q0 = B0 @ xv.reshape(k, n)
            if not autodiff:
                return values(q0[None])[0]
            h = STEP * np.maximum(1.0, np.abs(q0))
            out = values(np.vstack([q0, q0 + np.diag(h), q0 - np.diag(h)]))
            dq = (out[1 : 1 + n] - out[1 + n :]) / (2 * h[:, None])  # (n, 5)
            J = np.einsum("no,a->oan", dq, B0).reshape(5, k * n)
            return InitializeAutoDiff(out[0], J @ ExtractGradient(x))

        bound = np.array([DRIFT, DRIFT, TURN, TURN, TURN])
        prog.AddConstraint(evaluate, -bound, bound, variables, f"line {tau:.3f}")

    def program(self, setup, scene, guess, collision):  # noqa: ANN001, ANN201
        """(KTO, its program), initial guess ``guess`` (module docstring)."""
        kto, prog = self.rest_to_rest(scene, self.limits)
        if self.limits.jerk is not None:
            _from_and_to_rest(kto, self.limits.jerk)
        if self.retreat:
            kto.AddPathPositionConstraint(self.q_up, self.q_up, self.tau_up)
        kto.AddPathPositionConstraint(self.q_down, self.q_down, self.tau_down)
        cp, T = kto.control_points(), kto.duration()
        for (tau, side), rows in zip(self.samples, self.rows, strict=True):
            self.add_sample(prog, cp, T, tau, side, rows)
        if collision is not None:  # the transit, between the lines' tops
            taus = np.linspace(self.tau_up, self.tau_down, self.args.collision_samples)
            for tau in np.union1d(taus[1:-1], self.collision_taus):
                kto.AddPathPositionConstraint(collision, float(tau))
        kto.SetInitialGuess(guess)
        return kto, prog
