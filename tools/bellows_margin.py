"""The grasp margin from the bellows cup's stated dynamics, for a scenario's MOVEs.

    python tools/bellows_margin.py SCENARIO [--seed 1] [--trials 0 1 ...]
        [--rounds 10] [--tail-s 0] [--robust]

The planner keeps the *quasi-static* wrench ``w(t)`` of a retimed MOVE (the
held object's inertia and weight, in the tool frame T, the wrench the grasp
rows see) inside ``F w <= (1 - m) g``. On bellows cups the object rings: the
cups carry ``K d(t)``, the tool's stiffness times the held body's deflection,
driven by ``w(t)`` through the tool's modes
(:func:`rt_drake.dynamics.bellows_modes.bellows_wrench`: each mode a damped oscillator
with the natural frequency and damping ratio the cup catalogue states, as
``planning.grasp_ramp_s`` does; integrated exactly for a load linear between
samples, from rest in equilibrium; held at the MOVE's last load for
``--tail-s`` afterwards, default 0: the object is then set down). Each
change of acceleration adds to the ring of the previous one, which a single
ramp's bound (1.217, ``grasp_margin`` 0.18) does not see.

For each MOVE the dynamic load factor is

    D = max_t max_rows (F K d(t) / g) / max_t max_rows (F w(t) / g)

(the tool's rows without margin: ``SharedLoadSet``, ``load_sharing`` as
the scenario states), so the ring stays in the grasp set if ``(1 - m) D <=
1``, i.e. ``m >= 1 - 1 / D``. Also printed per mode: ``D_k = max |q_k| /
max |q_k,static|``. The margin is the worst over the derivation set (the
MOVEs ``tools/bellows_trial.py`` plays for ``--seed`` and ``--trials``; the
MOVE from the cup, as in scenarios with ``random_transport.start_on_cup``),
iterated from the scenario's ``planning.grasp_margin``: retime with m,
recompute D, ``m <- 1 - 1 / D_max``, until m grows by less than 0.005. A
slower MOVE rings less, so ``1 - 1 / D_max(m)`` falls as m grows; if a
round's m is past the fixed point ``m = 1 - 1 / D_max(m)`` (it asks for
less) or the grasp cannot take it at rest, the next rounds bisect between
the last m that asked for more and that one, to a bracket 0.005 wide, and
print its upper end. Each round prints; the paths are planned once, at
margin 0, and retimed at each m. ``--margins`` only evaluates D at the
margins given.

``--robust``: the MOVEs of ``experiment transport --robust`` instead (the
nominal object's path from APPROACH and REACH, retimed for every object of
the object's uncertainty set, the planner's rows of that set, with its
peel rows if the cup states them). The true objects that experiment plays
are the set's hardest corners (heaviest, largest moments, the centre of
mass at one of its 8 corners: ``hardest_corner``); D is the largest over
those 8, each rung by its own wrench and inertia and measured on the set's
rows: ``D = max_j max_t max_rows (F K d_j / g) / max_t max_rows (F w_j / g)``.
"""

from __future__ import annotations

import argparse
import dataclasses
import itertools

import numpy as np
from _bellows_common import trial_move
from pydrake.math import RigidTransform, RotationMatrix

from rt_drake.contact import LoadSharing, stiffness_shared_set
from rt_drake.contact.load_sharing import SharedLoadSet
from rt_drake.dynamics.bellows_modes import (
    bellows_wrench,
    held_inertia,
    modal_damping_ratios,
    tool_damping,
    tool_stiffness,
)
from rt_drake.dynamics.wrench import object_wrench
from rt_drake.experiments._transport_experiment import transport_inputs
from rt_drake.model.cup_physics import load_bellows_cup
from rt_drake.model.resources import resolve_scenario_path
from rt_drake.planning import sample_transports
from rt_drake.retiming import RetimeError
from rt_drake.simulation.move_grasp import held_object
from rt_drake.uncertainty.object_samples import ObjectInertia, perturbed

STEP_S = 0.002  # s, the load's sampling
GROWTH = 0.005  # stop when m grows by less


def main() -> None:
    """Print the modes, D per MOVE per round, and m."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenario")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--trials", type=int, nargs="+", default=list(range(20)))
    parser.add_argument("--rounds", type=int, default=10)
    parser.add_argument("--tail-s", type=float, default=0.0)
    parser.add_argument(
        "--robust", action="store_true",
        help="the robust experiment's MOVEs, rung by the set's hardest corners",
    )  # fmt: skip
    parser.add_argument(
        "--margins", type=float, nargs="*", default=[],
        help="only evaluate D at these margins (no iteration)",
    )  # fmt: skip
    args = parser.parse_args()
    path = resolve_scenario_path(args.scenario)
    scenario, name = transport_inputs(path, max(args.trials) + 1, 1, None)
    scenario = scenario.with_cup_physics("bellows")
    cup = load_bellows_cup(scenario.cup_physics.cup)
    tool = scenario.tool_parameters()
    X_TCs = [RigidTransform(RotationMatrix(c.R_TC), c.p_TC) for c in tool.cups]
    K, C = tool_stiffness(cup, X_TCs), tool_damping(cup, X_TCs)
    sharing = scenario.tool.load_sharing if scenario.tool is not None else "elastic"
    shared = Rows.of(scenario_rows(tool, sharing))
    pairs = sample_transports(scenario, max(args.trials) + 1, args.seed)
    jerk = bool(scenario.robot.jerk_limits)
    m0 = scenario.planning.grasp_margin
    # Plan at margin 0, so that grasp_for gives the tool's rows unshrunk.
    scenario = dataclasses.replace(
        scenario, planning=dataclasses.replace(scenario.planning, grasp_margin=0.0)
    )
    moves = []
    for i in args.trials:
        X_start, X_goal = pairs[i]
        try:
            trial = trial_move(
                scenario, name, X_start, X_goal, args.seed, i, jerk,
                robust=not args.robust,
            )  # fmt: skip
        except Exception as error:  # noqa: BLE001 (a study: report and go on)
            print(f"trial {i}: no MOVE: {type(error).__name__}", flush=True)
            continue
        motions, obj, move = trial.motions, trial.obj, trial.move
        plant, cup_frame = motions._plant, motions._cup  # noqa: SLF001
        context = plant.CreateDefaultContext()
        plant.SetPositions(context, trial.q_grasp)
        X_OC = X_start.inverse() @ cup_frame.frame.CalcPoseInWorld(context)
        unmargined = motions.grasp_for(obj, X_OC, robust=args.robust)
        if args.robust:
            helds = hardest_corners(obj, X_OC)
            rows_of = Rows(unmargined.F, unmargined.g)
        else:
            helds, rows_of = [held_object(obj, X_OC)], shared
        moves.append((i, motions, move.planned.path, helds, unmargined, rows_of))
        if len(moves) == 1:
            held = helds[0]
            M = held_inertia(held, cup, X_TCs)
            omega, zeta, _ = modal_damping_ratios(K, C, M)
            print(
                "modes (period ms, damping ratio): "
                + ", ".join(
                    f"{2e3 * np.pi / w:.0f} {z:.3f}"
                    for w, z in zip(omega, zeta, strict=True)
                ),
                flush=True,
            )
    context = (moves, cup, X_TCs, K, C, args.tail_s)
    if args.margins:
        for m in args.margins:
            evaluate(context, m, "margin")
        return
    m, lo, hi = m0, m0, None
    for round_ in range(1, args.rounds + 1):
        worst = evaluate(context, m, f"round {round_}")
        wanted = None if worst is None else 1.0 - 1.0 / worst
        if wanted is not None and hi is None and wanted - m < GROWTH:
            print(
                f"converged after {round_} round(s): grasp_margin: {max(m, wanted):.3f}"
            )
            return
        # Above the fixed point m = 1 - 1/D(m) (or infeasible): bisect below it.
        if wanted is None or wanted < m:
            hi = m
        else:
            lo = m
        if hi is not None and hi - lo < GROWTH:
            print(f"bracketed after {round_} round(s): grasp_margin: {hi:.3f}")
            return
        m = wanted if hi is None else 0.5 * (lo + hi)
    print(f"not converged after {args.rounds} rounds: [{lo:.3f}, {hi}]")


def evaluate(context, m: float, label: str) -> float | None:
    """D_max over the MOVEs retimed with margin m (None: m infeasible); prints."""
    moves, cup, X_TCs, K, C, tail_s = context
    worst, durations = 1.0, []
    for i, motions, geometric, helds, grasp, shared in moves:
        try:
            retimed = motions.retime_path(geometric, grasp.with_margin(m))
        except RetimeError as error:
            message = " ".join(str(error).split())[:120]
            print(f"{label} m {m:.3f} trial {i}: {message}", flush=True)
            return None
        ringing = []  # per object: (D, static rows, t at the peak, per mode)
        states = move_states(retimed.trajectory, tail_s)
        for held in helds:
            t, w = move_load(motions, states, held)
            M = held_inertia(held, cup, X_TCs)
            dynamic = bellows_wrench(t, w, K, C, M)
            static_rows = rows(shared, w).max()
            ring = rows(shared, dynamic)
            per_mode = modal_factors(w, dynamic, K, C, M)
            ringing.append(
                (ring.max() / static_rows, static_rows, t[ring.argmax()], per_mode)
            )
        j = int(np.argmax([r[0] for r in ringing]))
        D, static_rows, t_peak, per_mode = ringing[j]
        worst = max(worst, D)
        durations.append(retimed.duration)
        which = f" (object {j} of {len(helds)})" if len(helds) > 1 else ""
        print(
            f"{label} m {m:.3f} trial {i}: MOVE {retimed.duration:.3f} s, "
            f"rows static {static_rows:.3f} dynamic {static_rows * D:.3f}, "
            f"D {D:.3f} (at {t_peak:.3f} s){which}; per mode "
            + " ".join(f"{d:.2f}" for d in per_mode),
            flush=True,
        )
    print(
        f"{label}: m {m:.3f}, D_max {worst:.3f}, 1 - 1/D_max "
        f"{1.0 - 1.0 / worst:.3f}, MOVE median {np.median(durations):.3f} s",
        flush=True,
    )
    return worst


def move_states(trajectory, tail_s: float):
    """``(t, q, v, vdot, n_tail)`` along the MOVE (2 ms), then ``tail_s`` at rest."""
    h = 1e-3
    end = trajectory.end_time()
    n = int(np.ceil(end / STEP_S))
    ts = np.linspace(0.0, end, n + 1)
    step = end / n

    def q_at(t: float) -> np.ndarray:
        return np.asarray(trajectory.value(min(max(t, 0.0), end))).ravel()

    Q = np.array([q_at(t) for t in ts])
    V = np.array([(q_at(t + h) - q_at(t - h)) / (2 * h) for t in ts])
    A = np.array([(q_at(t + h) - 2 * q_at(t) + q_at(t - h)) / h**2 for t in ts])
    V[[0, -1]] = 0.0
    A[[0, -1]] = 0.0
    tail = step * np.arange(1, int(np.ceil(tail_s / step)) + 1)
    return np.concatenate([ts, end + tail]), Q, V, A, tail.size


def move_load(motions, states, held):
    """``(t, w)``: the object's wrench (N, 6, in T) along the MOVE, then held."""
    t, Q, V, A, n_tail = states
    w = object_wrench(motions._plant, held, Q, V, A, cup=motions._cup)  # noqa: SLF001
    return t, np.vstack([w, np.repeat(w[-1:], n_tail, 0)])


@dataclasses.dataclass(frozen=True)
class Rows:
    """A grasp set's rows ``F w <= g`` (w in T: N m, N), without margin."""

    F: np.ndarray
    g: np.ndarray

    @classmethod
    def of(cls, shared: SharedLoadSet) -> Rows:
        """The tool's set (``load_sharing`` as the scenario states)."""
        return cls(shared.F, shared.g)


def scenario_rows(tool, sharing: str) -> SharedLoadSet:
    """The tool's set under ``sharing``, the scenario's ``tool.load_sharing``.

    ``stiffness``: every cup's share ``S_i w`` in its own rim set
    (:func:`rt_drake.contact.stiffness_shared_set`); otherwise the elastic
    split (``SharedLoadSet.of``).
    """
    if LoadSharing(sharing) is LoadSharing.STIFFNESS:
        return stiffness_shared_set(tool)
    return SharedLoadSet.of(tool)


def rows(shared: Rows, w: np.ndarray) -> np.ndarray:
    """``max_rows F w / g`` at each sample (the set without margin)."""
    return ((w @ shared.F.T) / shared.g).max(axis=1)


def hardest_corners(obj, X_OC: RigidTransform) -> list:
    """The set's 8 hardest corners held at X_OC (mass, moments at the top).

    As ``hardest_corner`` draws them: the centre of mass at each of its
    box's 8 corners (along O's axes).
    """
    nominal = ObjectInertia.of_model(obj)
    return [
        perturbed(nominal, obj.uncertainty, 1.0, np.array(signs), np.ones(3)).held(X_OC)
        for signs in itertools.product((-1.0, 1.0), repeat=3)
    ]


def modal_factors(w, dynamic, K, C, M) -> np.ndarray:
    """``max |q_k| / max |q_k,static|`` per mode (slowest first)."""
    _, _, V = modal_damping_ratios(K, C, M)
    q_static = w @ V
    q = np.linalg.solve(M @ V, dynamic.T).T  # K d = M V diag(w^2) q
    return np.abs(q).max(axis=0) / np.abs(q_static).max(axis=0)


if __name__ == "__main__":
    main()
