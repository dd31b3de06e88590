"""rt_drake.simulation._retimer_system: the LeafSystem outputs what retime() does."""

import numpy as np
import pytest
from pydrake.common.value import AbstractValue
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import ConstantValueSource

from rt_drake.model.held import held_object_of
from rt_drake.model.plant import make_arm_plant
from rt_drake.model.resources import scenarios_dir
from rt_drake.model.scenario import load_scenario
from rt_drake.retiming import GraspConstraint, JointLimits, retime
from rt_drake.simulation._retimer_system import (
    Retimer,
    RetimeRequest,
)

HOME = np.array([0.0, 0.35, 1.75, 0.0, 1.04, 0.0])
PATH = np.array(
    [
        HOME,
        HOME + [-0.4, 0.1, -0.2, 0.0, 0.1, -0.5],
        HOME + [-1.2, -0.1, 0.2, 0, -0.1, -0.8],
    ]
)


@pytest.fixture(scope="module")
def setup():
    scenario = load_scenario(scenarios_dir() / "stack_four_objects.yaml")
    plant = make_arm_plant(scenario)
    limits = JointLimits.from_plant(plant, scenario.robot)
    held = held_object_of(scenario.object("notebook"))
    return plant, limits, GraspConstraint.for_cup(held, scenario.cup)


def _diagram(plant, limits, request):
    builder = DiagramBuilder()
    source = builder.AddSystem(ConstantValueSource(AbstractValue.Make(request)))
    retimer = builder.AddSystem(Retimer(plant, limits, HOME))
    builder.Connect(source.get_output_port(), retimer.get_request_input_port())
    return builder.Build(), retimer


def test_system_outputs_the_pure_function_result(setup):
    plant, limits, grasp = setup
    diagram, retimer = _diagram(
        plant, limits, RetimeRequest(PATH, 1, grasp, start_time=0.2)
    )
    simulator = Simulator(diagram)
    context = retimer.GetMyContextFromRoot(simulator.get_mutable_context())
    # Before the first step: nothing retimed yet, hold the initial state.
    assert retimer.get_trajectory_output_port().Eval(context) is None
    np.testing.assert_array_equal(
        retimer.get_desired_state_output_port().Eval(context), np.r_[HOME, 0 * HOME]
    )
    expected = retime(plant, PATH, limits, grasp, start_time=0.2)
    for t in (0.1, 0.45, 0.7, 2.0):
        simulator.AdvanceTo(t)
        trajectory = retimer.get_trajectory_output_port().Eval(context)
        assert trajectory.start_time() == 0.2
        assert trajectory.end_time() == pytest.approx(
            expected.trajectory.end_time(), abs=0
        )
        times = np.linspace(0.0, 1.5, 31)
        for ours, theirs in zip(
            trajectory.sample(times), expected.trajectory.sample(times), strict=True
        ):
            np.testing.assert_array_equal(ours, theirs)
        q, v = expected.trajectory.sample(t, order=1)
        np.testing.assert_array_equal(
            retimer.get_desired_state_output_port().Eval(context), np.r_[q[0], v[0]]
        )


def test_new_request_is_retimed_once_and_state_lives_in_the_context(setup):
    plant, limits, grasp = setup
    request = RetimeRequest(PATH, 1)  # start on arrival
    diagram, retimer = _diagram(plant, limits, request)
    simulator = Simulator(diagram)
    simulator.AdvanceTo(0.3)
    context = retimer.GetMyContextFromRoot(simulator.get_mutable_context())
    state = context.get_abstract_state(0).get_value()
    assert state.request_id == request.request_id
    first = retimer.get_trajectory_output_port().Eval(context)
    assert first.start_time() == 0.0  # the first per-step update at t = 0
    simulator.AdvanceTo(0.6)
    assert retimer.get_trajectory_output_port().Eval(context).start_time() == 0.0
    # A fresh context (e.g. re-simulation) starts with nothing retimed.
    fresh = retimer.CreateDefaultContext()
    assert fresh.get_abstract_state(0).get_value().result is None
