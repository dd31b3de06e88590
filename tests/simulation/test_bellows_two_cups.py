"""Two bellows cups: the slip is measured on the lips, not on the tool.

The heavy carton (2.2 kg) of ``carton_two_cups_bellows_20n`` starts sealed on
both lips with the bellows relaxed, the arm held still. It sinks into the
bellows and rings on them: the static stretch of each is ``(m / 2 + m_lip) g
/ k_axial`` = 15.7 mm, reached through an oscillation of period ``2 pi
sqrt((m + 2 m_lip) / (2 k_axial))`` = 0.25 s with damping ratio 0.07, so the
carton still swings by about 9 mm (``0.59 x`` the stretch) on the tool when
the MOVE (here: the arm held still for 0.3 s more) starts. With no shear and
no moment on the lips (a symmetric load, the tool vertical), friction holds
the carton on each lip: its slip on the lips stays near zero while its
motion on the tool is that swing.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from pydrake.trajectories import PiecewisePolynomial

from rt_drake.experiments._rollout import rollout_scenario, simulate_move
from rt_drake.experiments._transport_experiment import transport_scenario
from rt_drake.model.cup_physics import load_bellows_cup
from rt_drake.model.plant import make_arm_plant, scenario_cup_frame
from rt_drake.model.resources import resolve_scenario_path
from rt_drake.model.scenario import load_scenario

pytestmark = pytest.mark.slow

HOLD_S = 0.3  # s, the "MOVE": the arm held still


def _hanging_carton():
    """The scenario with the carton sealed on the tool at the arm's home."""
    scenario = load_scenario(resolve_scenario_path("carton_two_cups_bellows_20n"))
    obj = scenario.objects[0]
    plant = make_arm_plant(scenario)
    context = plant.CreateDefaultContext()
    q = np.array(scenario.robot.home)
    plant.SetPositions(context, q)
    X_WT = scenario_cup_frame(plant, scenario).CalcPoseInWorld(context)
    X_WO = X_WT @ obj.grasp.GetDeterministicValue().inverse()
    held = transport_scenario(scenario, obj.name, X_WO, X_WO)
    return rollout_scenario(held, q), q


def test_carton_on_two_lips_does_not_slip_while_the_bellows_ring():
    world, q = _hanging_carton()
    cup = load_bellows_cup(world.cup_physics.cup)
    # The swing the closed form predicts, for scale: the static stretch.
    mass = 2.2
    sag = (mass / 2 + cup.lip_mass) * 9.81 / cup.axial_stiffness
    assert sag == pytest.approx(0.0157, abs=2e-4)
    hold = PiecewisePolynomial.FirstOrderHold([0.0, HOLD_S], np.column_stack([q, q]))
    rollout = simulate_move(world, q, hold)
    # On the tool the carton swings with the bellows by a good share of the
    # stretch (the swing decays by exp(-zeta w t) = 0.59 by the MOVE's start).
    assert rollout.on_tool_translation > 0.2 * sag
    # On each lip it stays: friction carries no shear here.
    assert rollout.slip_translation < 0.5e-3
    assert rollout.slip_rotation < math.radians(0.5)
