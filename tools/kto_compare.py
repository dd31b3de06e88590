"""Where the KTO reference's MOVE paths differ from the shaped ones (issue 27).

Reads the waypoints ``tools/kto_reference.py --paths DIR`` keeps (one
``DIR/<seed>_<index>.npz`` per transport: the spline, shaped and KTO
paths, rad) and compares the shaped path P with the KTO path K, both
clamped chord-length splines (:class:`rt_drake.GeometricPath`), at equal
fractions u of their own joint-space length (rad):

- ``len``: joint-space length of each path (rad);
- ``max|dq|``: the largest ``|K_j(u) - P_j(u)|`` over joints j and u, with
  its joint and u;
- ``dz``: the cup's height difference ``z_C(K) - z_C(P)`` (m, world frame)
  at its largest over u, and where;
- ``tilt``: the largest angle (deg) of the cup axis to gravity on each;
- ``via u``: where the shaped path's free via points lie (u of its
  waypoints between the vertical end segments);
- ``ends``: the u at which each path's cup is 3 cm above the grasp and
  above the place (the vertical ends' share of the path).

With ``--surrogate``, how the search ranks the two: each transport's spline
MOVE is planned again as ``benchmarks/bench_optimize.py`` plans it (seed and
index from the file name; the spline path is checked equal to the stored
one), and both paths are scored by the search's coarse retimer as the
optimiser builds it (:class:`~rt_drake.shaping._surrogate.CoarseRetimer` on
``MoveOptimizer.search_grid``, rows from the spline path) and by the final
retime (``MoveOptimizer.retime``): ``coarse K/P`` against ``final K/P``
(below 1: the KTO path is faster), and each path's ``coarse / final``.
``--options JSON`` builds the optimiser (and so the search's grid) with
these ``MoveOptimizerOptions`` fields, e.g. ``{"search_end_points": 4}``
for each candidate's own points over its vertical ends.

    python tools/kto_compare.py out/paths/1_*.npz out/paths/11_*.npz
    python tools/kto_compare.py --surrogate out/paths/1_*.npz
    python tools/kto_compare.py --surrogate --options '{"search_end_points": 4}' \\
        out/paths/1_*.npz
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys
from pathlib import Path

import numpy as np

from rt_drake import CupFrame, GeometricPath, load_scenario, make_arm_plant
from rt_drake.model.resources import resolve_scenario_path
from rt_drake.shaping.cup_chain import CupChain

#: Samples of s per path; fractions u compared.
SAMPLES = 2001
FRACTIONS = np.linspace(0.0, 1.0, 101)
#: m: height of the vertical ends (the optimiser's vertical_height).
VERTICAL = 0.03


def at_fractions(path: GeometricPath) -> tuple[np.ndarray, float, np.ndarray]:
    """(q at FRACTIONS (101, n), length (rad), u of the path's knots)."""
    s = np.linspace(0.0, 1.0, SAMPLES)
    q = path.value(s)
    length = np.concatenate(
        [[0.0], np.cumsum(np.linalg.norm(np.diff(q, axis=0), axis=1))]
    )
    u = length / length[-1]
    resampled = np.column_stack(
        [np.interp(FRACTIONS, u, q[:, j]) for j in range(q.shape[1])]
    )
    return resampled, float(length[-1]), np.interp(path.knots, s, u)


def end_fractions(chain: CupChain, q: np.ndarray) -> tuple[float, float]:
    """u where the cup is first VERTICAL above its start and last above its end."""
    z = chain.cup_pose(q)[1][:, 2]
    up = np.flatnonzero(z - z[0] >= VERTICAL)
    down = np.flatnonzero(z - z[-1] >= VERTICAL)
    return float(FRACTIONS[up[0]]), float(FRACTIONS[down[-1]])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("files", type=Path, nargs="+")
    parser.add_argument("--scenario", default="random_transport")
    parser.add_argument("--surrogate", action="store_true")
    parser.add_argument("--options", type=json.loads, default={})
    args = parser.parse_args()
    if args.surrogate:
        surrogate(args.files, args.scenario, args.options)
        return
    scenario = load_scenario(resolve_scenario_path(args.scenario))
    plant = make_arm_plant(scenario)
    chain = CupChain(plant, CupFrame.of(plant))
    print(
        "transport  len P  len K  max|dq| joint  at u   dz max m  at u  tilt P  tilt K"
        "  via u       ends P     ends K"
    )
    for file in args.files:
        with np.load(file) as data:
            P = GeometricPath.from_waypoints(data["shaped"])
            K = GeometricPath.from_waypoints(data["kto"])
        qP, lP, uP = at_fractions(P)
        qK, lK, _ = at_fractions(K)
        dq = np.abs(qK - qP)
        i, j = np.unravel_index(int(np.argmax(dq)), dq.shape)
        dz = chain.cup_pose(qK)[1][:, 2] - chain.cup_pose(qP)[1][:, 2]
        k = int(np.argmax(np.abs(dz)))
        tP = np.degrees(chain.tilt(qP).max())
        tK = np.degrees(chain.tilt(qK).max())
        m = (len(uP) - 4) // 2  # vertical points per end: K = 2 via points
        via = " ".join(f"{v:.2f}" for v in uP[m + 1 : len(uP) - m - 1])
        eP, eK = end_fractions(chain, qP), end_fractions(chain, qK)
        print(
            f"{file.stem:>9}  {lP:5.2f}  {lK:5.2f}  {dq[i, j]:7.3f}  q{j}"
            f"  {FRACTIONS[i]:5.2f}"
            f"  {dz[k]:+8.3f}  {FRACTIONS[k]:4.2f}  {tP:6.1f}  {tK:6.1f}  {via:10s}"
            f"  {eP[0]:.2f} {eP[1]:.2f}  {eK[0]:.2f} {eK[1]:.2f}"
        )


def surrogate(files: list[Path], scenario: str, fields: dict) -> None:
    """Print the coarse and final durations of the shaped and KTO paths."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
    from bench_optimize import Setup

    from rt_drake.shaping import MoveOptimizer, MoveOptimizerOptions
    from rt_drake.shaping._surrogate import CoarseRetimer

    options = dataclasses.replace(MoveOptimizerOptions(), **fields)
    rows = []

    print("transport  coarse K/P  final K/P  coarse/final P  coarse/final K")
    setups: dict[int, tuple] = {}
    for file in files:
        seed, index = (int(v) for v in file.stem.split("_"))
        if seed not in setups:
            setup = Setup(scenario, seed)
            optimizer = MoveOptimizer(setup.plant, setup.limits, options, setup.cup)
            setups[seed] = (setup, optimizer, setup.transports(20))
        setup, optimizer, transports = setups[seed]
        move, _ = setup.spline_move(index, *transports[index])
        grasp = setup.grasp(move)
        with np.load(file) as data:
            assert np.allclose(data["spline"], move.path.waypoints, atol=1e-12)
            W = {key: np.array(data[key]) for key in ("shaped", "kto")}
        baseline = optimizer.retime(move.path, grasp)
        coarse = CoarseRetimer(
            optimizer.chain, setup.limits, grasp, optimizer.search_grid(baseline),
            ends=optimizer.end_grid(),
        )  # fmt: skip
        coarse.select_rows(move.path.waypoints[None])
        c = {key: float(coarse.durations(w[None])[0]) for key, w in W.items()}
        f = {
            key: optimizer.retime(GeometricPath.from_waypoints(w), grasp).duration
            for key, w in W.items()
        }
        row = (
            c["kto"] / c["shaped"], f["kto"] / f["shaped"],
            c["shaped"] / f["shaped"], c["kto"] / f["kto"],
        )  # fmt: skip
        rows.append(row)
        print(
            f"{file.stem:>9}  {row[0]:10.4f}  {row[1]:9.4f}  {row[2]:14.3f}"
            f"  {row[3]:14.3f}",
            flush=True,
        )
    table = np.array(rows)
    agree = int(np.sum((table[:, 0] < 1.0) == (table[:, 1] < 1.0)))
    print(
        f"medians: coarse K/P {np.median(table[:, 0]):.4f}, final K/P"
        f" {np.median(table[:, 1]):.4f}, the same ranking on {agree} / {len(table)};"
        f" coarse / final: P {np.median(table[:, 2]):.3f}"
        f" ({table[:, 2].min():.3f}-{table[:, 2].max():.3f}),"
        f" K {np.median(table[:, 3]):.3f}"
        f" ({table[:, 3].min():.3f}-{table[:, 3].max():.3f})"
    )


if __name__ == "__main__":
    main()
