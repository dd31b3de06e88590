"""Batched cup kinematics of the MOVE optimiser against Drake."""

from __future__ import annotations

import numpy as np

from rt_drake import CupFrame, HeldObject
from rt_drake.dynamics import path_wrench_coefficients
from rt_drake.planning.shape.kinematics import CupChain


def test_batched_wrench_coefficients_match_drake(scenario, plant):
    cup = CupFrame.of(plant)
    chain = CupChain(plant, cup)
    held = HeldObject.from_scenario_object(scenario.objects[0])
    rng = np.random.default_rng(1)
    q, dq, ddq = (rng.uniform(-1.5, 1.5, (9, 6)) for _ in range(3))
    expected = path_wrench_coefficients(plant, held, q, dq, ddq, cup=cup)
    mine_all = chain.wrench_coefficients(held, q, dq, ddq)
    for mine, drake in zip(mine_all, expected, strict=True):
        np.testing.assert_allclose(mine, drake, atol=1e-12)


def test_cup_pose_matches_drake(plant):
    cup = CupFrame.of(plant)
    chain = CupChain(plant, cup)
    context = plant.CreateDefaultContext()
    rng = np.random.default_rng(2)
    for q in rng.uniform(-1.5, 1.5, (5, 6)):
        R, p = chain.cup_pose(q)
        plant.SetPositions(context, q)
        X = cup.frame.CalcPoseInWorld(context)
        np.testing.assert_allclose(R, X.rotation().matrix(), atol=1e-12)
        np.testing.assert_allclose(p, X.translation(), atol=1e-12)


def test_tilt_is_the_angle_of_the_cup_axis_to_gravity(plant):
    chain = CupChain(plant, CupFrame.of(plant))
    context = plant.CreateDefaultContext()
    rng = np.random.default_rng(3)
    q = rng.uniform(-1.5, 1.5, (7, 6))
    tilt = chain.tilt(q)
    frame = CupFrame.of(plant).frame
    for k in range(7):
        plant.SetPositions(context, q[k])
        z_W = frame.CalcPoseInWorld(context).rotation().col(2)
        np.testing.assert_allclose(tilt[k], np.arccos(-z_W[2]), atol=1e-9)
