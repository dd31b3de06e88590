"""The optimiser's coarse TOPP-RA against the retimer's passes on Drake's data."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.interpolate import CubicSpline

from rt_drake import CupFrame, GraspConstraint, JointLimits
from rt_drake.contact import cached_wrench_polytope
from rt_drake.dynamics.wrench import path_wrench_coefficients
from rt_drake.model.held import held_object_of
from rt_drake.retiming import chord_knots
from rt_drake.retiming.passes import AffineConstraint, XBound, reachability
from rt_drake.shaping._surrogate import CoarseRetimer
from rt_drake.shaping.cup_chain import CupChain


def classic_toppra(plant, waypoints, limits, grasp, gridpoints):
    """TOPP-RA at the grid points only, every grasp row, Drake's kinematics."""
    spline = CubicSpline(chord_knots(waypoints), waypoints, bc_type="clamped")
    s = np.linspace(0.0, 1.0, gridpoints)
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
