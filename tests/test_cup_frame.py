"""The cup frame in plants with more than one arm: the gravity shortcut and
the wrench agree with an independent route (body accelerations +
Newton-Euler), and the retimed motion holds the grasp.

The plants reproduce the issue's probe: a parked arm (or a turntable) added
before the arm that carries the cup, each with a vertical joint welded to
the world that does not move the cup.
"""

from __future__ import annotations

import re

import numpy as np
import pytest
from plant_helpers import add_turntable
from pydrake.math import RigidTransform
from pydrake.multibody.parsing import Parser
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import ModelInstanceIndex
from scipy.interpolate import CubicSpline

from rt_drake import (
    CupFrame,
    GraspConstraint,
    InputError,
    JointLimits,
    check_trajectory,
    retime,
)
from rt_drake.dynamics.cup_frame import vertical_base_joint
from rt_drake.dynamics.newton_euler import reference_object_wrench
from rt_drake.dynamics.wrench import path_wrench_coefficients
from rt_drake.model.held import held_object_of
from rt_drake.model.parser import make_parser
from rt_drake.model.resources import models_dir
from rt_drake.model.scenario import RobotConfig
from rt_drake.retiming import Margin, RetimeInputError

HOME = np.array([0.0, 0.35, 1.75, 0.0, 1.04, 0.0])
SWING = [
    HOME,
    HOME + [0.6, -0.2, -0.2, 0.0, 0.3, 0.4],
    HOME + [1.2, 0.0, 0.0, 0, 0, 0.7],
]


def _arm(plant, parser, X_WB, with_tool):
    (arm,) = parser.AddModels(url="package://rt_drake/robot/vs060.urdf")
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("base_link", arm), X_WB)
    if with_tool:
        (tool,) = parser.AddModels(url="package://rt_drake/tool/suction_tool.urdf")
        plant.WeldFrames(
            plant.GetFrameByName("link6", arm), plant.GetFrameByName("tool", tool)
        )
    return arm


def two_arms() -> MultibodyPlant:
    """A parked arm first, then the arm with the cup (12 joints)."""
    plant = MultibodyPlant(0.0)
    parser = make_parser(plant)
    parser.SetAutoRenaming(True)
    _arm(plant, parser, RigidTransform([0.0, 0.9, 0.0]), with_tool=False)
    _arm(plant, parser, RigidTransform(), with_tool=True)
    plant.Finalize()
    return plant


def turntable_and_arm() -> MultibodyPlant:
    """A turntable on a vertical joint welded to the world, then the arm."""
    plant = MultibodyPlant(0.0)
    add_turntable(plant, [0.0, 0.0, 1.0])
    _arm(plant, make_parser(plant), RigidTransform(), with_tool=True)
    plant.Finalize()
    return plant


PLANTS = {"two arms": (two_arms, 6), "turntable": (turntable_and_arm, 1)}


@pytest.fixture(scope="module", params=sorted(PLANTS))
def case(request, scenario):
    build, first = PLANTS[request.param]
    plant = build()
    held = held_object_of(scenario.object("notebook"))
    grasp = GraspConstraint.for_cup(held, scenario.cup)
    return plant, first, grasp


def _full(plant, first, q_arm):
    q = np.zeros((len(q_arm), plant.num_positions()))
    q[:, first : first + 6] = q_arm
    return q


def test_only_a_joint_of_the_cups_chain_gives_gravity(case):
    plant, first, _ = case
    cup = CupFrame.of(plant)
    assert vertical_base_joint(plant, cup) == (first, pytest.approx(-9.81))


def test_a_joint_outside_the_cups_chain_sends_the_retimer_to_drake(case):
    """No batched chain (rt_drake.dynamics.chain) for these plants: Drake's route."""
    plant, _, _ = case
    assert CupFrame.of(plant).chain is None


def test_wrench_coefficients_equal_newton_euler_from_body_accelerations(case):
    plant, first, grasp = case
    knots = np.array([0.0, 0.4, 1.0])
    spline = CubicSpline(knots, np.array(SWING), bc_type="clamped")
    s = np.linspace(0.0, 1.0, 15)
    q, dq, ddq = (_full(plant, first, spline(s, k)) for k in range(3))
    a, b, c = path_wrench_coefficients(plant, grasp.held, q, dq, ddq)
    rng = np.random.default_rng(0)
    u, x = rng.uniform(-3.0, 3.0, len(s)), rng.uniform(0.0, 4.0, len(s))
    ours = a * u[:, None] + b * x[:, None] + c
    v, vdot = dq * np.sqrt(x)[:, None], dq * u[:, None] + ddq * x[:, None]
    reference = reference_object_wrench(
        plant, grasp.held, CupFrame.of(plant), q, v, vdot
    )
    np.testing.assert_allclose(ours, reference, rtol=1e-9, atol=1e-9)
    assert np.abs(reference[:, 3:]).max() > 1.0  # gravity is in there


def test_retimed_motion_holds_the_grasp_checked_independently(case):
    plant, first, grasp = case
    path = _full(plant, first, np.array(SWING))
    # The turntable has no limits in its model: 1 rad/s, 1 rad/s^2 (it stays).
    limits = JointLimits(
        *(
            np.where(np.isfinite(v), v, 1.0)
            for v in (
                plant.GetVelocityUpperLimits(),
                plant.GetAccelerationUpperLimits(),
            )
        )
    )
    result = retime(plant, path, limits, grasp)
    check = check_trajectory(plant, result.trajectory, limits, grasp)
    assert check.min_margin() >= -1e-3, check.summary()
    assert result.margins[Margin.GRASP].min() == pytest.approx(0.0, abs=1e-6)


def test_an_ambiguous_or_missing_frame_name_is_refused():
    plant = MultibodyPlant(0.0)
    parser = make_parser(plant)
    parser.SetAutoRenaming(True)
    _arm(plant, parser, RigidTransform([0.0, 0.9, 0.0]), with_tool=True)
    _arm(plant, parser, RigidTransform(), with_tool=True)
    plant.Finalize()
    with pytest.raises(InputError, match="several model instances"):
        CupFrame.of(plant)
    with pytest.raises(InputError, match="no frame named 'tip'"):
        CupFrame.of(plant, "tip")


def test_two_arms_each_retime_with_their_own_cup(scenario):
    """Two tools in one plant: each cup named by scope, each arm retimed."""
    plant = MultibodyPlant(0.0)
    parser = make_parser(plant)
    parser.SetAutoRenaming(True)
    _arm(plant, parser, RigidTransform([0.0, 0.9, 0.0]), with_tool=True)
    _arm(plant, parser, RigidTransform(), with_tool=True)
    plant.Finalize()
    tools = _instances(plant, "tool")
    held = held_object_of(scenario.object("notebook"))
    grasp = GraspConstraint.for_cup(held, scenario.cup)
    limits = JointLimits.from_plant(plant)
    for first, tool in zip((0, 6), tools, strict=True):
        cup = CupFrame.of(plant, f"{tool}::suction_cup")
        assert vertical_base_joint(plant, cup) == (first, pytest.approx(-9.81))
        path = np.tile(HOME, (3, 2))
        path[:, first : first + 6] = SWING
        result = retime(plant, path, limits, grasp, cup=cup)
        check = check_trajectory(plant, result.trajectory, limits, grasp, cup=cup)
        assert check.min_margin() >= -1e-3, check.summary()
        # The other cup's wrench would be the wrong one: its arm stands still.
        assert result.margins[Margin.GRASP].min() == pytest.approx(0.0, abs=1e-6)


def _instances(plant, body_name):
    names = []
    for i in range(plant.num_model_instances()):
        instance = ModelInstanceIndex(i)
        if plant.HasBodyNamed(body_name, instance):
            names.append(plant.GetModelInstanceName(instance))
    return names


def test_limits_a_model_lacks_are_asked_for_by_name():
    """A URDF without drake:acceleration and without transmissions."""
    plant = MultibodyPlant(0.0)
    text = (models_dir() / "robot" / "vs060.urdf").read_text()
    text = re.sub(r' drake:acceleration="[^"]*"', "", text)
    text = re.sub(r"<transmission.*?</transmission>", "", text, flags=re.S)
    (arm,) = Parser(plant).AddModelsFromString(text, "urdf")
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("base_link", arm))
    plant.Finalize()
    with pytest.raises(RetimeInputError, match=r"no acceleration limit for joint 1 "):
        JointLimits.from_plant(plant)
    robot = RobotConfig(acceleration_limits=np.full(6, 10.0))  # numpy arrays work
    limits = JointLimits.from_plant(plant, robot)
    assert limits.acceleration.tolist() == [10.0] * 6
    with pytest.raises(RetimeInputError, match="no torque limit for joint 1"):
        JointLimits.from_plant(plant, robot, torque=True)
    with pytest.raises(RetimeInputError, match="5 values but the plant has 6 joints"):
        JointLimits.from_plant(plant, RobotConfig(velocity_limits=[1.0] * 5))
