"""Each bellows lip's load along a rollout, against the planner's grasp rows.

    python tools/bellows_lip_loads.py SCENARIO [--trial 0] [--seed 0]
        [--still] [--times T ...] [--relaxed]

Plays trial ``--trial`` of ``experiment transport`` (as
``tools/bellows_trial.py``: same sampling, grasp, jerk limits, ramp and
margin) under the bellows cup, or with ``--still`` the arm held at the grasp
for 1.6 s (the object starts held, as ``experiment transport``'s rollouts
start it; ``--relaxed``: on relaxed bellows, as before session 6), and
records every millisecond, per lip L_i: the contact force
and moment the object puts on the lip (Drake's contact results, in L_i, at
its origin), the bushing's deflection X_CiLi, the object's pose on the lip
X_LiO and the seal.

``--still`` prints the statics, averaged over the last 0.5 s (two axial
periods), against the closed forms for the object hanging from n equal
cups on a vertical tool: each bushing carries ``(m / n + m_lip) g``, so
stretches by ``(m / n + m_lip) g / k_axial``; each lip is pressed by ``P A
- m g / n``; no shear, tilt or lateral deflection.

Otherwise, at each of ``--times`` (s after the MOVE starts) it prints:

- per lip: the slip on it since the MOVE started (mm), the lip's normal
  load N_i and shear (N);
- ``rows``: the largest ``F w / g`` of the planner's tool set (the
  scenario's ``tool``, elastic load sharing, no margin) for the wrench w the
  lips and the vacuum put on the object (about and in the tool frame T);
  the retimer kept the planned wrench within ``1 - grasp_margin``;
- ``util_i``: cup i's share of its own rim points' friction in the
  planner's model: the smallest lambda with ``t_i in lambda sum_j n_j Q_j``
  (j over cup i's rim points, n_j the planner's spring split of w, Q_j the
  friction polygon; an LP), t_i = (tau_z, f_x, f_y) cup i carries (about
  T's origin): as simulated (``sim``), and as the bellows' stiffness
  splits the total (``split``): equal lateral springs k at the cups'
  positions p_i and torsion k_r each, so one rotation r_z and one shift d
  of the object on the tool: ``f_i = F / n + k r_z z x p_i``, ``r_z =
  tau_z / (n k_r + k sum |p_i|^2)`` (cups placed about T's origin).

And for the MOVE as planned (the rigid wrench the retimer checks, from the
trajectory by finite differences): the largest ``rows`` and the largest
``util_i`` under the stiffness split.
"""

from __future__ import annotations

import argparse
import dataclasses

import numpy as np
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import EventStatus
from pydrake.trajectories import PiecewisePolynomial
from scipy.optimize import linprog

from rt_drake.contact.load_sharing import RimSprings, SharedLoadSet, rim_springs
from rt_drake.dynamics.wrench import object_wrench
from rt_drake.experiments._rollout import Replay, rollout_scenario
from rt_drake.experiments._transport_experiment import (
    move_from_the_cup,
    transport_inputs,
    transport_scenario,
)
from rt_drake.model.cup_physics import load_bellows_cup
from rt_drake.model.object_model import OBJECT_BODY
from rt_drake.model.plant import home_configuration
from rt_drake.model.resources import resolve_scenario_path
from rt_drake.planning import sample_transports
from rt_drake.simulation import OnlineMotions
from rt_drake.simulation._cycle_runner import build_cycle, hold_at_start
from rt_drake.simulation.move_grasp import held_object

STILL_S = 1.6  # s, the arm held still
SETTLED_S = 0.5  # s, the statics' averaging window at the end


def cup_utilisation(
    springs: RimSprings, n_cups: int, cup: int, n: np.ndarray, t: np.ndarray
) -> float:
    """Smallest lambda with ``t in lambda sum_j n_j Q_j`` over ``cup``'s points.

    The tool's cups are equal, so cup i owns rim points i m .. (i + 1) m - 1.
    """
    per_cup = len(springs.positions) // n_cups
    points = range(cup * per_cup, (cup + 1) * per_cup)
    columns, owner = [], []
    for j in points:
        for vertex in springs.polygons[j] * max(n[j], 0.0):
            columns.append(vertex)
            owner.append(j - cup * per_cup)
    A = np.array(columns).T
    k = A.shape[1]
    A_eq = np.zeros((3 + per_cup, k + 1))
    A_eq[:3, :k] = A
    A_eq[3 + np.array(owner), np.arange(k)] = 1.0
    A_eq[3:, k] = -1.0
    b_eq = np.concatenate([t, np.zeros(per_cup)])
    cost = np.zeros(k + 1)
    cost[k] = 1.0
    result = linprog(cost, A_eq=A_eq, b_eq=b_eq, bounds=(0, None), method="highs")
    return float(result.x[k]) if result.status == 0 else np.inf


def stiffness_split(w: np.ndarray, p: np.ndarray, k: float, k_r: float):
    """Each cup's (tau_z, f_x, f_y) about T under the bellows' stiffness split."""
    r_z = w[2] / (len(p) * k_r + k * float((p**2).sum()))
    shares = []
    for x, y in p:
        f = w[3:5] / len(p) + k * r_z * np.array([-y, x])
        shares.append(np.array([k_r * r_z + x * f[1] - y * f[0], f[0], f[1]]))
    return shares


def main() -> None:
    """Play the trial and print the loads."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenario")
    parser.add_argument("--trial", type=int, default=0)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--still", action="store_true")
    parser.add_argument("--times", type=float, nargs="*", default=[0.1])
    parser.add_argument(
        "--relaxed",
        action="store_true",
        help="start the object on relaxed bellows (not held at its sag)",
    )
    args = parser.parse_args()
    scenario, name = transport_inputs(
        resolve_scenario_path(args.scenario), args.trial + 1, 1, None
    )
    scenario = scenario.with_cup_physics("bellows")
    bellows = load_bellows_cup(scenario.cup_physics.cup)
    X_start, X_goal = sample_transports(scenario, args.trial + 1, args.seed)[args.trial]
    planned = transport_scenario(scenario, name, X_start, X_goal)
    motions = OnlineMotions(
        planned,
        grasp_constraint=True,
        seed=args.seed + args.trial,
        optimize=False,
        jerk_limits=bool(scenario.robot.jerk_limits),
    )
    obj = planned.objects[0]
    move = move_from_the_cup(motions, obj, X_start)
    q_grasp = move.planned.q_start
    trajectory = move.trajectory
    if args.still:
        trajectory = PiecewisePolynomial.FirstOrderHold(
            [0.0, STILL_S], np.column_stack([q_grasp, q_grasp])
        )
    world = rollout_scenario(dataclasses.replace(planned), q_grasp)
    tool = planned.tool_parameters()
    shared, springs = SharedLoadSet.of(tool), rim_springs(tool)
    p_cups = np.array([mount.p_TC[:2] for mount in tool.cups])
    X_TC0 = RigidTransform(RotationMatrix(tool.cups[0].R_TC), tool.cups[0].p_TC)
    pulls = [bellows.suction_force] * len(tool.cups)

    transport = world.random_transport
    held = transport is not None and transport.start_on_cup and not args.relaxed
    diagram, station, sequencer = build_cycle(
        world, Replay(q_grasp, trajectory), held_at_start=held
    )
    simulator = Simulator(diagram)
    root = simulator.get_mutable_context()
    plant = station.plant
    context = plant.GetMyMutableContextFromRoot(root)
    plant.SetPositions(context, station.models.robot, home_configuration(plant, world))
    if held:
        hold_at_start(world, station, root)
    sequencer_context = sequencer.GetMyContextFromRoot(root)
    suction = station.diagram.GetSubsystemByName("suction")
    body = plant.GetBodyByName(OBJECT_BODY, station.models.objects[obj.name])
    lips = [plant.get_body(lip.body_index) for lip in station.lips]
    mounts = [plant.get_frame(lip.mount) for lip in station.lips]
    samples: list[dict] = []

    def record(root_context) -> EventStatus:
        results = plant.get_contact_results_output_port().Eval(context)
        X_WO = plant.EvalBodyPoseInWorld(context, body)
        sample = {
            "t": root_context.get_time(),
            "phase": sequencer.sequencer_state(sequencer_context).phase.value,
            "seal": suction.seal_states(suction.GetMyContextFromRoot(root_context)),
            "X_WO": X_WO,
            "lips": [],
        }
        for lip, mount in zip(lips, mounts, strict=True):
            X_WL = plant.EvalBodyPoseInWorld(context, lip)
            f_W, m_W = np.zeros(3), np.zeros(3)
            for i in range(results.num_point_pair_contacts()):
                info = results.point_pair_contact_info(i)
                pair = (info.bodyA_index(), info.bodyB_index())
                if pair == (lip.index(), body.index()):
                    f = -info.contact_force()  # on A (the lip)
                elif pair == (body.index(), lip.index()):
                    f = info.contact_force()
                else:
                    continue
                f_W += f
                m_W += np.cross(info.contact_point() - X_WL.translation(), f)
            R_LW = X_WL.rotation().inverse().matrix()
            sample["lips"].append(
                {
                    "X_WL": X_WL,
                    "X_WC": mount.CalcPoseInWorld(context),
                    "f_L": R_LW @ f_W,
                    "m_L": R_LW @ m_W,
                }
            )
        samples.append(sample)
        return EventStatus.Succeeded()

    simulator.set_monitor(record)
    simulator.Initialize()
    t_end = STILL_S + 0.4 if args.still else trajectory.end_time() + 0.5
    simulator.AdvanceTo(t_end)
    moving = [s for s in samples if s["phase"] == "move"]
    t_move = moving[0]["t"]

    if args.still:
        _print_statics(samples, t_move + STILL_S, obj, body.default_mass(), bellows)
        return
    n_cups = len(tool.cups)
    print(f"MOVE {trajectory.end_time():.3f} s from t = {t_move:.3f} s")
    first = moving[0]
    X_LO_0 = [lip["X_WL"].inverse() @ first["X_WO"] for lip in first["lips"]]
    for dt in args.times:
        s = min(samples, key=lambda q: abs(q["t"] - t_move - dt))
        X_WT = s["lips"][0]["X_WC"] @ X_TC0.inverse()
        w, sims, line = np.zeros(6), [], []
        for i, lip in enumerate(s["lips"]):
            X_TL = X_WT.inverse() @ lip["X_WL"]
            R_TL, p_TL = X_TL.rotation().matrix(), X_TL.translation()
            live = s["seal"][i].name in ("DRAWING", "SEALED")
            f_T = -R_TL @ lip["f_L"] + R_TL @ [0, 0, -pulls[i] if live else 0.0]
            tau_T = -R_TL @ lip["m_L"] + np.cross(p_TL, f_T)
            w += np.concatenate([tau_T, f_T])
            sims.append(np.array([tau_T[2], f_T[0], f_T[1]]))
            slip = X_LO_0[i].inverse() @ (lip["X_WL"].inverse() @ s["X_WO"])
            line.append(
                f"cup {i}: slip {1e3 * np.linalg.norm(slip.translation()):.2f} mm, "
                f"N {-lip['f_L'][2]:.2f} N, shear {np.hypot(*lip['f_L'][:2]):.2f} N"
            )
        n = springs.normal_forces(w)
        split = stiffness_split(
            w, p_cups, bellows.lateral_stiffness, bellows.torsion_stiffness
        )
        utils = [
            f"util_{i} sim {cup_utilisation(springs, n_cups, i, n, sims[i]):.2f} "
            f"split {cup_utilisation(springs, n_cups, i, n, split[i]):.2f}"
            for i in range(n_cups)
        ]
        print(
            f"t + {s['t'] - t_move:.3f} s: seals {[x.name for x in s['seal']]}; "
            + "; ".join(line)
            + f"; rows {float(((shared.F @ w) / shared.g).max()):.3f}; "
            + "; ".join(utils)
        )
    # The MOVE as planned: the rigid wrench the retimer checks.
    plant_arm = motions._plant  # noqa: SLF001 (a study reads the planner's plant)
    cup_frame = motions._cup  # noqa: SLF001
    arm_context = plant_arm.CreateDefaultContext()
    plant_arm.SetPositions(arm_context, q_grasp)
    X_OC = X_start.inverse() @ cup_frame.frame.CalcPoseInWorld(arm_context)
    held = held_object(obj, X_OC)
    h = 1e-3
    ts = np.arange(h, trajectory.end_time() - h, 0.005)

    def q_at(t: float) -> np.ndarray:
        return np.asarray(trajectory.value(t)).ravel()

    Q = np.array([q_at(t) for t in ts])
    V = np.array([(q_at(t + h) - q_at(t - h)) / (2 * h) for t in ts])
    A = np.array([(q_at(t + h) - 2 * q_at(t) + q_at(t - h)) / h**2 for t in ts])
    W = object_wrench(plant_arm, held, Q, V, A, cup=cup_frame)
    rows = ((W @ shared.F.T) / shared.g).max(axis=1)
    utils = np.array(
        [
            [
                cup_utilisation(springs, n_cups, i, springs.normal_forces(w), t_i)
                for i, t_i in enumerate(
                    stiffness_split(
                        w, p_cups, bellows.lateral_stiffness, bellows.torsion_stiffness
                    )
                )
            ]
            for w in W
        ]
    )
    print(
        f"planned: rows at most {rows.max():.3f} (t = {ts[rows.argmax()]:.3f} s); "
        + "; ".join(
            f"util_{i} split at most {utils[:, i].max():.3f} "
            f"(t = {ts[utils[:, i].argmax()]:.3f} s)"
            for i in range(n_cups)
        )
    )


def _print_statics(samples, t_stop, obj, mass, bellows) -> None:
    """Average the last SETTLED_S s of the still arm; print with closed forms."""
    window = [s for s in samples if t_stop - SETTLED_S <= s["t"] <= t_stop]
    n = len(window[0]["lips"])
    g = 9.81
    stretch = (mass / n + bellows.lip_mass) * g / bellows.axial_stiffness
    pressed = bellows.suction_force - mass * g / n
    print(
        f"closed forms ({obj.name}, {mass} kg on {n} cups): bushing stretch "
        f"{1e3 * stretch:.2f} mm, lip normal load {pressed:.2f} N, no shear, no tilt"
    )
    for i in range(n):
        X_CL = [(s["lips"][i]["X_WC"].inverse() @ s["lips"][i]["X_WL"]) for s in window]
        p = np.mean([X.translation() for X in X_CL], axis=0)
        tilt = np.mean([np.degrees(X.rotation().ToAngleAxis().angle()) for X in X_CL])
        f = np.mean([s["lips"][i]["f_L"] for s in window], axis=0)
        X_LO = window[-1]["lips"][i]["X_WL"].inverse() @ window[-1]["X_WO"]
        print(
            f"cup {i}: stretch {1e3 * p[2]:.2f} mm, lateral "
            f"{1e3 * np.hypot(p[0], p[1]):.3f} mm, tilt {tilt:.3f} deg; lip normal "
            f"{-f[2]:.2f} N, shear {np.hypot(f[0], f[1]):.3f} N; object on the lip "
            f"p_LO {np.round(1e3 * X_LO.translation(), 2)} mm"
        )


if __name__ == "__main__":
    main()
