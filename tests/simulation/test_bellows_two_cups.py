"""Two bellows cups: the slip on the lips, and how a trial's carton starts.

The heavy carton (2.2 kg) hangs from two bellows cups at the arm's home, the
arm held still (the "MOVE" here). Closed forms for it: each bushing's static
stretch is ``(m / 2 + m_lip) g / k_axial`` = 15.7 mm; dropped onto relaxed
bellows the carton rings about that stretch with period ``2 pi sqrt((m / 2 +
m_lip) / k_axial)`` = 0.25 s and damping ratio ``zeta = c / (2 sqrt(k_axial
(m / 2 + m_lip)))`` = 0.071, so its first swing overshoots the static load
by ``exp(-pi zeta / sqrt(1 - zeta^2))`` = 0.80 of it.

- Relaxed start (``start_on_cup`` off: the carton placed on unstretched
  bellows), cups of 20 N: the carton swings on the tool, and friction holds
  it on each lip (no shear, no moment: a symmetric load), so the slip on the
  lips stays near zero while the motion on the tool is that swing.
- The same relaxed start on the catalogue's 14.7 N cups: at the bottom of the
  first swing each lip must pull ``1.80 (m / 2) g`` = 19.4 N onto the carton
  against a pull of 14.7 N; it lets go and the carton falls, before any MOVE.
- Held start (``start_on_cup``: the carton already picked, at rest on the
  stretched bellows): on the 14.7 N cups the carton stays, on the lips and on
  the tool.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from pydrake.trajectories import PiecewisePolynomial

from rt_drake.experiments._rollout import Replay, rollout_scenario, simulate_move
from rt_drake.experiments._transport_experiment import transport_scenario
from rt_drake.model.cup_physics import load_bellows_cup
from rt_drake.model.plant import make_arm_plant, scenario_cup_frame
from rt_drake.model.resources import resolve_scenario_path
from rt_drake.model.scenario import load_scenario
from rt_drake.simulation import run_cycle

pytestmark = pytest.mark.slow

HOLD_S = 0.3  # s, the "MOVE": the arm held still
MASS = 2.2  # kg, the heavy carton
G = 9.81


def _hanging_carton(name: str, held: bool):
    """The scenario ``name`` with the carton sealed on the tool at the arm's home.

    ``held``: a trial's start on the cup (``random_transport.start_on_cup``);
    else the carton is placed on relaxed bellows.
    """
    scenario = load_scenario(resolve_scenario_path(name))
    obj = scenario.objects[0]
    plant = make_arm_plant(scenario)
    context = plant.CreateDefaultContext()
    q = np.array(scenario.robot.home)
    plant.SetPositions(context, q)
    X_WT = scenario_cup_frame(plant, scenario).CalcPoseInWorld(context)
    X_WO = X_WT @ obj.grasp.GetDeterministicValue().inverse()
    held_scenario = transport_scenario(scenario, obj.name, X_WO, X_WO)
    assert held_scenario.random_transport is not None
    assert held_scenario.random_transport.start_on_cup
    if not held:
        held_scenario = dataclasses.replace(held_scenario, random_transport=None)
    return rollout_scenario(held_scenario, q), q


def _still(q: np.ndarray):
    return PiecewisePolynomial.FirstOrderHold([0.0, HOLD_S], np.column_stack([q, q]))


def _axial(name: str):
    """(static stretch m, overshoot of a dropped load) of one bushing, closed form."""
    cup = load_bellows_cup(load_scenario(resolve_scenario_path(name)).cup_physics.cup)
    mass = MASS / 2 + cup.lip_mass
    zeta = cup.axial_damping / (2.0 * math.sqrt(cup.axial_stiffness * mass))
    return (
        mass * G / cup.axial_stiffness,
        math.exp(-math.pi * zeta / math.sqrt(1 - zeta**2)),
        cup,
    )


def test_relaxed_start_swings_on_the_tool_not_on_the_lips():
    world, q = _hanging_carton("carton_two_cups_bellows_20n", held=False)
    sag, overshoot, cup = _axial("carton_two_cups_bellows_20n")
    assert sag == pytest.approx(0.0157, abs=2e-4)
    # 20 N cups survive the first swing: (1 + overshoot) m g / 2 < P A.
    assert (1 + overshoot) * MASS * G / 2 < cup.suction_force
    rollout = simulate_move(world, q, _still(q))
    # On the tool the carton swings with the bellows by a good share of the
    # stretch (the swing decays by exp(-zeta w t) = 0.59 by the MOVE's start).
    assert rollout.on_tool_translation > 0.2 * sag
    # On each lip it stays: friction carries no shear here.
    assert rollout.slip_translation < 0.5e-3
    assert rollout.slip_rotation < math.radians(0.5)


def _record(world, q, held: bool):
    result = run_cycle(
        world, Replay(q, _still(q)), max_sim_time=30.0, held_at_start=held
    )
    (record,) = result.records
    return record


def test_relaxed_start_drops_the_carton_from_14_7_n_cups():
    world, q = _hanging_carton("carton_two_cups_bellows", held=False)
    _, overshoot, cup = _axial("carton_two_cups_bellows")
    # The closed form: the first swing asks more of each lip than its pull.
    assert (1 + overshoot) * MASS * G / 2 > cup.suction_force
    record = _record(world, q, held=False)
    # Both seals are lost before the MOVE starts (no vacuum then), and the
    # carton ends far from where it hung (its goal: the start).
    assert record.move_suction_force == 0.0
    assert record.placement_translation > 0.05


def test_held_start_keeps_the_carton_on_14_7_n_cups():
    world, q = _hanging_carton("carton_two_cups_bellows", held=True)
    sag, _, cup = _axial("carton_two_cups_bellows")
    record = _record(world, q, held=True)
    assert record.move_suction_force == pytest.approx(2 * cup.suction_force)
    assert record.max_slip_translation < 0.5e-3
    assert record.max_slip_rotation < math.radians(0.5)
    # Started at its sag, it does not swing on the tool either.
    assert record.max_on_tool_translation < 0.1 * sag
