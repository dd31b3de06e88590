"""The UR5e model against Universal Robots' published data, and its scenario.

The references are typed in from the sources that ur5e.urdf cites, not read
from the URDF: UR's "DH Parameters for calculations of kinematics and
dynamics" (UR5e table: DH parameters, link masses, centres of mass in the DH
frame of each link) and Universal_Robots_ROS2_Description 2.4.5,
config/ur5e/joint_limits.yaml (position, velocity, effort limits).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from pydrake.multibody.plant import MultibodyPlant

from rt_drake import (
    CyclePlanner,
    GraspConstraint,
    JointLimits,
    OnlineMotions,
    check_trajectory,
    load_scenario,
    retime,
    run_cycle,
)
from rt_drake.model.held import held_object_of
from rt_drake.model.parser import make_parser
from rt_drake.model.plant import (
    CUP_FRAME,
    make_arm_plant,
)
from rt_drake.model.resources import (
    models_dir,
    scenarios_dir,
)
from rt_drake.retiming import Margin

# UR's DH table, UR5e: (d, a, alpha) of joints 1..6 (m, rad); theta = q.
DH = [
    (0.1625, 0.0, np.pi / 2),
    (0.0, -0.425, 0.0),
    (0.0, -0.3922, 0.0),
    (0.1333, 0.0, np.pi / 2),
    (0.0997, 0.0, -np.pi / 2),
    (0.0996, 0.0, 0.0),
]
# UR's table: link masses (kg) and centres of mass in each link's DH frame (m).
MASSES = [3.761, 8.058, 2.846, 1.37, 1.3, 0.365]
COMS = [
    [0.0, -0.02561, 0.00193],
    [0.2125, 0.0, 0.11336],
    [0.15, 0.0, 0.0265],
    [0.0, -0.0018, 0.01634],
    [0.0, 0.0018, 0.01634],
    [0.0, 0.0, -0.001159],
]
# joint_limits.yaml: 180 deg/s everywhere; 150 N m (size-3 joints), 28 N m
# (wrists); +-360 deg, the elbow +-180 deg.
VELOCITY = np.full(6, np.pi)
EFFORT = [150.0, 150.0, 150.0, 28.0, 28.0, 28.0]
POSITION = np.radians([360, 360, 180, 360, 360, 360])
SCENARIO = scenarios_dir() / "ur5e_transport.yaml"
GRIDPOINTS = 400


def dh_frames(q: np.ndarray) -> list[np.ndarray]:
    """X_0i (4x4) of DH frames 1..6: prod_i Rz(q_i) Tz(d_i) Tx(a_i) Rx(alpha_i)."""
    X = np.eye(4)
    frames = []
    for theta, (d, a, alpha) in zip(q, DH, strict=True):
        c, s, ca, sa = np.cos(theta), np.sin(theta), np.cos(alpha), np.sin(alpha)
        X = X @ np.array(
            [
                [c, -s * ca, s * sa, a * c],
                [s, c * ca, -c * sa, a * s],
                [0.0, sa, ca, d],
                [0.0, 0.0, 0.0, 1.0],
            ]
        )
        frames.append(X)
    return frames


CONFIGURATIONS = [
    np.zeros(6),
    np.array([-0.35, -1.9, 1.9, -1.5708, -1.5708, 0.0]),
    *np.random.default_rng(7).uniform(-np.pi, np.pi, (4, 6)),
]


@pytest.fixture(scope="module")
def arm() -> MultibodyPlant:
    """ur5e.urdf alone, its base frame (DH frame 0) welded at the world origin."""
    plant = MultibodyPlant(0.0)
    make_parser(plant).AddModels(str(models_dir() / "robot" / "ur5e.urdf"))
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("base_link"))
    plant.Finalize()
    return plant


@pytest.mark.parametrize("q", CONFIGURATIONS, ids=lambda q: np.array2string(q, 2))
def test_tool0_is_the_dh_flange(arm, q):
    context = arm.CreateDefaultContext()
    arm.SetPositions(context, q)
    X_0F = arm.GetFrameByName("tool0").CalcPoseInWorld(context).GetAsMatrix4()
    np.testing.assert_allclose(X_0F, dh_frames(q)[-1], atol=1e-12)


@pytest.mark.parametrize("q", CONFIGURATIONS[1:3], ids=lambda q: np.array2string(q, 2))
def test_link_masses_and_centres_of_mass_are_the_published_ones(arm, q):
    context = arm.CreateDefaultContext()
    arm.SetPositions(context, q)
    for i, X_0i in enumerate(dh_frames(q)):
        body = arm.GetBodyByName(f"link{i + 1}")
        assert body.default_mass() == pytest.approx(MASSES[i], abs=1e-12)
        p_0cm = body.EvalPoseInWorld(context).multiply(
            body.CalcCenterOfMassInBodyFrame(context)
        )
        p_icm = np.linalg.solve(X_0i, np.append(p_0cm, 1.0))[:3]
        np.testing.assert_allclose(p_icm, COMS[i], atol=1e-12)
    moving = sum(arm.GetBodyByName(f"link{i}").default_mass() for i in range(1, 7))
    assert moving == pytest.approx(17.7, abs=1e-9)


def test_limits_are_the_published_ones_with_an_actuator_per_joint(arm):
    np.testing.assert_allclose(arm.GetVelocityUpperLimits(), VELOCITY)
    np.testing.assert_allclose(arm.GetVelocityLowerLimits(), -VELOCITY)
    np.testing.assert_allclose(arm.GetPositionUpperLimits(), POSITION)
    np.testing.assert_allclose(arm.GetPositionLowerLimits(), -POSITION)
    assert arm.num_actuators() == 6
    np.testing.assert_allclose(arm.GetEffortUpperLimits(), EFFORT)
    # Not published: a finite cap, for the retimer, above any torque-bound value.
    assert np.all(np.isfinite(arm.GetAccelerationUpperLimits()))


@pytest.fixture(scope="module")
def scenario():
    return load_scenario(SCENARIO)


def test_cup_sits_on_the_flange_axis_in_the_cell(scenario):
    """The cell turns the base by pi about z; the cup face is 0.12 m beyond tool0."""
    plant = make_arm_plant(scenario)
    context = plant.CreateDefaultContext()
    q = np.array(scenario.robot.home)
    plant.SetPositions(context, q)
    X_WC = plant.GetFrameByName(CUP_FRAME).CalcPoseInWorld(context).GetAsMatrix4()
    Rz = np.diag([-1.0, -1.0, 1.0, 1.0])
    X_WF = Rz @ dh_frames(q)[-1]
    np.testing.assert_allclose(X_WC[:3, :3], X_WF[:3, :3], atol=1e-12)
    np.testing.assert_allclose(
        X_WC[:3, 3], X_WF[:3, 3] + 0.12 * X_WF[:3, 2], atol=1e-12
    )
    assert X_WC[2, 2] == pytest.approx(-1.0, abs=1e-4)  # home: the cup points down


def test_scenario_plans_a_move_and_retimes_it_under_grasp_and_torques(scenario):
    planner = CyclePlanner(scenario, seed=0)
    approach = planner.plan_approach(planner.q_home, "notebook")
    reach = planner.plan_reach(approach.q_goal, "notebook")
    move = planner.plan_move(reach.q_goal, "notebook", reach=reach)

    # The MOVE ends with the notebook on its goal, held at its grasp.
    plant = make_arm_plant(scenario)
    context = plant.CreateDefaultContext()
    plant.SetPositions(context, move.q_goal)
    obj = scenario.object("notebook")
    X_WC_goal = obj.goal.GetDeterministicValue() @ obj.grasp.GetDeterministicValue()
    X_WC = plant.GetFrameByName(CUP_FRAME).CalcPoseInWorld(context)
    np.testing.assert_allclose(X_WC.translation(), X_WC_goal.translation(), atol=1e-4)

    limits = JointLimits.from_plant(plant, scenario.robot)
    np.testing.assert_allclose(limits.torque, EFFORT)  # robot.limit_torques
    grasp = GraspConstraint.for_cup(held_object_of(obj), scenario.cup)
    # TOPP-RA constrains the grid points only. At the cycle's 100 points this
    # path overshoots the shoulder-lift torque by about 8 % between them (the
    # check's 5 % tolerance was measured on VS-060 paths); at 400, by about 3 %.
    held = retime(plant, move.path, limits, grasp, gridpoints=GRIDPOINTS)
    free = retime(plant, move.path, limits, gridpoints=GRIDPOINTS)
    check = check_trajectory(plant, held.trajectory, limits, grasp)
    assert check.passed(), check.summary()
    assert held.duration >= free.duration * (1 - 1e-9)
    # Not vacuous: retimed under the joint limits alone, the notebook would slip.
    free_check = check_trajectory(plant, free.trajectory, limits, grasp)
    assert free_check.margins[Margin.GRASP].value < -0.2, free_check.summary()


def test_limit_torques_switches_the_torque_limits_on(scenario):
    plant = make_arm_plant(scenario)
    robot = dataclasses.replace(scenario.robot, limit_torques=False)
    assert JointLimits.from_plant(plant, robot).torque is None
    assert JointLimits.from_plant(plant, robot, torque=True).torque is not None


@pytest.mark.slow
def test_simulated_transport_keeps_the_notebook_on_the_cup(scenario):
    notebook_only = dataclasses.replace(scenario, objects=[scenario.object("notebook")])
    result = run_cycle(notebook_only, OnlineMotions(notebook_only, seed=0))
    (record,) = result.records
    assert record.max_slip_translation < 2e-3
    assert record.max_slip_rotation < np.radians(2.0)
    assert record.placement_translation < 10e-3
