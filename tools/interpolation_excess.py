"""How much of a controller's interpolation the grasp guarantee absorbs.

Retimed Table I MOVEs (``random_transport_paper``, the grasp constraint, the
transports and seeds of ``rt-drake experiment transport --seed S``) are
exported at 2, 4 and 8 ms (:func:`rt_drake.export.sample_on_grid`: the grid,
padded at rest). The motion a controller makes between the samples is
reconstructed three ways, on each interval ``[t_k, t_k+1]`` of length T:

- ``quintic``: the quintic Hermite through positions, velocities and
  accelerations at both ends (C2);
- ``cubic``: the cubic Hermite through positions and velocities (C1; its
  acceleration jumps at the samples);
- ``linear``: the polyline of the positions. Its velocity jumps at every
  sample, so its acceleration is impulsive: here the velocity and
  acceleration are those a 1 kHz servo commands when it follows the
  polyline, central finite differences of the positions at 1 kHz
  (``numpy.gradient``), i.e. the impulse spread over 1 ms.

Each reconstruction is checked at 1 kHz by :func:`rt_drake.check_trajectory`
against the MOVE's own grasp rows: the grasp margin ``1 - max F w / g``
(negative: outside the set) against the retimed trajectory's own, and the
largest position deviation ``max |q_ctrl(t) - q(t)|`` at 1 kHz. With
``--margins`` the MOVEs are retimed again under ``F w <= (1 - m) g``
(:meth:`GraspConstraint.with_margin`, scenario key
``planning.grasp_margin``) and each reconstruction is checked against the
unshrunk set: the smallest m whose worst margin is >= 0 covers that
interpolation.

    python tools/interpolation_excess.py --n 6 --seed 0 --margins 0.01 0.02 0.05
"""

from __future__ import annotations

import argparse
import dataclasses

import numpy as np
from pydrake.trajectories import Trajectory

from rt_drake import CupFrame, JointLimits, check_trajectory, load_scenario, retime
from rt_drake.experiments._transport_experiment import (
    move_from_the_cup,
    transport_scenario,
)
from rt_drake.export import GridSamples, sample_on_grid
from rt_drake.model.plant import make_arm_plant
from rt_drake.model.resources import scenarios_dir
from rt_drake.planning import PlanningError, sample_transports
from rt_drake.retiming import Margin
from rt_drake.simulation import OnlineMotions

PERIODS = (0.002, 0.004, 0.008)
KINDS = ("linear", "cubic", "quintic")
RATE_HZ = 1000.0


class Reconstructed(Trajectory):
    """The motion a controller makes from samples, for ``check_trajectory``.

    ``sample(times, order=2)`` gives ``[q, q', q'']`` (rad, rad/s, rad/s^2)
    at ``times`` (s); beyond the last sample it holds the last pose.
    """

    def __init__(self, samples: GridSamples, kind: str) -> None:
        Trajectory.__init__(self)
        self._s, self._kind = samples, kind

    def sample(self, times: np.ndarray, order: int = 2) -> list[np.ndarray]:
        assert order == 2
        s, times = self._s, np.atleast_1d(np.asarray(times, dtype=float))
        if self._kind == "linear":
            q = np.stack(
                [np.interp(times, s.t, s.q[:, j]) for j in range(s.q.shape[1])], 1
            )
            qd = np.gradient(q, times, axis=0)
            return [q, qd, np.gradient(qd, times, axis=0)]
        T = s.period
        k = np.clip(np.floor(times / T).astype(int), 0, len(s.t) - 2)
        x = np.clip((times - s.t[k]) / T, 0.0, 1.0)[:, None]
        q0, q1 = s.q[k], s.q[k + 1]
        v0, v1 = s.qd[k] * T, s.qd[k + 1] * T  # per unit x
        if self._kind == "cubic":
            a0 = a1 = np.zeros_like(q0)
            c = [q0, v0, 3 * (q1 - q0) - 2 * v0 - v1, 2 * (q0 - q1) + v0 + v1]
        else:
            a0, a1 = s.qdd[k] * T**2, s.qdd[k + 1] * T**2
            d = q1 - q0
            c = [
                q0,
                v0,
                a0 / 2,
                10 * d - 6 * v0 - 4 * v1 - 1.5 * a0 + 0.5 * a1,
                -15 * d + 8 * v0 + 7 * v1 + 1.5 * a0 - a1,
                6 * d - 3 * v0 - 3 * v1 - 0.5 * a0 + 0.5 * a1,
            ]
        q = sum(ci * x**i for i, ci in enumerate(c))
        qd = sum(i * ci * x ** (i - 1) for i, ci in enumerate(c) if i >= 1) / T
        qdd = sum(i * (i - 1) * ci * x ** (i - 2) for i, ci in enumerate(c) if i >= 2)
        return [q, qd, qdd / T**2]

    def do_value(self, t: float) -> np.ndarray:
        return self.sample(np.array([t]))[0].reshape(-1, 1)

    def do_has_derivative(self) -> bool:
        return False

    def do_rows(self) -> int:
        return int(self._s.q.shape[1])

    def do_cols(self) -> int:
        return 1

    def do_start_time(self) -> float:
        return 0.0

    def do_end_time(self) -> float:
        return float(self._s.t[-1])

    def Clone(self) -> Reconstructed:
        return Reconstructed(self._s, self._kind)


@dataclasses.dataclass
class Move:
    index: int
    plant: object
    limits: JointLimits
    cup: CupFrame
    motions: OnlineMotions
    path: object
    grasp: object
    trajectory: object
    duration: float


def planned_moves(n: int, seed: int) -> list[Move]:
    base = load_scenario(scenarios_dir() / "random_transport_paper.yaml")
    assert base.random_transport is not None
    name = base.random_transport.object
    moves = []
    for index, (X_start, X_goal) in enumerate(sample_transports(base, n, seed)):
        trial = transport_scenario(base, name, X_start, X_goal)
        motions = OnlineMotions(trial, seed=seed + index, optimize=False)
        try:
            move = move_from_the_cup(motions, trial.objects[0], X_start)
        except PlanningError as error:
            print(f"transport {index}: not planned ({error})")
            continue
        assert move.grasp is not None and move.retimed is not None
        plant = make_arm_plant(trial)
        moves.append(
            Move(
                index,
                plant,
                JointLimits.from_plant(plant, trial.robot),
                CupFrame.of(plant, trial.robot.cup_frame),
                motions,
                move.planned.path,
                move.grasp,
                move.retimed.trajectory,
                move.retimed.duration,
            )  # fmt: skip
        )
    return moves


def grasp_margin(move: Move, trajectory: Trajectory) -> float:
    check = check_trajectory(
        move.plant, trajectory, move.limits, move.grasp, rate_hz=RATE_HZ, cup=move.cup
    )
    return check.margins[Margin.GRASP].value


def deviation(trajectory: Trajectory, reconstructed: Reconstructed) -> float:
    times = np.append(np.arange(0.0, reconstructed.end_time(), 1.0 / RATE_HZ),
                      reconstructed.end_time())  # fmt: skip
    q = trajectory.sample(times, order=0)[0]
    return float(np.abs(reconstructed.sample(times)[0] - q).max())


def study(moves: list[Move], label: str, fraction: float) -> None:
    """One table row per (interpolation, period): worst over the MOVEs."""
    own = []
    worst: dict[tuple[str, float], list[tuple[float, float]]] = {}
    for move in moves:
        trajectory = move.trajectory
        if fraction > 0.0:
            shrunk = move.grasp.with_margin(fraction)
            trajectory = retime(
                move.plant, move.path, move.limits, shrunk, cup=move.cup,
                gridpoints=move.motions._gridpoints,
            ).trajectory  # fmt: skip
        own.append((grasp_margin(move, trajectory), trajectory.duration))
        for period in PERIODS:
            samples = sample_on_grid(trajectory, period, "study")
            for kind in KINDS:
                motion = Reconstructed(samples, kind)
                worst.setdefault((kind, period), []).append(
                    (grasp_margin(move, motion), deviation(trajectory, motion))
                )
    margins = [m for m, _ in own]
    durations = [d for _, d in own]
    print(
        f"\n{label}: {len(moves)} MOVEs, median duration {np.median(durations):.3f} s;"
        f" retimed trajectory's own worst grasp margin {min(margins):+.2e}"
    )
    print("| interpolation | period (ms) | worst grasp margin | median of MOVEs' "
          "worst | MOVEs outside | largest position deviation (mrad) |")  # fmt: skip
    print("|---|---|---|---|---|---|")
    for (kind, period), rows in worst.items():
        values = np.array([m for m, _ in rows])
        dev = max(d for _, d in rows)
        print(
            f"| {kind} | {1e3 * period:g} | {values.min():+.4f} | "
            f"{np.median(values):+.4f} | {(values < -1e-3).sum()}/{len(values)} | "
            f"{1e3 * dev:.4f} |"
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=6)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--margins", type=float, nargs="*", default=[])
    args = parser.parse_args()
    moves = planned_moves(args.n, args.seed)
    study(moves, "no margin (planning.grasp_margin: 0)", 0.0)
    for fraction in args.margins:
        study(moves, f"planning.grasp_margin: {fraction:g}", fraction)


if __name__ == "__main__":
    main()
