"""The batched serial-chain kinematics against Drake's, and the retimer on both.

Each arm's object-wrench coefficients from :mod:`rt_drake.dynamics.chain` equal
Drake's Jacobian-and-bias route (:func:`path_wrench_coefficients`) on random
paths: the Denso arm, the UR5e, and an arm on a turntable (a 7-joint chain).
The retimer, given the chain, returns what it returns with Drake's route
(plants with joints outside the cup's chain: ``tests/test_cup_frame.py``).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from plant_helpers import add_turntable
from pydrake.math import RigidTransform, RollPitchYaw
from pydrake.multibody.plant import MultibodyPlant

from rt_drake import CupFrame, GraspConstraint, HeldObject, JointLimits, retime
from rt_drake.dynamics.wrench import path_wrench_coefficients
from rt_drake.model.held import held_object_of
from rt_drake.model.parser import make_parser
from rt_drake.model.plant import make_arm_plant
from rt_drake.model.resources import scenarios_dir
from rt_drake.model.scenario import load_scenario

HOME = np.array([0.0, 0.35, 1.75, 0.0, 1.04, 0.0])


def arm_on_turntable() -> MultibodyPlant:
    """The Denso arm and tool mounted off-centre on a tilted turntable joint."""
    plant = MultibodyPlant(0.0)
    table = add_turntable(plant, [0.1, 0.0, 1.0])
    parser = make_parser(plant)
    (arm,) = parser.AddModels(url="package://rt_drake/robot/vs060.urdf")
    X_TB = RigidTransform(RollPitchYaw(0.0, 0.0, 0.3), [0.2, -0.1, 0.05])
    plant.WeldFrames(table.body_frame(), plant.GetFrameByName("base_link", arm), X_TB)
    (tool,) = parser.AddModels(url="package://rt_drake/tool/suction_tool.urdf")
    plant.WeldFrames(
        plant.GetFrameByName("link6", arm), plant.GetFrameByName("tool", tool)
    )
    plant.Finalize()
    return plant


def _scenario_plant(name: str) -> MultibodyPlant:
    return make_arm_plant(load_scenario(scenarios_dir() / f"{name}.yaml"))


PLANTS = {
    "denso": lambda: _scenario_plant("stack_four_objects"),
    "ur5e": lambda: _scenario_plant("ur5e_transport"),
    "turntable under the arm": arm_on_turntable,
}


@pytest.fixture(scope="module")
def notebook():
    scenario = load_scenario(scenarios_dir() / "stack_four_objects.yaml")
    return scenario.object("notebook"), scenario.cup


@pytest.mark.parametrize("name", sorted(PLANTS))
def test_batched_wrench_coefficients_equal_drakes(name):
    """Random paths and a random object (centre of mass off the cup axis)."""
    plant = PLANTS[name]()
    cup = CupFrame.of(plant)
    assert cup.chain is not None and cup.chain.num_joints == plant.num_positions()
    rng = np.random.default_rng(7)
    root = rng.normal(size=(3, 3))
    held = HeldObject(
        mass=rng.uniform(0.2, 2.0),
        p_CoScm_C=rng.uniform(-0.05, 0.05, 3) + [0.0, 0.0, 0.04],
        I_Scm_C=root @ root.T * 1e-3 + 1e-3 * np.eye(3),
    )
    n = plant.num_positions()
    q = rng.uniform(-2.5, 2.5, (40, n))
    dq, ddq = rng.normal(0.0, 1.5, (40, n)), rng.normal(0.0, 4.0, (40, n))
    drake = path_wrench_coefficients(plant, held, q, dq, ddq, cup=cup)
    batched = cup.chain.wrench_coefficients(held, q, dq, ddq)
    for mine, theirs in zip(batched, drake, strict=True):
        scale = np.abs(theirs).max(axis=0)
        assert np.all(np.abs(mine - theirs) <= 1e-9 * scale), np.abs(mine - theirs)


def test_retime_on_the_chain_equals_retime_on_drakes_route(notebook):
    """The same path retimed with the chain and with Drake's per-point route."""
    obj, cup_config = notebook
    plant = _scenario_plant("stack_four_objects")
    held = held_object_of(obj)
    grasp = GraspConstraint.for_cup(held, cup_config)
    limits = JointLimits.from_plant(plant)
    path = np.array(
        [
            HOME,
            HOME + [0.2, -0.25, -0.3, 0, 0.35, 0.2],
            HOME + [1.3, -0.25, -0.3, 0, 0.35, 0.9],
            HOME + [1.5, 0.05, 0.1, 0, -0.15, 1.1],
        ]
    )
    cup = CupFrame.of(plant)
    assert cup.chain is not None
    batched = retime(plant, path, limits, grasp, 40, cup=cup)
    drake = retime(
        plant, path, limits, grasp, 40, cup=dataclasses.replace(cup, chain=None)
    )
    assert batched.duration == pytest.approx(drake.duration, rel=1e-9)
    np.testing.assert_allclose(batched.gridpoints, drake.gridpoints, rtol=1e-12)
    np.testing.assert_allclose(batched.sd, drake.sd, rtol=1e-9, atol=1e-12)
