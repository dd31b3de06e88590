"""The optimiser's coarse TOPP-RA against the retimer's passes on Drake's data.

And the per-candidate grid over the vertical ends (:class:`EndGrid`): the
same TOPP-RA on each path's own grid, built here from the retimer's knots,
and, on a pair of searched MOVE paths, the same ranking as the final
retime (the independent reference), where the grid shared by all
candidates ranks them the other way.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest
from pydrake.common.schema import Transform
from pydrake.math import RigidTransform
from scipy.interpolate import CubicSpline

from rt_drake import (
    CupFrame,
    GeometricPath,
    GraspConstraint,
    JointLimits,
    load_scenario,
    make_arm_plant,
)
from rt_drake.contact import cached_wrench_polytope
from rt_drake.dynamics.wrench import path_wrench_coefficients
from rt_drake.model.held import held_object_of
from rt_drake.retiming import chord_knots
from rt_drake.retiming.passes import AffineConstraint, XBound, reachability
from rt_drake.shaping import MoveOptimizer, MoveOptimizerOptions, retime_adaptive
from rt_drake.shaping._surrogate import MAX_END_SPAN, CoarseRetimer, EndGrid
from rt_drake.shaping.cup_chain import CupChain

#: Seed 1's transport 16 of ``benchmarks/bench_optimize.py`` (random_transport):
#: the spline MOVE, the path the default search returned, the path the same
#: search returned scored by the final retime itself, and the grasp X_OC.
PAIR = Path(__file__).parent / "data" / "search_pair.npz"


def classic_toppra(plant, waypoints, limits, grasp, gridpoints):
    """TOPP-RA at the grid points only, every grasp row, Drake's kinematics.

    ``gridpoints``: a number of uniform points, or the points.
    """
    spline = CubicSpline(chord_knots(waypoints), waypoints, bc_type="clamped")
    s = (
        np.linspace(0.0, 1.0, gridpoints)
        if np.ndim(gridpoints) == 0
        else np.asarray(gridpoints, dtype=float)
    )
    q, dq, ddq = spline(s), spline(s, 1), spline(s, 2)
    n = q.shape[1]
    box = np.vstack([np.eye(n), -np.eye(n)])
    with np.errstate(divide="ignore"):
        x_cap = np.min(limits.velocity**2 / dq**2, axis=1)
    wrench = path_wrench_coefficients(plant, grasp.held, q, dq, ddq)
    constraints = [
        XBound(np.column_stack([np.zeros_like(s), np.minimum(x_cap, 1e8)])),
        AffineConstraint(
            dq, ddq, np.zeros_like(dq), box, np.tile(limits.acceleration, 2)
        ),
        AffineConstraint(*wrench, grasp.F, grasp.g),
    ]
    solution = reachability(constraints, None, s)
    if solution.x is None:
        return np.inf
    x = np.maximum(solution.x, 0.0)
    return float(np.sum(2.0 * np.diff(s) / (np.sqrt(x[:-1]) + np.sqrt(x[1:]))))


def test_coarse_retimer_is_classic_toppra_with_every_row(scenario, plant):
    """Same grid, same constraints at the grid points: the same duration."""
    chain = CupChain(plant, CupFrame.of(plant))
    polytope = cached_wrench_polytope(scenario.cup)
    grasp = GraspConstraint(held_object_of(scenario.objects[2]), polytope.F, polytope.g)
    limits = JointLimits.from_plant(plant, scenario.robot)
    q_home = np.array(scenario.robot.home)
    rng = np.random.default_rng(2)
    W = q_home + np.cumsum(rng.normal(scale=0.15, size=(3, 5, 6)), axis=1)
    surrogate = CoarseRetimer(chain, limits, grasp, 24)
    durations, exact, _ = surrogate.evaluate(W)
    assert exact.all()
    for p in range(3):
        expected = classic_toppra(plant, W[p], limits, grasp, 24)
        assert durations[p] == pytest.approx(expected, rel=1e-9)


def test_end_grid_is_classic_toppra_on_each_paths_own_grid(scenario, plant):
    """Each path's grid: E points over f times each vertical end, s between."""
    chain = CupChain(plant, CupFrame.of(plant))
    polytope = cached_wrench_polytope(scenario.cup)
    grasp = GraspConstraint(held_object_of(scenario.objects[2]), polytope.F, polytope.g)
    limits = JointLimits.from_plant(plant, scenario.robot)
    rng = np.random.default_rng(3)
    steps = rng.normal(scale=0.15, size=(3, 6, 6))
    steps[:, [1, -1]] *= 0.1  # short end segments, as a MOVE's vertical ends
    W = np.array(scenario.robot.home) + np.cumsum(steps, axis=1)
    ends = EndGrid(points=3, span=2.0, vertical_points=1)
    s = np.linspace(0.0, 1.0, 12)
    surrogate = CoarseRetimer(chain, limits, grasp, s, ends=ends)
    durations, exact, _ = surrogate.evaluate(W)
    assert exact.all()
    for p in range(3):
        knots = chord_knots(W[p])
        up, down = 2.0 * knots[1], 2.0 * (1.0 - knots[-2])
        assert max(up, down) < MAX_END_SPAN  # the cap does not bind here
        grid = np.concatenate(
            [
                [0.0, up / 3, 2 * up / 3],
                up + (1.0 - up - down) * s,
                [1.0 - 2 * down / 3, 1.0 - down / 3, 1.0],
            ]
        )
        assert len(grid) == len(s) + 2 * ends.points
        expected = classic_toppra(plant, W[p], limits, grasp, grid)
        assert durations[p] == pytest.approx(expected, rel=1e-9)


def test_end_grid_ranks_this_pair_as_the_final_retime_does(scenario_paths):
    """The final retime: the second path 3.4 % faster; the shared grid: slower."""
    scenario = load_scenario(scenario_paths["random_transport"])
    plant = make_arm_plant(scenario)
    limits = JointLimits.from_plant(plant, scenario.robot)
    with np.load(PAIR) as data:
        spline, X_OC = data["spline"], RigidTransform(data["X_OC"])
        paths = [data["searched"], data["final_searched"]]
    obj = scenario.object(scenario.random_transport.object)
    held = held_object_of(dataclasses.replace(obj, grasp=Transform(X_OC)))
    grasp = GraspConstraint.for_cup(held, scenario.cup)

    def final(waypoints: np.ndarray) -> float:
        path = GeometricPath.from_waypoints(waypoints)
        return retime_adaptive(plant, path, limits, grasp).duration

    reference = final(paths[1]) / final(paths[0])
    baseline = retime_adaptive(
        plant, GeometricPath.from_waypoints(spline), limits, grasp
    )

    def score(options: MoveOptimizerOptions) -> float:
        optimizer = MoveOptimizer(plant, limits, options)
        surrogate = CoarseRetimer(
            optimizer.chain, limits, grasp, optimizer.search_grid(baseline),
            ends=optimizer.end_grid(),
        )  # fmt: skip
        surrogate.select_rows(spline[None])
        durations = surrogate.durations(np.array(paths))
        return float(durations[1] / durations[0])

    assert reference < 0.98
    assert score(MoveOptimizerOptions()) > 1.0  # the shared grid: the other way
    ranked = score(MoveOptimizerOptions(search_end_points=4))
    assert ranked == pytest.approx(reference, abs=0.01)
