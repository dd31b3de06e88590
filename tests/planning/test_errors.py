"""Planning failures: typed errors naming phase, object and cause."""

from __future__ import annotations

import numpy as np
import pytest
from pydrake.geometry import Box
from pydrake.math import RigidTransform, RotationMatrix

from rt_drake.errors import RtDrakeError
from rt_drake.model.scenario import load_scenario
from rt_drake.planning import (
    CyclePlanner,
    GoalInCollisionError,
    NoPathError,
    PlanningError,
    StartInCollisionError,
    UnreachablePoseError,
)
from rt_drake.types.phase import Phase


@pytest.fixture
def planner(scenario_paths):
    scenario = load_scenario(scenario_paths["random_transport"])
    return CyclePlanner(scenario, seed=0, budget_s=0.5)


def test_errors_are_typed():
    for error in (
        UnreachablePoseError,
        StartInCollisionError,
        GoalInCollisionError,
        NoPathError,
    ):
        assert issubclass(error, PlanningError) and issubclass(error, RtDrakeError)
    error = NoPathError(Phase.MOVE, "notebook", "no path")
    assert (str(error), error.phase, error.object) == (
        "MOVE notebook: no path",
        Phase.MOVE,
        "notebook",
    )


def test_unreachable_object(planner):
    planner.set_object_pose("notebook", RigidTransform([1.5, 0.0, 0.0]))
    with pytest.raises(UnreachablePoseError) as caught:
        planner.plan_approach(planner.q_home, "notebook")
    assert str(caught.value).startswith("APPROACH notebook: approach pose unreachable")
    assert "[1.5, 0.0, 0.213]" in str(caught.value)  # the cup's position (m)


@pytest.mark.parametrize(
    "q, words",
    [
        ([0.0, 1.6, 1.6, 0.0, 0.0, 0.0], "(vs060::link4 with cell::table_obstacle"),
        ([0.0, 0.35, 1.75, 0.0, 1.04, 3.5], "outside the joint limits"),
    ],
)
def test_start_in_collision_or_outside_limits(planner, q, words):
    with pytest.raises(StartInCollisionError) as caught:
        planner.plan_approach(np.array(q), "notebook")
    message = str(caught.value)
    assert message.startswith("APPROACH notebook: start configuration")
    assert words in message


def test_goal_in_collision_names_the_carried_object(planner):
    """A goal inside the table obstacle: every place configuration collides."""
    approach = planner.plan_approach(planner.q_home, "notebook")
    reach = planner.plan_reach(approach.q_goal, "notebook")
    X_goal = RigidTransform(RotationMatrix.MakeZRotation(np.pi), [0.5, 0.0, 0.06])
    with pytest.raises(GoalInCollisionError) as caught:
        planner.plan_move(reach.q_goal, "notebook", X_goal)
    message = str(caught.value)
    assert message.startswith("MOVE notebook: goal configuration in collision (")
    assert "notebook (held) with cell::table_obstacle" in message


def test_move_from_a_configuration_that_does_not_hold_the_object(planner):
    with pytest.raises(
        PlanningError, match="MOVE notebook: start configuration does not hold"
    ):
        planner.plan_move(planner.q_home, "notebook")


def test_no_path_within_the_budget(planner):
    """The notebook caged at its place pose: the tool fits through the lid, the
    notebook does not, so no path exists; the planner gives up with its budget."""
    X_OC = planner.grasps("notebook")[0]
    X_goal = planner.scenario.object("notebook").goal.GetDeterministicValue()
    planner.prepare(Phase.MOVE, "notebook", planner.q_home, X_OC)
    q_place = planner.configuration_for(X_goal @ X_OC, planner.q_home)
    q_above = planner.configuration_for(
        RigidTransform([0, 0, 0.2]) @ X_goal @ X_OC, q_place
    )
    scene = planner.scene
    # Walls 1 cm around the notebook (0.213 x 0.14 x 0.025, yaw 180 deg), a lid
    # 3 cm above its top with a 0.1 m square hole around the cup axis.
    c = X_goal.translation()
    top = c[2] + 0.0125
    half = np.array([0.1065 + 0.01, 0.07 + 0.01])
    z0, z1 = 0.031, top + 0.03
    wall_h = z1 - z0
    boxes = {
        "wall+x": (
            Box(0.01, 2 * half[1] + 0.02, wall_h),
            [half[0] + 0.005, 0, z0 + wall_h / 2],
        ),
        "wall-x": (
            Box(0.01, 2 * half[1] + 0.02, wall_h),
            [-half[0] - 0.005, 0, z0 + wall_h / 2],
        ),
        "wall+y": (
            Box(2 * half[0], 0.01, wall_h),
            [0, half[1] + 0.005, z0 + wall_h / 2],
        ),
        "wall-y": (
            Box(2 * half[0], 0.01, wall_h),
            [0, -half[1] - 0.005, z0 + wall_h / 2],
        ),
    }
    hole = 0.05
    for sign in (1, -1):
        length = half[0] + 0.01 - hole
        boxes[f"lid x{sign}"] = (
            Box(length, 2 * half[1] + 0.02, 0.01),
            [sign * (hole + length / 2), 0, z1 + 0.005],
        )
        width = half[1] + 0.01 - hole
        boxes[f"lid y{sign}"] = (
            Box(2 * hole, width, 0.01),
            [0, sign * (hole + width / 2), z1 + 0.005],
        )
    try:
        for name, (shape, offset) in boxes.items():
            scene.add_obstacle(
                name, shape, RigidTransform(np.array([c[0], c[1], 0]) + offset)
            )
        assert scene.is_free(q_place) and scene.is_free(q_above)
        assert not scene.edge_free(q_above, q_place)  # the notebook hits the lid
        planner.budget_s = 0.3
        with pytest.raises(NoPathError) as caught:
            planner.plan_between(q_above, q_place, "notebook", X_OC)
        assert str(caught.value).startswith(
            "MOVE notebook: no collision-free path found within the 0.3 s budget"
        )
    finally:
        for name in boxes:
            scene.remove_obstacle(name)
    assert scene.edge_free(q_above, q_place)
