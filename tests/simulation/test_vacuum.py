"""The vacuum: first-order build-up and release, "part present", and its guard.

The law against its closed form; the station's suction force against the
same closed form; then the cycle: a MOVE starts only once "part present"
fires, and a MOVE started before it (forced) drops the object where the
guarded one carries it.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from motion_helpers import IkMotions
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import ConstantVectorSource, TrajectorySource
from pydrake.trajectories import PiecewisePolynomial

from rt_drake.experiments._rollout import Replay
from rt_drake.model.held import held_object_of
from rt_drake.model.scenario import load_scenario
from rt_drake.model.vacuum import (
    Vacuum,
    VacuumTimeout,
    next_level,
    time_to_part_present,
    wait_over,
)
from rt_drake.simulation import UPDATE_PERIOD, MakeStation, run_cycle
from rt_drake.types.phase import Phase

FIRST_ORDER = Vacuum(
    model="first_order",
    attach_s=1.0,
    detach_s=1.0,
    build_up_tau_s=0.1,
    release_tau_s=0.05,
    part_present_fraction=0.8,
)


def test_level_steps_follow_the_exponential():
    level, h = 0.0, 1e-3
    for k in range(1, 301):
        level = next_level(FIRST_ORDER, level, True, h)
        assert level == pytest.approx(1 - math.exp(-k * h / 0.1), abs=1e-12)
    start = level
    for k in range(1, 101):
        level = next_level(FIRST_ORDER, level, False, h)
        assert level == pytest.approx(start * math.exp(-k * h / 0.05), abs=1e-12)
    assert time_to_part_present(FIRST_ORDER) == pytest.approx(0.1 * math.log(5.0))
    assert next_level(Vacuum(), 0.0, True, 1e-3) == 1.0
    assert next_level(Vacuum(), 1.0, False, 1e-3) == 0.0


def test_waits_end_on_time_or_on_the_signal_and_time_out():
    fixed = Vacuum(attach_s=1.0, detach_s=0.5)
    assert not wait_over(fixed, Phase.ATTACH, 0.99, True, "box")
    assert wait_over(fixed, Phase.ATTACH, 1.0, False, "box")
    assert wait_over(fixed, Phase.DETACH, 0.5, False, "box")
    assert wait_over(FIRST_ORDER, Phase.ATTACH, 0.2, True, "box")
    assert not wait_over(FIRST_ORDER, Phase.ATTACH, 0.9, False, "box")
    with pytest.raises(VacuumTimeout, match="ATTACH box: no part present within 1 s"):
        wait_over(FIRST_ORDER, Phase.ATTACH, 1.01, False, "box")
    with pytest.raises(VacuumTimeout, match="DETACH box: no release within 1 s"):
        wait_over(FIRST_ORDER, Phase.DETACH, 1.01, False, "box")


def _cup_on_the_notebook(scenario):
    ik = IkMotions(scenario)
    return ik.ik(ik.grasp(scenario.object("notebook")), np.array(scenario.robot.home))


def test_station_force_builds_up_and_releases_as_a_first_order_lag(scenario_paths):
    scenario = load_scenario(scenario_paths["random_transport"])
    scenario = dataclasses.replace(scenario, vacuum=FIRST_ORDER)
    q = _cup_on_the_notebook(scenario)
    station = MakeStation(scenario)
    builder = DiagramBuilder()
    cell = builder.AddSystem(station.diagram)
    hold = builder.AddSystem(ConstantVectorSource(np.concatenate([q, 0 * q])))
    builder.Connect(hold.get_output_port(), cell.GetInputPort("robot.desired_state"))
    zero = builder.AddSystem(ConstantVectorSource(np.zeros(6)))
    builder.Connect(
        zero.get_output_port(), cell.GetInputPort("robot.desired_acceleration")
    )
    t_off = 0.5
    valve = builder.AddSystem(
        TrajectorySource(
            PiecewisePolynomial.ZeroOrderHold([0.0, t_off, 10.0], [[1.0, 0.0, 0.0]])
        )
    )
    builder.Connect(valve.get_output_port(), cell.GetInputPort("suction.valve"))
    diagram = builder.Build()
    simulator = Simulator(diagram)
    context = simulator.get_mutable_context()
    station.plant.SetPositions(
        station.plant.GetMyMutableContextFromRoot(context), station.models.robot, q
    )
    cell_context = cell.GetMyContextFromRoot(context)
    force_port = cell.GetOutputPort("suction.suction_force")
    present_port = cell.GetOutputPort("suction.part_present")
    PA = scenario.cup.suction_force
    t_present = time_to_part_present(FIRST_ORDER)
    for t in np.arange(0.01, 0.8, 0.02):  # never on the valve switch
        simulator.AdvanceTo(t)
        force = force_port.Eval(cell_context)[0]
        # The discrete level is within one 1 ms step of the valve's switches.
        steps = (-1e-3, 0.0, 1e-3)
        if t < t_off:
            expected = [PA * (1 - math.exp(-(t - d) / 0.1)) for d in steps]
        else:
            expected = [
                PA
                * (1 - math.exp(-(t_off + e) / 0.1))
                * math.exp(-(t - t_off - e) / 0.05)
                for e in steps
            ]
        assert min(expected) - 1e-6 <= force <= max(expected) + 1e-6, (t, force)
        present = present_port.Eval(cell_context)[0] > 0.5
        if abs(t - t_present) > 2e-3 and t < t_off:
            assert present == (t > t_present), t


@pytest.fixture(scope="module")
def guarded_move(scenario_paths):
    """A notebook MOVE retimed for 0.8 P A, and the arm at its grasp."""
    from rt_drake.simulation import OnlineMotions

    scenario = load_scenario(scenario_paths["random_transport"])
    scenario = dataclasses.replace(scenario, vacuum=FIRST_ORDER)
    motions = OnlineMotions(scenario)
    obj = scenario.object("notebook")
    pick = motions.pick(motions.q_home, obj)
    move = motions.move(pick.q_end, obj, pick)
    assert move.grasp.cup.suction_force == pytest.approx(0.8 * 20.0)
    return scenario, pick.q_end, move


#: s, a slow build-up for the guard tests: with it the force lags the MOVE's
#: first acceleration by long enough to matter.
SLOW_TAU = 0.5


def _play(scenario, q_grasp, move, fraction):
    # A long DETACH time-out: a dropped object may tumble before it rests.
    vacuum = dataclasses.replace(
        FIRST_ORDER,
        build_up_tau_s=SLOW_TAU,
        part_present_fraction=fraction,
        attach_s=5.0,
        detach_s=5.0,
    )
    world = dataclasses.replace(
        scenario,
        vacuum=vacuum,
        robot=dataclasses.replace(scenario.robot, home=[float(x) for x in q_grasp]),
    )
    (record,) = run_cycle(
        world, Replay(q_grasp, move.trajectory), max_sim_time=10.0
    ).records
    return record


@pytest.mark.slow
def test_move_waits_for_part_present_and_the_guarded_move_holds(guarded_move):
    scenario, q_grasp, move = guarded_move
    record = _play(scenario, q_grasp, move, 0.8)
    PA = scenario.cup.suction_force
    assert record.move_suction_force >= 0.8 * PA
    # ATTACH lasted until the switch fired (within an update period); the
    # valve opened with REACH (its last stretch: the cup already sealed), so
    # the build-up counts from there.
    attach = record.exec_s[Phase.ATTACH]
    reach = record.exec_s[Phase.REACH]
    t_present = SLOW_TAU * math.log(1.0 / (1.0 - 0.8))
    assert t_present <= reach + attach + 1e-3
    assert reach + attach <= t_present + UPDATE_PERIOD + 2e-3
    assert record.max_slip_translation < 2e-3
    assert np.degrees(record.max_slip_rotation) < 2.0
    # DETACH ended once released: the object stays on its goal.
    assert record.placement_translation < 0.01


@pytest.mark.slow
def test_a_move_started_before_part_present_loses_the_object(guarded_move):
    scenario, q_grasp, move = guarded_move
    # The switch set far too low: the same MOVE starts with ~5 % of P A.
    record = _play(scenario, q_grasp, move, 0.05)
    assert record.move_suction_force < 0.8 * scenario.cup.suction_force
    assert record.max_slip_translation > 5e-3


@pytest.mark.slow
def test_a_vacuum_that_does_not_hold_in_time_stops_the_cycle(scenario_paths):
    scenario = load_scenario(scenario_paths["random_transport"])
    slow = dataclasses.replace(FIRST_ORDER, attach_s=0.05, build_up_tau_s=0.5)
    scenario = dataclasses.replace(scenario, vacuum=slow)
    # A brisk APPROACH and REACH (1.0 and 0.6 s by default): the time-out
    # comes 50 ms into ATTACH whatever came before it.
    brisk = IkMotions(scenario, approach_s=0.5, reach_s=0.3)
    with pytest.raises(VacuumTimeout, match="ATTACH notebook: no part present"):
        run_cycle(scenario, brisk, max_sim_time=10.0)


@pytest.mark.slow
def test_the_valve_opens_on_the_descent_and_the_seal_forms_at_contact(scenario_paths):
    """first_order: the build-up overlaps the descent's end; the MOVE still waits.

    The level builds only while the cup is sealed (the face within the seal
    distance), from the valve opening ``time_to_part_present`` before REACH
    ends. So ATTACH lasts less than the closed-form build-up time from a cold
    start, yet the MOVE starts with at least ``part_present_fraction`` of P A
    (the force its retime assumed) and the notebook holds and lands. Likewise
    the valve closes before the MOVE arrives (its guarantee says how early),
    and the notebook still holds on the way down and lands.
    """
    from rt_drake.simulation import OnlineMotions

    scenario = load_scenario(scenario_paths["random_transport"])
    scenario = dataclasses.replace(scenario, vacuum=FIRST_ORDER)
    motions = OnlineMotions(scenario, optimize=False)
    (record,) = run_cycle(scenario, motions, max_sim_time=10.0).records
    attach = record.exec_s[Phase.ATTACH]
    assert 0.0 <= attach < time_to_part_present(FIRST_ORDER) - 0.01
    assert record.move_suction_force >= 0.8 * scenario.cup.suction_force
    assert "s before arrival" in record.guarantee
    # Closed on arrival, the force (at least 0.8 P A then) would need
    # tau_r ln(0.8 P A / W) to fall below the weight W: DETACH is shorter.
    weight = held_object_of(scenario.object("notebook")).mass * 9.81
    on_arrival = FIRST_ORDER.release_tau_s * math.log(
        0.8 * scenario.cup.suction_force / weight
    )
    assert record.exec_s[Phase.DETACH] < on_arrival
    assert record.max_slip_translation < 2e-3
    assert record.placement_translation < 0.01
