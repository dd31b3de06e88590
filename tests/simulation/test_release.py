"""Release on arrival: the valve closes before a MOVE ends as far as the grasp holds.

The lead L of :func:`rt_drake.simulation._release.release_lead` (the object's
wrench sampled at 1 kHz, joint-space Newton-Euler) is checked on the MOVE's
own retiming grid through the other route to the same wrench, the path
coefficients ``a s'' + b s'^2 + c``
(:meth:`~rt_drake.simulation.OnlineMotions.grasp_margin`): with the force
certain at arrival, ``f0 exp(-L / tau_r)``, every grid point of the last L
seconds keeps a margin >= 0 (within the samples' resolution), and a lead
longer by ``STEP`` breaks it.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from rt_drake.contact import cached_wrench_polytope, with_suction_force
from rt_drake.model.scenario import load_scenario
from rt_drake.model.vacuum import Vacuum
from rt_drake.retiming import GraspConstraint

#: s: the longer lead that must break the grasp.
STEP = 0.01
#: Relative margin the 1 kHz samples may miss between them on the grid.
TOLERANCE = 2e-3


@pytest.fixture(scope="module")
def release(scenario_paths):
    """A notebook MOVE of random_transport with the first_order vacuum."""
    from rt_drake.simulation import OnlineMotions

    scenario = load_scenario(scenario_paths["random_transport"])
    scenario = dataclasses.replace(scenario, vacuum=Vacuum(model="first_order"))
    motions = OnlineMotions(scenario)
    obj = scenario.object("notebook")
    pick = motions.pick(motions.q_home, obj)
    move = motions.move(pick.q_end, obj, pick)
    return scenario, motions, move


def test_the_lead_is_the_longest_the_decaying_force_holds(release):
    scenario, motions, move = release
    vacuum, cup = scenario.vacuum, scenario.cup
    lead = move.release_s
    assert 0.0 < lead < 3.0 * vacuum.release_tau_s
    assert f"valve closed {lead:.3f} s before arrival" in move.guarantee
    f0 = vacuum.part_present_fraction * cup.suction_force
    full = cached_wrench_polytope(cup)
    margin = scenario.planning.grasp_margin
    result = move.retimed
    dt = 2.0 * np.diff(result.gridpoints) / (result.sd[:-1] + result.sd[1:])
    t = np.concatenate([[0.0], np.cumsum(dt)])
    assert t[-1] == pytest.approx(move.duration, rel=1e-6)

    def worst(length: float) -> float:
        force = f0 * math.exp(-length / vacuum.release_tau_s)
        polytope = with_suction_force(full, force)
        grasp = GraspConstraint.for_polytope(move.grasp.held, polytope)
        grasp = grasp.with_margin(margin)
        margins = motions.grasp_margin(move.planned.path, result, grasp)
        return float(margins[t >= t[-1] - length].min())

    assert worst(lead) >= -TOLERANCE
    assert worst(lead + STEP) < 0.0


def test_no_lead_with_the_fixed_vacuum(release):
    scenario, motions, _ = release
    fixed = dataclasses.replace(scenario, vacuum=Vacuum())
    from rt_drake.simulation import OnlineMotions

    motions = OnlineMotions(fixed)
    obj = fixed.object("notebook")
    pick = motions.pick(motions.q_home, obj)
    move = motions.move(pick.q_end, obj, pick)
    assert move.release_s == 0.0
    assert "valve closed" not in move.guarantee
