"""Two-cup MOVEs retimed under each load-sharing model, checked and simulated.

For chosen transports of ``rt-drake experiment transport --scenario
scenarios/carton_two_cups.yaml --n 20 --seed 0`` (same samples and seeds),
this retimes the MOVE under the tool's set for ``load_sharing`` ``any``
(the Minkowski sum: any split of the load between the cups) and
``elastic`` (the rims as equal springs), and for each:

- checks it at 1 kHz with :func:`rt_drake.check_trajectory` against its own
  set (the retime's contract; excess at most 1e-3);
- asks the independent spring LP (:func:`rt_drake.contact.shared_load_residual`)
  for the largest residual of the planned wrenches at 100 Hz (0: the springs
  hold every wrench the MOVE asks for);
- plays it in the cycle's physics and reports the carton's slip on the tool.

    python tools/check_two_cup_transports.py --index 8 9 4 0
"""

from __future__ import annotations

import argparse
import dataclasses

import numpy as np

from rt_drake import CupFrame, JointLimits, check_trajectory, load_scenario
from rt_drake.contact import shared_load_residual
from rt_drake.dynamics.newton_euler import reference_object_wrench
from rt_drake.experiments._rollout import (
    rollout_scenario,
    simulate_move,
)
from rt_drake.experiments._transport_experiment import (
    move_from_the_cup,
    transport_scenario,
)
from rt_drake.model.plant import make_arm_plant
from rt_drake.model.resources import scenarios_dir
from rt_drake.planning import sample_transports
from rt_drake.retiming import Margin
from rt_drake.simulation import OnlineMotions


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--index", type=int, nargs="+", default=[8, 9, 4, 0])
    parser.add_argument("--n", type=int, default=20)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    base = load_scenario(scenarios_dir() / "carton_two_cups.yaml")
    assert base.tool is not None
    transports = sample_transports(base, args.n, args.seed)
    name = base.objects[0].name
    tool = base.tool_parameters()
    print(
        "transport  sharing  rows   duration (s)  own-set excess  spring LP residual"
        "  slip (mm, deg)"
    )
    for index in args.index:
        X_start, X_goal = transports[index]
        for sharing in ("any", "elastic"):
            scenario = dataclasses.replace(
                base, tool=dataclasses.replace(base.tool, load_sharing=sharing)
            )
            trial = transport_scenario(scenario, name, X_start, X_goal)
            motions = OnlineMotions(trial, seed=args.seed + index, optimize=False)
            move = move_from_the_cup(motions, trial.objects[0], X_start)
            assert move.grasp is not None and move.retimed is not None
            plant = make_arm_plant(trial)
            limits = JointLimits.from_plant(plant, trial.robot)
            cup = CupFrame.of(plant, trial.robot.cup_frame)
            trajectory = move.trajectory
            check = check_trajectory(plant, trajectory, limits, move.grasp, cup=cup)
            times = np.arange(trajectory.start_time(), trajectory.end_time(), 0.01)
            q, v, vdot = (
                np.array([trajectory.EvalDerivative(t, k).ravel() for t in times])
                for k in (0, 1, 2)
            )
            wrenches = reference_object_wrench(plant, move.grasp.held, cup, q, v, vdot)
            residual = shared_load_residual(wrenches, tool).max()
            q_grasp = trajectory.value(trajectory.start_time()).ravel()
            rollout = simulate_move(
                rollout_scenario(trial, q_grasp), q_grasp, trajectory
            )
            grasp_excess = -check.margins[Margin.GRASP].value
            print(
                f"{index:9d}  {sharing:7s}  {move.grasp.F.shape[0]:5d}"
                f"  {move.retimed.duration:12.3f}  {grasp_excess:+14.1e}"
                f"  {residual:18.2e}  {1e3 * rollout.slip_translation:6.2f},"
                f" {np.degrees(rollout.slip_rotation):4.2f}",
                flush=True,
            )


if __name__ == "__main__":
    main()
