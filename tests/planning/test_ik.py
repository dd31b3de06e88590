"""CupIk: one program, re-used, solves as a program built afresh per pose."""

from __future__ import annotations

import numpy as np
from pydrake.multibody.inverse_kinematics import InverseKinematics
from pydrake.solvers import SnoptSolver, SolverOptions

from rt_drake.model.plant import CUP_FRAME
from rt_drake.planning._ik import (
    _POINTS_C,
    OPTIMALITY_TOLERANCE,
    TOLERANCE,
    CupIk,
)


def fresh_solve(plant, X_WC, q_near, q_guess):
    """Drake's InverseKinematics built for this pose alone (the reference)."""
    context = plant.CreateDefaultContext()
    ik = InverseKinematics(plant, context, with_joint_limits=True)
    cup, world = plant.GetFrameByName(CUP_FRAME), plant.world_frame()
    for p_CP in _POINTS_C:
        p_WP = X_WC.multiply(p_CP)
        ik.AddPositionConstraint(cup, p_CP, world, p_WP - TOLERANCE, p_WP + TOLERANCE)
    prog = ik.prog()
    prog.AddQuadraticErrorCost(np.eye(len(q_near)), q_near, ik.q())
    prog.SetInitialGuess(ik.q(), q_guess)
    options = SolverOptions()
    options.SetOption(
        SnoptSolver.id(), "Major optimality tolerance", OPTIMALITY_TOLERANCE
    )
    result = SnoptSolver().Solve(prog, None, options)
    return result.GetSolution(ik.q()) if result.is_success() else None


def test_reused_program_gives_the_fresh_programs_solutions(plant):
    cup_ik = CupIk(plant, plant.GetFrameByName(CUP_FRAME))
    context = plant.CreateDefaultContext()
    lower, upper = plant.GetPositionLowerLimits(), plant.GetPositionUpperLimits()
    rng = np.random.default_rng(7)
    solved = 0
    for _ in range(12):
        # A reachable pose (from a random q), sought from a nearby q.
        q_true = rng.uniform(0.8 * lower, 0.8 * upper)
        plant.SetPositions(context, q_true)
        X_WC = plant.GetFrameByName(CUP_FRAME).CalcPoseInWorld(context)
        q_near = q_true + rng.normal(0.0, 0.3, q_true.shape)
        expected = fresh_solve(plant, X_WC, q_near, q_near)
        got = cup_ik.solve(X_WC, q_near, q_near)
        if expected is None:
            assert got is None
            continue
        assert got is not None
        solved += 1
        np.testing.assert_allclose(got, expected, atol=1e-9)
    assert solved >= 8
