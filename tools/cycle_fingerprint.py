"""Record the motions a cycle plays, or compare them with a record, bit for bit.

Run ``python tools/cycle_fingerprint.py record out.npz`` on one commit,
then ``python tools/cycle_fingerprint.py compare out.npz`` on another: a
change meant to move code without changing behaviour must leave every
motion equal to the bit.

The motions are those the sequencer asks for, in its order and with its
arguments, without the simulation: per object, the pick (from home, else
from the last place with a retreat) and the MOVE from the pick's end
(``OnlineMotions`` as ``rt-drake run`` builds it: the scenario's jerk
limits, seed 0). Recorded per motion: q, q' and q'' sampled every
millisecond, its duration, its parts' ends, whether it is staged, and its
valve lead ``release_s``. Scenarios: the default ``stack_four_objects``
and ``stack_four_objects_vacuum_sensor`` (``--scenarios`` for others).
"""

from __future__ import annotations

import argparse
import sys

import numpy as np

from rt_drake.model.resources import scenarios_dir
from rt_drake.model.scenario import load_scenario
from rt_drake.simulation import OnlineMotions

SCENARIOS = ("stack_four_objects", "stack_four_objects_vacuum_sensor")
#: s, sampling period.
PERIOD = 1e-3


def cycle_motions(name: str) -> dict[str, np.ndarray]:
    """Arrays describing every motion of the cycle of scenario ``name``."""
    scenario = load_scenario(scenarios_dir() / f"{name}.yaml")
    motions = OnlineMotions(scenario, jerk_limits=True)
    q = motions.q_home
    out: dict[str, np.ndarray] = {}
    for index, obj in enumerate(scenario.objects):
        pick = motions.pick(q, obj, retreat=index > 0)
        move = motions.move(pick.q_end, obj, pick)
        for kind, motion in (("pick", pick), ("move", move)):
            key = f"{name}/{obj.name}/{kind}"
            trajectory = motion.trajectory
            times = np.arange(0.0, trajectory.end_time(), PERIOD)
            for order in range(3):
                out[f"{key}/d{order}"] = np.array(
                    [trajectory.EvalDerivative(t, order).ravel() for t in times]
                )
            out[f"{key}/scalars"] = np.array(
                [
                    motion.duration,
                    motion.release_s,
                    float(getattr(motion, "staged", False)),
                    *(part.end_s for part in motion.parts),
                ]
            )
        q = move.q_end
    return out


def main() -> int:
    """Record or compare; exit 1 on any difference."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("mode", choices=["record", "compare"])
    parser.add_argument("file")
    parser.add_argument("--scenarios", nargs="+", default=list(SCENARIOS))
    args = parser.parse_args()
    got: dict[str, np.ndarray] = {}
    for name in args.scenarios:
        got.update(cycle_motions(name))
    if args.mode == "record":
        np.savez_compressed(args.file, **got)
        print(f"recorded {len(got)} arrays in {args.file}")
        return 0
    with np.load(args.file, allow_pickle=False) as data:
        recorded = {key: data[key] for key in data.files}
    differ = sorted(
        key
        for key in recorded.keys() | got.keys()
        if key not in recorded
        or key not in got
        or recorded[key].shape != got[key].shape
        or not np.array_equal(recorded[key], got[key])
    )
    for key in differ:
        print(f"differs: {key}")
    print(f"{len(recorded)} arrays compared, {len(differ)} differ")
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
