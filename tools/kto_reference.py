"""Offline reference for issue 13: Drake's KinematicTrajectoryOptimization (KTO).

Is the issue's target (median optimised MOVE <= 0.75x the spline path) reachable
with a richer path family than the optimiser's? For chosen transports of
``bench_optimize.py``'s setup (same transports, seeds, planner, held object and
grasp constraint; the CMA-ES optimiser is run over all transports in order, as
the benchmark does, with its defaults and ``--clock process``), this solves,
with no time budget, one KTO per transport:

- q(t) = r(t / T), r a clamped B-spline of order ``--order`` with
  ``--control-points`` control points; minimise T (``AddDurationCost``);
- r(0) = q_grasp, r(1) = q_place, r'(0) = r'(1) = 0;
- joint position, velocity and acceleration bounds (``AddPositionBounds``,
  ``AddVelocityBounds``, ``AddAccelerationBounds``: on the control points,
  sufficient);
- the grasp constraint ``F w <= g`` at ``--samples`` normalised times, w the
  object wrench at (q, qd, qdd) = (r, r'/T, r''/T^2) (the retimer's
  :class:`rt_drake.dynamics.chain.SerialChain` kernels; gradients by central
  differences in (r, r', r'') and exactly in T); the polytope's rows are those
  the initial guess brings within ``--row-share`` of their bound, and rows a
  solution violates (checked at 1 kHz) are added and the KTO solved again;
- vertical ends: r(tau_up) = the optimiser family's configuration 3 cm above
  the grasp (same cup orientation), tau_up its normalised time on the initial
  guess, and the cup's horizontal drift from the grasp <= 0.5 mm at 5 samples
  in [0, tau_up]; the same above the place;
- cup tilt <= 45 deg (the optimiser's bound) at the samples.

Initial guess: the optimiser's path (``--guess spline``: the spline path),
retimed (the adaptive 400-point retime), fitted by least squares. With
``--collision-samples K``, a ``MinimumDistanceLowerBoundConstraint`` on the
planner's checker (carried object attached) of ``--clearance`` m at K samples
between the vertical segments; either way the result is checked afterwards
with the planner's dense check, the carried object included (``check_path``).
The rows are re-selected at most ``--rounds`` times; ``--time-limit`` is
SNOPT's per solve (s). The KTO path is then retimed exactly (``rt_drake.retime``,
1000 uniform points, and the optimiser's adaptive scheme) as a clamped
chord-length spline through 200 samples of r; both the KTO trajectory and the
retimed one are checked at 1 kHz (``check_trajectory``).

Printed per transport (s): ``spl100`` the spline path at 100 uniform points
(the issue's denominator), ``spl`` on the adaptive scheme, ``cma`` the
optimiser's result (0.15 s CPU), ``T`` the KTO's own duration, ``kto`` its path
retimed exactly (adaptive; ``kto1k`` at 1000 points), the ratios to spl100,
the collision verdict, tilt, drift and the solve's CPU time.

    OPENBLAS_NUM_THREADS=1 python tools/kto_reference.py --seed 1 \\
        --collision-samples 40 --indices 6 17 0 15 19
"""

from __future__ import annotations

import argparse
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
from rt_drake.shaping import (
    MoveOptimizer,
    MoveOptimizerOptions,
    vertical_drift,
)
from rt_drake.types.path import GeometricPath  # noqa: E402
from rt_drake.types.phase import Phase  # noqa: E402

#: m: horizontal drift allowed at the vertical segments' samples.
DRIFT_TOLERANCE = 5e-4
#: Samples on each vertical segment (inside, ends excluded).
VERTICAL_SAMPLES = 5
#: Relative step of the central differences in (r, r', r'').
STEP = 1e-6


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
        self.rows = self.initial_rows()

    def initial_rows(self) -> np.ndarray:
        """Rows within ``row_share`` of their bound somewhere on the initial guess."""
        ratio = self.wrench_ratio(self.initial_bspline(), 1000)
        return np.flatnonzero(ratio.max(axis=0) >= self.args.row_share)

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

    def add_sample(self, prog, cp, T, tau: float, vertical: str | None) -> None:
        """Grasp rows, tilt and (on a vertical segment) drift at tau."""
        active, (B0, B1, B2) = self.sample_terms(tau)
        variables = np.concatenate([cp[:, active].T.ravel(), [T]])
        k, n = len(active), self.n
        rows = self.rows
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
            Z = np.vstack([z0, z0 + np.diag(h), z0 - np.diag(h)])
            b, c, cos, drift = values(Z, Tv)
            wr = b / Tv**2 + c
            out = (wr @ F.T) / g - 1.0
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

    def solve(self, setup, scene):
        """(KTO trajectory, T, solver result, CPU s, rounds)."""
        lower, upper = scene.lower, scene.upper
        collision = None
        if self.args.collision_samples:
            checker_context = scene.checker.MakeStandaloneModelContext()
            collision = MinimumDistanceLowerBoundConstraint(
                scene.checker, self.args.clearance, checker_context, None,
                self.args.influence,
            )  # fmt: skip
            self._keep = (checker_context, collision)
        cpu = time.process_time()
        guess = self.initial_bspline()
        rounds = 0
        while True:
            rounds += 1
            kto = KinematicTrajectoryOptimization(self.n, self.args.control_points,
                                                  self.args.order, self.T0)  # fmt: skip
            prog = kto.get_mutable_prog()
            kto.AddDurationCost(1.0)
            kto.AddPositionBounds(lower, upper)
            kto.AddVelocityBounds(-setup.limits.velocity, setup.limits.velocity)
            kto.AddAccelerationBounds(
                -setup.limits.acceleration, setup.limits.acceleration
            )
            kto.AddDurationConstraint(0.2 * self.T0, 2.0 * self.T0)
            zero = np.zeros(self.n)
            kto.AddPathPositionConstraint(self.q0, self.q0, 0.0)
            kto.AddPathPositionConstraint(self.q1, self.q1, 1.0)
            kto.AddPathVelocityConstraint(zero, zero, 0.0)
            kto.AddPathVelocityConstraint(zero, zero, 1.0)
            kto.AddPathPositionConstraint(self.q_up, self.q_up, self.tau_up)
            kto.AddPathPositionConstraint(self.q_down, self.q_down, self.tau_down)
            cp, T = kto.control_points(), kto.duration()
            assert np.allclose(kto.basis().knots(), self.basis().knots())
            taus = list(np.linspace(0.0, 1.0, self.args.samples))
            for tau in taus:
                self.add_sample(prog, cp, T, float(tau), None)
            for lo, hi, side in (
                (0.0, self.tau_up, "up"),
                (self.tau_down, 1.0, "down"),
            ):
                for tau in np.linspace(lo, hi, VERTICAL_SAMPLES + 2)[1:-1]:
                    self.add_sample(prog, cp, T, float(tau), side)
            if collision is not None:  # between the vertical segments
                taus = np.linspace(
                    self.tau_up, self.tau_down, self.args.collision_samples
                )
                for tau in taus:
                    kto.AddPathPositionConstraint(collision, float(tau))
            kto.SetInitialGuess(guess)
            options = SolverOptions()
            snopt = SnoptSolver()
            options.SetOption(
                snopt.id(), "Major iterations limit", self.args.iterations
            )
            options.SetOption(snopt.id(), "Major feasibility tolerance", 1e-6)
            options.SetOption(snopt.id(), "Major optimality tolerance", 1e-5)
            options.SetOption(snopt.id(), "Time limit", float(self.args.time_limit))
            result = snopt.Solve(prog, None, options)
            traj = kto.ReconstructTrajectory(result)
            ratio = self.wrench_ratio(traj, int(1000 * traj.end_time()) + 1)
            worst = ratio.max(axis=0) - 1.0
            new = np.setdiff1d(np.flatnonzero(worst > 1e-3), self.rows)
            if len(new) == 0 or rounds >= self.args.rounds:
                break
            self.rows = np.union1d(self.rows, new)
            guess = traj
        return traj, traj.end_time(), result, time.process_time() - cpu, rounds


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
    """Clamped chord-length GeometricPath through ``count`` samples of r, and the
    knots of its vertical segment tops.
    """
    taus = np.union1d(np.linspace(0, 1, count), [kto.tau_up, kto.tau_down])
    T = traj.end_time()
    q = np.array([traj.value(t * T).ravel() for t in taus])
    path = GeometricPath.from_waypoints(q)
    return (
        path,
        float(path.knots[np.searchsorted(taus, kto.tau_up)]),
        float(path.knots[np.searchsorted(taus, kto.tau_down)]),
    )


HEADER = (
    "spl100    spl    cma  spl1k  cma1k      T    kto  kto1k  cma/100  kto/100"
    "  kto1k/spl1k  rows  collision  tilt  drift mm  grasp T %  retimed chk %"
    "  snopt  cpu s"
)


def measure(setup, optimizer, move, grasp, result, args) -> dict:
    """One transport's KTO, its checks and retimes, and the anchors (s)."""
    plant, limits, planner, chain = (
        setup.plant, setup.limits, setup.planner, optimizer.chain
    )  # fmt: skip
    kw = {"context": setup.context, "cup": setup.cup}
    spl100 = retime(plant, move.path, limits, grasp, 100, **kw).duration
    spl1k = retime(plant, move.path, limits, grasp, 1000, **kw).duration
    cma1k = retime(plant, result.path, limits, grasp, 1000, **kw).duration
    scene = planner.prepare(Phase.MOVE, move.object, move.q_start, move.X_OC)
    kto = Kto(optimizer, move, grasp, result, args)
    traj, T, solved, cpu_s, rounds = kto.solve(setup, scene)
    path, s_up, s_down = path_of(traj, kto)
    scene = planner.prepare(Phase.MOVE, move.object, move.q_start, move.X_OC)
    collision = check_path(scene, path)
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
    return {
        "spline100_s": spl100, "spline_s": result.spline_duration,
        "cma_s": result.duration, "spline1k_s": spl1k, "cma1k_s": cma1k,
        "kto_T_s": T, "kto_s": kto_s, "kto1k_s": kto1k,
        "cma_ratio_100": result.duration / spl100, "kto_ratio_100": kto_s / spl100,
        "kto1k_ratio_100": kto1k / spl100, "kto_T_ratio_100": T / spl100,
        "kto1k_ratio_spl1k": kto1k / spl1k, "rows": len(kto.rows),
        "collision_free": collision.ok,
        "collision": collision.reason or "ok", "collision_s": collision.s,
        "tilt_deg": float(np.degrees(tilt)), "drift_mm": 1e3 * drift,
        "kto_own_grasp_excess_pct": -100 * own.margins[Margin.GRASP].value,
        "kto_own_worst_pct": -100 * own.min_margin(),
        "retimed_check_worst_pct": 100 * worst,
        "snopt": str(solved.get_solution_result()),
        "snopt_info": int(solved.get_solver_details().info),
        "cpu_s": cpu_s, "rounds": rounds, "tau_up": kto.tau_up,
        "tau_down": kto.tau_down,
    }  # fmt: skip


def format_row(r: dict) -> str:
    """One printed line of :data:`HEADER`."""
    return (
        f"{r['spline100_s']:6.3f} {r['spline_s']:6.3f} {r['cma_s']:6.3f} "
        f"{r['spline1k_s']:6.3f} {r['cma1k_s']:6.3f} {r['kto_T_s']:6.3f} "
        f"{r['kto_s']:6.3f} {r['kto1k_s']:6.3f} {r['cma_ratio_100']:8.3f} "
        f"{r['kto_ratio_100']:8.3f} {r['kto1k_ratio_spl1k']:12.3f} {r['rows']:5d} "
        f"{'ok' if r['collision_free'] else 'HIT':>10} {r['tilt_deg']:5.1f} "
        f"{r['drift_mm']:9.2f} {r['kto_own_grasp_excess_pct']:+10.2f} "
        f"{r['retimed_check_worst_pct']:+14.3f}  {r['snopt_info']:5d} "
        f"{r['cpu_s']:6.1f}"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenario", default="random_transport")
    parser.add_argument("--n", type=int, default=20)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--indices", type=int, nargs="+", required=True)
    parser.add_argument("--order", type=int, default=5)
    parser.add_argument("--control-points", type=int, default=16)
    parser.add_argument("--samples", type=int, default=40)
    parser.add_argument("--row-share", type=float, default=0.3)
    parser.add_argument("--iterations", type=int, default=300)
    parser.add_argument("--time-limit", type=float, default=60.0)
    parser.add_argument("--rounds", type=int, default=2)
    parser.add_argument("--collision-samples", type=int, default=0)
    parser.add_argument("--clearance", type=float, default=0.002)
    parser.add_argument("--influence", type=float, default=0.02)
    parser.add_argument("--guess", choices=["optimised", "spline"], default="optimised")
    parser.add_argument("--json", type=Path, default=None)
    args = parser.parse_args()

    setup = Setup(args.scenario, args.seed)
    options = MoveOptimizerOptions()
    optimizer = MoveOptimizer(setup.plant, setup.limits, options, setup.cup)
    plant, limits = setup.plant, setup.limits
    kw = {"context": setup.context, "cup": setup.cup}
    transports = setup.transports(args.n)

    def run(index, X_start, X_goal):
        return setup.optimize(optimizer, index, X_start, X_goal)[:3]

    run(0, *transports[0])  # as bench_optimize.py: compile, load caches
    print(
        f"{setup.path.name}, n={args.n}, seed={args.seed}, order {args.order}, "
        f"{args.control_points} control points, {args.samples} samples, "
        f"{args.collision_samples} collision samples (clearance {args.clearance} m), "
        f"guess {args.guess}"
    )
    found = {}
    for index, (X_start, X_goal) in enumerate(transports):
        try:
            found[index] = run(index, X_start, X_goal)
        except PlanningError as error:
            print(f"{index:3d} planning failed: {error}")
    for index, (move, grasp, result) in found.items():
        spl100 = retime(plant, move.path, limits, grasp, 100, **kw).duration
        print(
            f"cma {index:3d}: spline100 {spl100:.3f} s, optimised "
            f"{result.duration:.3f} s, ratio {result.duration / spl100:.3f}, "
            f"cpu {1e3 * result.cpu_s:.0f} ms"
        )
    print("  # " + HEADER)
    rows = []
    for index in args.indices:
        row = measure(setup, optimizer, *found[index], args)
        rows.append({"index": index, **row})
        print(f"{index:3d} " + format_row(row), flush=True)
        if not row["collision_free"]:
            print(f"      {row['collision']} at s = {row['collision_s']:.3f}")
        if args.json:
            args.json.parent.mkdir(parents=True, exist_ok=True)
            args.json.write_text(json.dumps(rows, indent=1))
    for key in (
        "cma_ratio_100",
        "kto_ratio_100",
        "kto_T_ratio_100",
        "kto1k_ratio_spl1k",
    ):
        print(f"median {key}: {np.nanmedian([r[key] for r in rows]):.3f}")


if __name__ == "__main__":
    main()
