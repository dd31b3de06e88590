"""Does the two-cup tool's retime keep its own contract on carton_two_cups?

In ``rt-drake experiment transport --scenario scenarios/carton_two_cups.yaml
--n 20 --seed 0`` 8 of 20 constrained MOVEs slip in simulation. This replans
chosen transports of that run (same samples and seeds), and checks each
retimed MOVE at 1 kHz with :func:`rt_drake.check_trajectory`, whose object
wrench comes from Drake's spatial accelerations (an independent route) and
is tested against the tool's exact wrench set W_T: an excess at most 1e-3
means the retime keeps its contract, so a slip comes from the gap between
W_T's contact model and the simulated contact.

    python benchmarks/check_two_cup_transports.py --index 8 9 4
"""

from __future__ import annotations

import argparse

from rt_drake import CupFrame, JointLimits, check_trajectory, load_scenario
from rt_drake.experiments.transport import move_from_the_cup, transport_scenario
from rt_drake.planning import sample_transports
from rt_drake.plant import make_arm_plant
from rt_drake.resources import scenarios_dir
from rt_drake.simulation import OnlineMotions


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--index", type=int, nargs="+", default=[8, 9, 4])
    parser.add_argument("--n", type=int, default=20)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    scenario = load_scenario(scenarios_dir() / "carton_two_cups.yaml")
    transports = sample_transports(scenario, args.n, args.seed)
    name = scenario.objects[0].name
    print("transport  duration (s)  rows  grasp excess  velocity  acceleration")
    for index in args.index:
        X_start, X_goal = transports[index]
        trial = transport_scenario(scenario, name, X_start, X_goal)
        motions = OnlineMotions(trial, seed=args.seed + index, optimize=False)
        move = move_from_the_cup(motions, trial.objects[0], X_start)
        assert move.grasp is not None and move.retimed is not None
        plant = make_arm_plant(trial)
        limits = JointLimits.from_plant(plant, trial.robot)
        cup = CupFrame.of(plant, trial.robot.cup_frame)
        excess = check_trajectory(plant, move.trajectory, limits, move.grasp, cup=cup)
        e = excess.excess
        print(
            f"{index:9d}  {move.retimed.duration:12.3f}  {move.grasp.F.shape[0]:5d}"
            f"  {e['grasp'].value:+12.1e}  {e['velocity'].value:+8.3f}"
            f"  {e['acceleration'].value:+12.3f}"
        )


if __name__ == "__main__":
    main()
