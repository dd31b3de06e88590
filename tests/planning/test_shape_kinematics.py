"""Batched cup kinematics of the MOVE optimiser against Drake."""

from __future__ import annotations

import numpy as np

from rt_drake import CupFrame
from rt_drake.dynamics.wrench import path_wrench_coefficients
from rt_drake.model.held import held_object_of
from rt_drake.shaping.cup_chain import CupChain


def test_batched_wrench_coefficients_match_drake(scenario, plant):
    cup = CupFrame.of(plant)
    chain = CupChain(plant, cup)
    held = held_object_of(scenario.objects[0])
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


def test_solve_pose_reaches_drake_poses_and_reports_drake_error(plant):
    """Newton's method reaches cup poses from Drake, for a batch and one pose.

    Targets are Drake's cup poses at configurations 0.1 rad from the seeds;
    the reported error is checked against Drake's pose at the solution, and
    a pose that cannot converge in one step reports a large error.
    """
    cup = CupFrame.of(plant)
    chain = CupChain(plant, cup)
    context = plant.CreateDefaultContext()
    rng = np.random.default_rng(4)
    seeds = rng.uniform(-1.2, 1.2, (3, 4, 6))
    targets = seeds + rng.normal(0.0, 0.1, seeds.shape)
    R_target = np.empty((3, 4, 3, 3))
    p_target = np.empty((3, 4, 3))
    for index in np.ndindex(3, 4):
        plant.SetPositions(context, targets[index])
        X = cup.frame.CalcPoseInWorld(context)
        R_target[index], p_target[index] = X.rotation().matrix(), X.translation()

    def drake_error(q, R, p):
        plant.SetPositions(context, q)
        X = cup.frame.CalcPoseInWorld(context)
        E = R @ X.rotation().matrix().T
        vee = np.array([E[2, 1] - E[1, 2], E[0, 2] - E[2, 0], E[1, 0] - E[0, 1]])
        angle = np.arctan2(np.linalg.norm(vee) / 2.0, (np.trace(E) - 1.0) / 2.0)
        return angle + np.linalg.norm(p - X.translation())

    q, error = chain.solve_pose(R_target, p_target, seeds, iterations=20)
    assert q.shape == seeds.shape and error.shape == (3, 4)
    for index in np.ndindex(3, 4):
        assert error[index] < 1e-10
        assert drake_error(q[index], R_target[index], p_target[index]) < 1e-8
    one, one_error = chain.solve_pose(R_target[0, 0], p_target[0, 0], seeds[0, 0])
    assert one.shape == (6,) and one_error.shape == () and one_error < 1e-10
    assert drake_error(one, R_target[0, 0], p_target[0, 0]) < 1e-8
    _, early = chain.solve_pose(R_target, p_target, seeds, iterations=1)
    for index in np.ndindex(3, 4):
        expected = drake_error(seeds[index], R_target[index], p_target[index])
        np.testing.assert_allclose(early[index], expected, rtol=1e-6)
