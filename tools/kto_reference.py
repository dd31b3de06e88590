"""Offline reference for issue 13: Drake's KinematicTrajectoryOptimization (KTO).

How far is the shaped MOVE (:class:`rt_drake.shaping.MoveOptimizer`, its
defaults: 240 paths scored, step 0.2) from a richer path family's local
optimum? For
chosen transports of ``bench_optimize.py``'s setup (same transports, seeds,
planner, held object and grasp constraint; each transport planned and
shaped alone, its planner seeded ``seed + index`` as the benchmark does),
this solves one KTO per transport:

- q(t) = r(t / T), r a clamped B-spline of order ``--order`` with
  ``--control-points`` control points; minimise T (``AddDurationCost``);
- r(0) = q_grasp, r(1) = q_place, r'(0) = r'(1) = 0;
- joint position, velocity and acceleration bounds (``AddPositionBounds``,
  ``AddVelocityBounds``, ``AddAccelerationBounds``: on the control points,
  sufficient);
- the grasp constraint ``F w <= g`` at ``--samples`` normalised times (and
  the vertical segments' samples), w the object wrench at (q, qd, qdd) =
  (r, r'/T, r''/T^2) (the retimer's :class:`rt_drake.dynamics.chain.SerialChain`
  kernels; gradients by central differences in (r, r', r'') and exactly in
  T). Each sample carries only its own rows: those within ``--row-share`` of
  their bound in its cell (the part of the initial guess, at 1 kHz, nearer
  to it than to any other sample), at most ``--max-rows``. After a solve the
  rows a cell's KTO trajectory violates are added and the KTO solved again
  (at most ``--rounds`` programs);
- vertical ends: r(tau_up) = the optimiser family's configuration 3 cm above
  the grasp (same cup orientation), tau_up its normalised time on the initial
  guess, and the cup's horizontal drift from the grasp <= 0.5 mm at 5 samples
  in [0, tau_up]; the same above the place;
- cup tilt <= 45 deg (the optimiser's bound) at the samples.

Cost. With every row within 0.3 of its bound on all samples (623 of 834
rows x 50 samples, the earlier scheme), one SNOPT solve took 52 s of CPU
and the first transport of ``--seed 11 --time-limit 30`` did not finish in
15 min: the program had 31,000 nonlinear constraints, and SNOPT's "Time
limit" option is not honoured here (a 3 s limit ran 53 s). With rows per
cell, a transport's solve takes about 0.5-4 s of CPU (BENCHMARKS.md, "The
KTO reference"). The time limit is honoured by the script itself: SNOPT
runs in chunks of ``--chunk`` major iterations, each warm-started from the
last, and stops once ``--time-limit`` CPU seconds are spent (checked after
each chunk) or SNOPT ends for another reason than its iteration limit. The
iterate kept is the feasible one (every constraint of the program within
1e-5) of least T, else the last.

Initial guess: the optimiser's path, retimed (the adaptive 400-point
retime), fitted by least squares. (``--guess spline``, the spline path,
ended infeasible, SNOPT 13, on the four transports tried: the vertical
ends' times then come from another path.) With ``--collision-samples K``, a
``MinimumDistanceLowerBoundConstraint`` on the planner's checker (carried
object attached) of ``--clearance`` m at K samples between the vertical
segments. Without it, a KTO path that the planner's check finds colliding
is solved again from the same guess with 40 such samples and three more
around each collision found, at most ``--collision-rounds`` times. The KTO
path is a clamped chord-length spline through 200 samples of r at equal
steps of its joint-space length. Its duration, ``kto``, is its exact retime
under the grasp constraint by the optimiser's scheme
(``MoveOptimizer.retime``: ``rt_drake.retime`` on the adaptive grid;
``kto1k`` at 1000 uniform points), the same scheme as the shaped MOVE's
``cma``; the KTO trajectory and the retimed one are checked at 1 kHz
(``check_trajectory``). A KTO path is valid (and enters the medians) if it
passes the optimiser's own acceptance: the planner's dense collision check
with the carried object (``check_path``), the tilt bound (+0.5 deg between
samples) and the vertical ends within 1 mm.

Printed per transport (s): ``spl100`` the spline path at 100 uniform points
(the issue's denominator), ``spl`` on the adaptive scheme, ``cma`` the
shaped MOVE, ``T`` the KTO's own duration, ``kto``, ``kto1k``; the ratios
to spl100 and ``kto/cma``; the checks and the solve's CPU time. The JSON
(``--json``) is rewritten after every transport, so a run stopped early
still reports what it finished. ``--paths DIR`` keeps each transport's
spline, shaped and KTO waypoints in ``DIR/<seed>_<index>.npz``.

    OPENBLAS_NUM_THREADS=1 python tools/kto_reference.py --seed 0 --json out/kto0.json
    OPENBLAS_NUM_THREADS=1 python tools/kto_reference.py --seed 11 \\
        --time-limit 30 --indices 15 3 7 12 0
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys
import time
from pathlib import Path

import numpy as np
from pydrake.autodiffutils import ExtractGradient, ExtractValue, InitializeAutoDiff
from pydrake.math import BsplineBasis, KnotVectorType
from pydrake.multibody.inverse_kinematics import MinimumDistanceLowerBoundConstraint
from pydrake.planning import KinematicTrajectoryOptimization
from pydrake.solvers import SnoptSolver, SolverOptions
from pydrake.trajectories import BsplineTrajectory
from scipy.interpolate import BSpline

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
from bench_optimize import Setup  # noqa: E402

from rt_drake import PlanningError, RetimeError, check_trajectory, retime  # noqa: E402
from rt_drake.planning.dense_check import check_path  # noqa: E402
from rt_drake.retiming import Margin  # noqa: E402
from rt_drake.shaping import (  # noqa: E402
    MoveOptimizer,
    MoveOptimizerOptions,
    vertical_drift,
)
from rt_drake.shaping._options import VERTICAL_DRIFT  # noqa: E402
from rt_drake.types.path import GeometricPath  # noqa: E402
from rt_drake.types.phase import Phase  # noqa: E402

#: m: horizontal drift allowed at the vertical segments' samples.
DRIFT_TOLERANCE = 5e-4
#: Samples on each vertical segment (inside, ends excluded).
VERTICAL_SAMPLES = 5
#: Relative step of the central differences in (r, r', r'').
STEP = 1e-6
#: A KTO iterate is feasible if every constraint holds within this (the grasp
#: rows are normalised, ``F w / g - 1``; drift in m; tilt as a cosine).
FEASIBILITY_TOLERANCE = 1e-5
#: SNOPT's exit code when it stops at its major iteration limit.
SNOPT_MAJOR_LIMIT = 32
#: rad: tilt allowed above the optimiser's bound between the KTO's samples.
TILT_TOLERANCE = np.radians(0.5)


@dataclasses.dataclass
class Solved:
    """What :meth:`Kto.solve` returns.

    Attributes:
        trajectory: The KTO trajectory kept (the best feasible iterate, or the
            last one if none was feasible).
        feasible: Whether it satisfies every constraint of its program
            (``CheckSatisfied``, tolerance :data:`FEASIBILITY_TOLERANCE`).
        info: SNOPT's exit code of the last chunk (1: optimal; 32: major
            iteration limit, i.e. a chunk ended).
        cpu_s: This process's CPU time (s) of the solve.
        chunks: SNOPT calls made.
        rounds: Row selections solved.
        stopped: Why the solve stopped ("optimal", "time limit", ...).
    """

    trajectory: BsplineTrajectory
    feasible: bool
    info: int
    cpu_s: float
    chunks: int
    rounds: int
    stopped: str


class Kto:
    """One transport's KTO (module docstring)."""

    def __init__(self, optimizer, move, grasp, result, args) -> None:
        self.chain = optimizer.chain
        self.held = grasp.held
        self.grasp = grasp
        self.args = args
        self.n = self.chain.num_joints
        family = optimizer._family(move, optimizer.options.via_points)
        self.q_up, self.q_down = family.up[-1], family.down[0]
        self.q0, self.q1 = move.path.waypoints[0], move.path.waypoints[-1]
        self.tilt_cos = np.cos(optimizer.options.tilt_bound)
        down = self.chain.gravity_W / np.linalg.norm(self.chain.gravity_W)
        self.down = down
        self.horizontal = np.linalg.svd(np.eye(3) - np.outer(down, down))[0][:, :2]
        self.p0 = self.chain.cup_pose(self.q0)[1]
        self.p1 = self.chain.cup_pose(self.q1)[1]
        # The initial guess: the optimiser's (or the spline) path, retimed.
        spline = args.guess == "spline" or not result.improved
        retimed = result.spline_retimed if spline else result.retimed
        self.T0 = retimed.duration
        s_up, s_down = family.segment_ends(result.path.knots)
        if spline:  # the spline path: where the cup is 3 cm above its ends
            s_up, s_down = _spline_segment_ends(
                self.chain, result.path, self.p0, self.p1
            )
        dt = 2 * np.diff(retimed.gridpoints) / (retimed.sd[:-1] + retimed.sd[1:])
        t_grid = np.concatenate([[0.0], np.cumsum(dt)])
        self.tau_up = float(np.interp(s_up, retimed.gridpoints, t_grid) / self.T0)
        self.tau_down = float(np.interp(s_down, retimed.gridpoints, t_grid) / self.T0)
        times = np.linspace(0.0, self.T0, 600)
        self.q_guess = np.array([retimed.trajectory.value(t).ravel() for t in times])
        self.tau_guess = times / self.T0
        # The samples: (tau, side), side "up"/"down" on a vertical segment.
        self.samples: list[tuple[float, str | None]] = [
            (float(tau), None) for tau in np.linspace(0.0, 1.0, args.samples)
        ]
        for lo, hi, side in ((0.0, self.tau_up, "up"), (self.tau_down, 1.0, "down")):
            inner = np.linspace(lo, hi, VERTICAL_SAMPLES + 2)[1:-1]
            self.samples += [(float(tau), side) for tau in inner]
        self.rows = self.cell_rows(self.initial_bspline(), args.row_share, None)
        #: Extra collision samples (where an earlier solution collided).
        self.collision_taus: list[float] = []

    def cell_rows(self, traj, share: float, rows) -> list[np.ndarray]:
        """Per sample, its rows: those within ``share`` of their bound in its cell.

        The cell of a sample is the part of the trajectory (at 1 kHz) nearer
        to it than to any other sample. With ``rows`` given, returns them with
        the rows that exceed their bound (``F w / g > share``) in each cell
        added; else at most ``max_rows`` per sample, the highest first.
        """
        T = traj.end_time()
        count = int(1000 * T) + 1
        ratio = self.wrench_ratio(traj, count)
        taus = np.array([tau for tau, _ in self.samples])
        tau_dense = np.linspace(0.0, 1.0, count)
        cell = np.argmin(np.abs(tau_dense[:, None] - taus[None]), axis=1)
        chosen = []
        for i in range(len(taus)):
            peak = ratio[cell == i].max(axis=0)
            near = np.flatnonzero(peak >= share)
            if rows is None:
                near = near[np.argsort(-peak[near])][: self.args.max_rows]
                chosen.append(np.sort(near))
            else:
                chosen.append(np.union1d(rows[i], near))
        return chosen

    def wrench_ratio(self, traj, count: int) -> np.ndarray:
        """(count, R) ``F w / g`` along a trajectory, by the batched chain."""
        t = np.linspace(traj.start_time(), traj.end_time(), count)
        q = np.array([traj.value(ti).ravel() for ti in t])
        qd = np.array([traj.EvalDerivative(ti, 1).ravel() for ti in t])
        qdd = np.array([traj.EvalDerivative(ti, 2).ravel() for ti in t])
        _, b, c = self.chain.wrench_coefficients(self.held, q, qd, qdd)
        w = b + c  # u = 0, x = 1 with q' = qd, q'' = qdd
        return (w @ self.grasp.F.T) / self.grasp.g

    # -- the B-spline --------------------------------------------------------

    def basis(self) -> BsplineBasis:
        return BsplineBasis(
            self.args.order, self.args.control_points,
            KnotVectorType.kClampedUniform, 0.0, 1.0,
        )  # fmt: skip

    def initial_control_points(self) -> np.ndarray:
        """(N, n) least-squares fit to the guess, ends and end slopes fixed."""
        knots = np.asarray(self.basis().knots())
        k, N = self.args.order - 1, self.args.control_points
        B = BSpline(knots, np.eye(N), k)(np.clip(self.tau_guess, 0, 1 - 1e-12))
        P = np.zeros((N, self.n))
        P[:2], P[-2:] = self.q0, self.q1
        free = slice(2, N - 2)
        rhs = self.q_guess - B[:, :2] @ P[:2] - B[:, -2:] @ P[-2:]
        P[free] = np.linalg.lstsq(B[:, free], rhs, rcond=None)[0]
        return P

    def initial_bspline(self) -> BsplineTrajectory:
        P = self.initial_control_points()
        knots = np.asarray(self.basis().knots()) * self.T0
        basis = BsplineBasis(self.args.order, list(knots))
        return BsplineTrajectory(basis, [p.reshape(-1, 1) for p in P])

    # -- constraints ----------------------------------------------------------

    def sample_terms(self, tau: float):
        """Basis values (k,) of r, r', r'' at tau and the active indices."""
        knots = np.asarray(self.basis().knots())
        N, k = self.args.control_points, self.args.order - 1
        spline = BSpline(knots, np.eye(N), k)
        t = min(tau, 1 - 1e-12)
        values = [spline(t, nu) for nu in range(3)]
        active = np.flatnonzero(np.any(np.abs(np.array(values)) > 1e-14, axis=0))
        return active, [v[active] for v in values]

    def add_sample(self, prog, cp, T, tau: float, vertical, rows) -> None:
        """Grasp ``rows``, tilt and (on a vertical segment) drift at tau."""
        active, (B0, B1, B2) = self.sample_terms(tau)
        variables = np.concatenate([cp[:, active].T.ravel(), [T]])
        k, n = len(active), self.n
        F, g = self.grasp.F[rows], self.grasp.g[rows]
        n_out = len(rows) + 1 + (2 if vertical else 0)
        p_ref = self.p0 if vertical == "up" else self.p1

        def values(z, T):
            """Outputs for (S, 3n) stacked states z = (r, r', r'')."""
            q, d1, d2 = z[:, :n], z[:, n : 2 * n], z[:, 2 * n :]
            _, b, c = self.chain.wrench_coefficients(self.held, q, d1, d2)
            R, p = self.chain.cup_pose(q)
            return b, c, R[:, :, 2] @ self.down, (p - p_ref) @ self.horizontal

        def evaluate(x):
            autodiff = x.dtype == object
            xv = ExtractValue(x).ravel() if autodiff else np.asarray(x, float)
            P = xv[:-1].reshape(k, n)
            Tv = xv[-1]
            z0 = np.concatenate([B0 @ P, B1 @ P, B2 @ P])
            h = STEP * np.maximum(1.0, np.abs(z0))
            # The value alone, or with central differences in z.
            Z = (
                np.vstack([z0, z0 + np.diag(h), z0 - np.diag(h)])
                if autodiff
                else z0[None]
            )
            b, c, cos, drift = values(Z, Tv)
            out = ((b / Tv**2 + c) @ F.T) / g - 1.0
            full = np.column_stack([out, -cos[:, None]] + ([drift] if vertical else []))
            y = full[0]
            if not autodiff:
                return y
            m = 3 * n
            dz = (full[1 : 1 + m] - full[1 + m :]) / (2 * h[:, None])  # (3n, out)
            # chain rule: z = (B0 P, B1 P, B2 P), P (k, n) row-major
            J = np.zeros((n_out, k * n + 1))
            for j, Bj in enumerate((B0, B1, B2)):
                block = dz[j * n : (j + 1) * n].T  # (out, n)
                J[:, : k * n] += np.einsum("on,a->oan", block, Bj).reshape(n_out, k * n)
            dT = np.zeros(n_out)
            dT[: len(rows)] = ((-2.0 * b[0] / Tv**3) @ F.T) / g
            J[:, -1] = dT
            return InitializeAutoDiff(y, J @ ExtractGradient(x))

        upper = np.concatenate(
            [np.zeros(len(rows)), [-self.tilt_cos]]
            + ([np.full(2, DRIFT_TOLERANCE)] if vertical else [])
        )
        lower = np.concatenate(
            [np.full(len(rows), -np.inf), [-1.0]]
            + ([np.full(2, -DRIFT_TOLERANCE)] if vertical else [])
        )
        prog.AddConstraint(evaluate, lower, upper, variables, f"sample {tau:.3f}")

    def rest_to_rest(self, scene, limits):
        """(KTO, its program): minimum T from rest at q0 to rest at q1.

        ``args.control_points`` control points of order ``args.order`` over
        [0, 1], T in [0.2, 2] T0; the joint position bounds of ``scene`` and
        the velocity and acceleration bounds of ``limits`` on the control
        points.
        """
        kto = KinematicTrajectoryOptimization(
            self.n, self.args.control_points, self.args.order, self.T0
        )
        prog = kto.get_mutable_prog()
        kto.AddDurationCost(1.0)
        kto.AddPositionBounds(scene.lower, scene.upper)
        kto.AddVelocityBounds(-limits.velocity, limits.velocity)
        kto.AddAccelerationBounds(-limits.acceleration, limits.acceleration)
        kto.AddDurationConstraint(0.2 * self.T0, 2.0 * self.T0)
        zero = np.zeros(self.n)
        kto.AddPathPositionConstraint(self.q0, self.q0, 0.0)
        kto.AddPathPositionConstraint(self.q1, self.q1, 1.0)
        kto.AddPathVelocityConstraint(zero, zero, 0.0)
        kto.AddPathVelocityConstraint(zero, zero, 1.0)
        return kto, prog

    def program(self, setup, scene, guess, collision):
        """(KTO, its program) with the current rows, initial guess ``guess``."""
        kto, prog = self.rest_to_rest(scene, setup.limits)
        kto.AddPathPositionConstraint(self.q_up, self.q_up, self.tau_up)
        kto.AddPathPositionConstraint(self.q_down, self.q_down, self.tau_down)
        cp, T = kto.control_points(), kto.duration()
        assert np.allclose(kto.basis().knots(), self.basis().knots())
        for (tau, side), rows in zip(self.samples, self.rows, strict=True):
            self.add_sample(prog, cp, T, tau, side, rows)
        if collision is not None:  # between the vertical segments
            taus = np.union1d(
                np.linspace(self.tau_up, self.tau_down, self.args.collision_samples),
                self.collision_taus,
            )
            for tau in taus:
                kto.AddPathPositionConstraint(collision, float(tau))
        kto.SetInitialGuess(guess)
        return kto, prog

    def solve(self, setup, scene) -> Solved:
        """SNOPT in chunks of ``chunk`` major iterations within ``time_limit`` CPU s.

        SNOPT's own "Time limit" option is not honoured by Drake's SNOPT (a
        3 s limit ran 53 s of CPU), so the solve stops itself: after each
        chunk (warm-started from the last), it stops if SNOPT reported
        anything but its major iteration limit, or if the CPU time is spent.
        The iterate kept is the feasible one of least duration, else the
        last. Rows are then re-selected (:meth:`cell_rows`) for at most
        ``rounds`` programs while time is left.
        """
        args = self.args
        collision = None
        if args.collision_samples:
            checker_context = scene.checker.MakeStandaloneModelContext()
            collision = MinimumDistanceLowerBoundConstraint(
                scene.checker, args.clearance, checker_context, None,
                args.influence,
            )  # fmt: skip
            self._keep = (checker_context, collision)
        cpu = time.process_time()
        snopt = SnoptSolver()
        options = SolverOptions()
        options.SetOption(snopt.id(), "Major iterations limit", args.chunk)
        options.SetOption(snopt.id(), "Major feasibility tolerance", 1e-6)
        options.SetOption(snopt.id(), "Major optimality tolerance", 1e-5)
        guess, chunks, rounds = self.initial_bspline(), 0, 0
        best: tuple[float, BsplineTrajectory] | None = None
        last, info, stopped = guess, 0, "rounds"
        while rounds < args.rounds:
            rounds += 1
            kto, prog = self.program(setup, scene, guess, collision)
            best = None  # feasible for this program's rows
            x = prog.GetInitialGuess(prog.decision_variables())
            for _ in range(max(1, args.iterations // args.chunk)):
                result = snopt.Solve(prog, x, options)
                chunks += 1
                x = result.GetSolution()
                info = int(result.get_solver_details().info)
                last = kto.ReconstructTrajectory(result)
                if prog.CheckSatisfied(
                    prog.GetAllConstraints(), x, FEASIBILITY_TOLERANCE
                ) and (best is None or last.end_time() < best[0]):
                    best = (last.end_time(), last)
                if time.process_time() - cpu > args.time_limit:
                    stopped = "time limit"
                    break
                if info != SNOPT_MAJOR_LIMIT:
                    stopped = f"snopt {info}"
                    break
            else:
                stopped = "iterations"
            if stopped == "time limit":
                break
            kept = best[1] if best is not None else last
            rows = self.cell_rows(kept, 1.0 + 1e-3, self.rows)
            if all(len(a) == len(b) for a, b in zip(rows, self.rows, strict=True)):
                break
            self.rows, guess = rows, kept
        feasible = best is not None
        return Solved(
            best[1] if feasible else last, feasible, info,
            time.process_time() - cpu, chunks, rounds, stopped,
        )  # fmt: skip


def _spline_segment_ends(chain, path, p0, p1) -> tuple[float, float]:
    """S where the spline path's cup first/last is 3 cm above its ends."""
    s = np.linspace(0, 1, 2001)
    p = chain.cup_pose(path.value(s))[1]
    up = -chain.gravity_W / np.linalg.norm(chain.gravity_W)
    h0, h1 = (p - p0) @ up, (p - p1) @ up
    return float(s[np.argmax(h0 >= 0.03)]), float(
        s[len(s) - 1 - np.argmax(h1[::-1] >= 0.03)]
    )


def path_of(traj, kto: Kto, count: int = 200):
    """Clamped chord-length GeometricPath through ``count`` samples of r, the
    knots of its vertical segment tops, and the samples' tau (one per knot).

    The samples are at equal steps of r's chord length in joint space (from
    4000 uniform ones), not of tau: a rest-to-rest r moves as tau^2 near its
    ends, and points bunched there make the spline's start ill-shaped.
    """
    dense = np.linspace(0.0, 1.0, 4000)
    T = traj.end_time()
    q = np.array([traj.value(t * T).ravel() for t in dense])
    length = np.concatenate(
        [[0.0], np.cumsum(np.linalg.norm(np.diff(q, axis=0), axis=1))]
    )
    taus = np.interp(np.linspace(0.0, length[-1], count), length, dense)
    taus = np.union1d(taus, [kto.tau_up, kto.tau_down])
    q = np.array([traj.value(t * T).ravel() for t in taus])
    path = GeometricPath.from_waypoints(q)
    return (
        path,
        float(path.knots[np.searchsorted(taus, kto.tau_up)]),
        float(path.knots[np.searchsorted(taus, kto.tau_down)]),
        taus,
    )


HEADER = (
    "spl100    spl    cma      T    kto  kto1k  cma/100  kto/100  kto/cma"
    "  rows  collision  tilt  drift mm  grasp T %  retimed chk %  feasible"
    "  chunks  stopped       cpu s"
)


def solve_and_check(setup, optimizer, move, grasp, result, args, extra=(), kind=Kto):
    """(Kto, Solved, (path, s_up, s_down, taus), the planner's collision check).

    ``extra``: collision samples (tau) added to the uniform ones; ``kind``:
    the program (:class:`Kto` or a subclass).
    """
    planner = setup.planner
    scene = planner.prepare(Phase.MOVE, move.object, move.q_start, move.X_OC)
    kto = kind(optimizer, move, grasp, result, args)
    kto.collision_taus = list(extra)
    solved = kto.solve(setup, scene)
    path = path_of(solved.trajectory, kto)
    scene = planner.prepare(Phase.MOVE, move.object, move.q_start, move.X_OC)
    return kto, solved, path, check_path(scene, path[0])


@dataclasses.dataclass
class CollisionFree:
    """What :func:`solve_collision_free` returns.

    Attributes:
        solution: The last ``solve_once`` result: (Kto, Solved, (path, s_up,
            s_down, taus), the planner's collision check).
        cpu_s: CPU time (s) of every solve.
        retries: Solves after the first.
    """

    solution: tuple
    cpu_s: float
    retries: int


def solve_collision_free(solve_once, args) -> CollisionFree:
    """A KTO solved again until the planner's check finds its path clean.

    ``solve_once(args, extra)`` solves one program (:func:`solve_and_check`'s
    result), ``extra`` the collision samples (tau) added to the uniform ones.
    While its path collides (at most ``args.collision_rounds`` times), it is
    solved again from the same guess with collision constraints (40 uniform
    samples if ``args.collision_samples`` asked for none) and three more
    around each collision found (tau +- 0.005), within the vertical ends.
    """
    solution = solve_once(args, [])
    kto, solved, (path, _, _, taus), collision = solution
    cpu_s, retries, extra = solved.cpu_s, 0, []
    again = argparse.Namespace(
        **{**vars(args), "collision_samples": args.collision_samples or 40}
    )
    while not collision.ok and retries < args.collision_rounds:
        retries += 1
        hit = float(np.interp(collision.s, path.knots, taus))
        extra += list(np.clip(hit + np.array([-0.005, 0.0, 0.005]),
                              kto.tau_up, kto.tau_down))  # fmt: skip
        solution = solve_once(again, extra)
        kto, solved, (path, _, _, taus), collision = solution
        cpu_s += solved.cpu_s
    return CollisionFree(solution, cpu_s, retries)


def measure(setup, optimizer, move, grasp, result, args, save=None) -> dict:
    """One transport's KTO, its checks and retimes, and the anchors (s).

    ``save``: an .npz file for the paths' waypoints (rad): the spline path's
    (``spline``), the shaped one's (``shaped``) and the KTO's (``kto``).
    """
    plant, limits, chain = setup.plant, setup.limits, optimizer.chain
    kw = {"context": setup.context, "cup": setup.cup}
    spl100 = retime(plant, move.path, limits, grasp, 100, **kw).duration
    spl1k = retime(plant, move.path, limits, grasp, 1000, **kw).duration
    cma1k = retime(plant, result.path, limits, grasp, 1000, **kw).duration

    def solve_once(args, extra):
        return solve_and_check(setup, optimizer, move, grasp, result, args, extra)

    found = solve_collision_free(solve_once, args)
    kto, solved, (path, s_up, s_down, taus), collision = found.solution
    cpu_s, retries = found.cpu_s, found.retries
    traj, T = solved.trajectory, solved.trajectory.end_time()
    tilt = chain.tilt(path.value(np.linspace(0, 1, 1000))).max()
    drift = max(
        vertical_drift(chain, path, 0.0, s_up), vertical_drift(chain, path, s_down, 1.0)
    )
    own = check_trajectory(plant, traj, limits, grasp, **kw)
    try:
        adaptive = optimizer.retime(path, grasp)
        kto_s = adaptive.duration
        kto1k = retime(plant, path, limits, grasp, 1000, **kw).duration
        check = check_trajectory(plant, adaptive.trajectory, limits, grasp, **kw)
        worst = -check.min_margin()
    except RetimeError as error:
        print(f"    retime failed: {error}")
        kto_s = kto1k = worst = float("nan")
    if save is not None:
        save.parent.mkdir(parents=True, exist_ok=True)
        np.savez(
            save, spline=move.path.waypoints, shaped=result.path.waypoints,
            kto=path.waypoints, kto_knots=path.knots, kto_s_up=s_up,
            kto_s_down=s_down,
        )  # fmt: skip
    # The optimiser's own acceptance (its _certify): collision-free by the
    # planner's check, tilt within the bound, vertical ends within 1 mm.
    valid = bool(
        collision.ok
        and tilt <= optimizer.options.tilt_bound + TILT_TOLERANCE
        and drift <= VERTICAL_DRIFT
        and np.isfinite(kto_s)
    )
    return {
        "spline100_s": spl100, "spline_s": result.spline_duration,
        "cma_s": result.duration, "spline1k_s": spl1k, "cma1k_s": cma1k,
        "kto_T_s": T, "kto_s": kto_s, "kto1k_s": kto1k,
        "cma_ratio_100": result.duration / spl100, "kto_ratio_100": kto_s / spl100,
        "cma_ratio_same_grid": result.duration / result.spline_duration,
        "kto_ratio_same_grid": kto_s / result.spline_duration,
        "kto_over_cma": kto_s / result.duration,
        "kto1k_ratio_100": kto1k / spl100, "kto_T_ratio_100": T / spl100,
        "kto1k_ratio_spl1k": kto1k / spl1k,
        "rows": int(sum(len(r) for r in kto.rows)),
        "valid": valid, "collision_free": collision.ok,
        "collision": collision.reason or "ok", "collision_s": collision.s,
        "tilt_deg": float(np.degrees(tilt)), "drift_mm": 1e3 * drift,
        "kto_own_grasp_excess_pct": -100 * own.margins[Margin.GRASP].value,
        "kto_own_worst_pct": -100 * own.min_margin(),
        "retimed_check_worst_pct": 100 * worst,
        "feasible": solved.feasible, "snopt_info": solved.info,
        "stopped": solved.stopped, "chunks": solved.chunks,
        "cpu_s": cpu_s, "retries": retries, "rounds": solved.rounds,
        "tau_up": kto.tau_up, "tau_down": kto.tau_down,
    }  # fmt: skip


def format_row(r: dict) -> str:
    """One printed line of :data:`HEADER`."""
    return (
        f"{r['spline100_s']:6.3f} {r['spline_s']:6.3f} {r['cma_s']:6.3f} "
        f"{r['kto_T_s']:6.3f} {r['kto_s']:6.3f} {r['kto1k_s']:6.3f} "
        f"{r['cma_ratio_100']:8.3f} {r['kto_ratio_100']:8.3f} "
        f"{r['kto_over_cma']:8.3f} {r['rows']:5d} "
        f"{'ok' if r['collision_free'] else 'HIT':>10} {r['tilt_deg']:5.1f} "
        f"{r['drift_mm']:9.2f} {r['kto_own_grasp_excess_pct']:+10.2f} "
        f"{r['retimed_check_worst_pct']:+14.3f}  {r['feasible']!s:>8} "
        f"{r['chunks']:7d}  {r['stopped']:<12} {r['cpu_s']:6.1f}"
        + (f"  ({r['retries']} with collision constraints)" if r["retries"] else "")
    )


SUMMARY_KEYS = (
    "cma_ratio_100", "kto_ratio_100", "cma_ratio_same_grid",
    "kto_ratio_same_grid", "kto_over_cma", "kto_T_ratio_100", "cpu_s",
)  # fmt: skip


def summary(rows: list[dict]) -> dict:
    """Medians over the transports whose KTO path is valid (the same ones for
    the optimiser's and the KTO's columns)."""
    valid = [r for r in rows if r["valid"]]
    out = {"count": len(rows), "valid": len(valid)}
    for key in SUMMARY_KEYS:
        out[key] = float(np.median([r[key] for r in valid])) if valid else None
    return out


def add_kto_arguments(parser: argparse.ArgumentParser) -> None:
    """The KTO's options (module docstring), on ``parser``."""
    parser.add_argument("--order", type=int, default=5)
    parser.add_argument("--control-points", type=int, default=16)
    parser.add_argument("--samples", type=int, default=40)
    parser.add_argument("--row-share", type=float, default=0.9)
    parser.add_argument("--max-rows", type=int, default=20)
    parser.add_argument("--iterations", type=int, default=300)
    parser.add_argument("--chunk", type=int, default=20)
    parser.add_argument("--time-limit", type=float, default=120.0)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--collision-samples", type=int, default=0)
    parser.add_argument("--collision-rounds", type=int, default=3)
    parser.add_argument("--clearance", type=float, default=0.002)
    parser.add_argument("--influence", type=float, default=0.02)
    parser.add_argument("--guess", choices=["optimised", "spline"], default="optimised")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenario", default="random_transport")
    parser.add_argument("--n", type=int, default=20)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--indices", type=int, nargs="+", default=None)
    add_kto_arguments(parser)
    parser.add_argument("--json", type=Path, default=None)
    parser.add_argument("--paths", type=Path, default=None)
    args = parser.parse_args()

    setup = Setup(args.scenario, args.seed)
    options = MoveOptimizerOptions()
    optimizer = MoveOptimizer(setup.plant, setup.limits, options, setup.cup)
    transports = setup.transports(args.n)
    indices = range(args.n) if args.indices is None else args.indices

    def run(index):
        return setup.optimize(optimizer, index, *transports[index])[:3]

    run(0)  # as bench_optimize.py: compile, load caches
    print(
        f"{setup.path.name}, n={args.n}, seed={args.seed}, order {args.order}, "
        f"{args.control_points} control points, {args.samples} samples, rows "
        f">= {args.row_share} of their bound (at most {args.max_rows} a sample), "
        f"{args.collision_samples} collision samples (clearance {args.clearance} "
        f"m), guess {args.guess}, {args.time_limit} s CPU each"
    )
    print("  # " + HEADER)
    rows: list[dict] = []
    for index in indices:
        # Each transport alone (planner seeded seed + index, as the benchmark).
        try:
            found = run(index)
        except PlanningError as error:
            print(f"{index:3d} planning failed: {error}")
            continue
        save = None if args.paths is None else args.paths / f"{args.seed}_{index}.npz"
        row = measure(setup, optimizer, *found, args, save)
        rows.append({"index": index, **row})
        print(f"{index:3d} " + format_row(row), flush=True)
        if not row["collision_free"]:
            print(f"      {row['collision']} at s = {row['collision_s']:.3f}")
        if args.json:  # after every transport: a stopped run still reports
            args.json.parent.mkdir(parents=True, exist_ok=True)
            args.json.write_text(
                json.dumps({"rows": rows, "summary": summary(rows)}, indent=1)
            )
    result = summary(rows)
    print(f"valid KTO paths: {result['valid']}/{result['count']}; medians over them:")
    for key in SUMMARY_KEYS:
        if result[key] is not None:
            print(f"  median {key}: {result[key]:.3f}")


if __name__ == "__main__":
    main()
