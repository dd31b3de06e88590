"""Record what ``retime`` computes on many paths, or compare with a record.

Run: ``python tools/retime_fingerprint.py record out.npz`` on one
commit, then ``python tools/retime_fingerprint.py compare out.npz`` on
another: a change meant only to make ``retime`` faster must leave every
result equal (to ``--rtol``, default 1e-9 relative).

Cases: the five paths of ``bench_retime.py`` (notebook); the three paths of
``tests/retiming/test_solve.py`` with each of its three objects, without an
object, with the model's torque limits, with tight ones and on coarse grids
(refinements), as a Drake ``PiecewisePolynomial``, a ``CompositeTrajectory``
(evaluated, not cubic), a ``BsplineTrajectory`` and with an explicit grid;
30 seeded random paths (as in the contract test) with a random object and
without. Recorded per case: the duration, grid, s'(s), s'', margins, grasp
rows, repairs and refinements, or the error's type and message.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np
from pydrake.math import BsplineBasis
from pydrake.trajectories import (
    BsplineTrajectory,
    CompositeTrajectory,
    PiecewisePolynomial,
)

from rt_drake.model.held import held_object_of
from rt_drake.model.plant import make_arm_plant
from rt_drake.model.resources import scenarios_dir
from rt_drake.model.scenario import load_scenario
from rt_drake.retiming import GraspConstraint, JointLimits, RetimeError, retime

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
from bench_retime import HOME, move_paths  # noqa: E402

PATHS = {
    "swing": [
        HOME,
        HOME + [0.2, -0.25, -0.3, 0, 0.35, 0.2],
        HOME + [1.3, -0.25, -0.3, 0, 0.35, 0.9],
        HOME + [1.5, 0.05, 0.1, 0, -0.15, 1.1],
    ],
    "back": [
        HOME,
        HOME + [-0.4, 0.1, -0.2, 0.0, 0.1, -0.5],
        HOME + [-1.2, -0.1, 0.2, 0, -0.1, -0.8],
    ],
    "wrist": [
        HOME,
        HOME + [0.3, 0.1, -0.1, 0.3, 0.0, 1.0],
        HOME + [0.6, -0.1, 0.2, -0.2, -0.1, 2.2],
    ],
}
OBJECTS = ["notebook", "carton_box", "whetstone_box"]
FIELDS = ("duration", "gridpoints", "sd", "sdd", "margin", "counts")


def cases() -> Iterator[tuple[str, Callable[[], Any]]]:
    """(name, thunk returning a RetimeResult) of every case."""
    scenario = load_scenario(scenarios_dir() / "stack_four_objects.yaml")
    plant = make_arm_plant(scenario)
    context = plant.CreateDefaultContext()
    limits = JointLimits.from_plant(plant, scenario.robot)
    torque = JointLimits.from_plant(plant, scenario.robot, torque=True)
    grasps = {
        name: GraspConstraint.for_cup(
            held_object_of(scenario.object(name)), scenario.cup
        )
        for name in OBJECTS
    }

    def run(path: Any, lim: JointLimits, grasp: Any, grid: Any = 100) -> Any:
        return lambda: retime(plant, path, lim, grasp, grid, context=context)

    for k, path in enumerate(move_paths(5)):
        yield f"bench{k}", run(path, limits, grasps["notebook"])
    for name, waypoints in PATHS.items():
        path = np.array(waypoints)
        yield f"{name}-free", run(path, limits, None)
        for obj in OBJECTS:
            yield f"{name}-{obj}", run(path, limits, grasps[obj])
        yield f"{name}-torque", run(path, torque, grasps["carton_box"])
        for factor in (0.35, 0.3):
            tight = JointLimits(
                torque.velocity, torque.acceleration, factor * torque.torque
            )
            yield f"{name}-tight{factor}", run(path, tight, grasps["carton_box"])
        for size in (20, 30):
            yield f"{name}-coarse{size}", run(path, torque, grasps["carton_box"], size)
        yield (
            f"{name}-grid",
            run(path, limits, grasps["notebook"], np.linspace(0, 1, 57)),
        )
        times = np.linspace(0.0, 2.0, len(path))
        cubic = PiecewisePolynomial.CubicWithContinuousSecondDerivatives(
            times, path.T, np.zeros(6), np.zeros(6)
        )
        yield f"{name}-pp-cubic", run(cubic, limits, grasps["notebook"])
        yield (
            f"{name}-composite",
            run(_composite(times, path), limits, grasps["whetstone_box"]),
        )
        basis = BsplineBasis(4, 2 * len(path) + 2)
        controls = [
            row for row in np.linspace(path[0], path[-1], basis.num_basis_functions())
        ]
        yield (
            f"{name}-bspline",
            run(
                BsplineTrajectory(basis, [c[:, None] for c in controls]),
                limits,
                grasps["carton_box"],
            ),
        )
    rng = np.random.default_rng(12)
    for k in range(30):
        steps = rng.uniform(-0.5, 0.5, size=(rng.integers(1, 5), 6))
        path = np.cumsum(np.vstack([HOME, steps]), axis=0)
        obj = OBJECTS[k % 3]
        yield f"random{k}-{obj}", run(path, limits, grasps[obj])
        yield f"random{k}-free", run(path, limits, None, 60 + 7 * k)


def _composite(times: np.ndarray, path: np.ndarray) -> CompositeTrajectory:
    """A cubic path as a ``CompositeTrajectory`` (not known cubic: evaluated)."""
    pieces = [
        PiecewisePolynomial.CubicWithContinuousSecondDerivatives(
            times[k : k + 2], path[k : k + 2].T, np.zeros(6), np.zeros(6)
        )
        for k in range(len(times) - 1)
    ]
    return CompositeTrajectory(pieces)


def fingerprint(thunk: Callable[[], Any]) -> dict[str, np.ndarray]:
    """The result's arrays, or its error's type and message."""
    try:
        r = thunk()
    except RetimeError as error:
        return {"error": np.array(f"{type(error).__name__}: {error}")}
    return {
        "duration": np.array([r.duration]),
        "gridpoints": r.gridpoints,
        "sd": r.sd,
        "sdd": r.sdd,
        "margin": r.margin,
        "counts": np.array([r.grasp_rows, r.repairs, r.refinements], dtype=float),
    }


def relative_difference(field: str, old: np.ndarray, new: np.ndarray) -> float:
    """Largest ``|new - old|`` relative to ``|old|``, elementwise.

    s'' changes sign and margins reach 0: theirs is relative to the
    array's largest value (1 for margins, which are fractions).
    """
    diff = np.abs(new - old)
    if field in ("sdd", "margin"):
        scale = np.full_like(old, max(float(np.max(np.abs(old), initial=0.0)), 1.0))
    else:
        scale = np.abs(old)
    ratio = np.divide(
        diff, scale, out=np.where(diff == 0, 0.0, np.inf), where=scale > 0
    )
    return float(np.max(ratio, initial=0.0))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("mode", choices=["record", "compare"])
    parser.add_argument("file")
    parser.add_argument("--rtol", type=float, default=1e-9)
    args = parser.parse_args()
    results = {
        f"{name}/{key}": value
        for name, thunk in cases()
        for key, value in fingerprint(thunk).items()
    }
    if args.mode == "record":
        np.savez(args.file, **results)
        print(f"{len(results)} arrays recorded")
        return
    recorded = dict(np.load(args.file))
    worst, bad = 0.0, []
    for key in sorted(set(recorded) | set(results)):
        old, new = recorded.get(key), results.get(key)
        if old is None or new is None or old.shape != new.shape:
            bad.append(f"{key}: {old!r} vs {new!r}")
            continue
        if old.dtype.kind in "US":
            if str(old) != str(new):
                bad.append(f"{key}: {old} vs {new}")
            continue
        rel = relative_difference(key.split("/")[1], old, new)
        worst = max(worst, rel)
        if rel > args.rtol:
            bad.append(f"{key}: relative difference {rel:.3g}")
    names = {key.split("/")[0] for key in recorded}
    print(f"{len(names)} cases, max relative difference {worst:.3g}")
    for line in bad:
        print("DIFFERENT", line)
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
