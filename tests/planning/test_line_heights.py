"""``approach_offset: auto``: every vertical line of the cycle clears the cell
by ``approach_clearance``, and none is longer than it needs.

The reference is independent of the line search: the planner's own collision
checker (``SceneGraphCollisionChecker.CalcRobotClearance``) with the arm put
at the line's top by inverse kinematics and the held object attached to the
cup, where the search uses a separate plant with a free-floating tool.
"""

from __future__ import annotations

import numpy as np
import pytest
from pydrake.math import RigidTransform
from pydrake.planning import RobotCollisionType

from rt_drake.model.scenario import load_scenario
from rt_drake.planning import CyclePlanner
from rt_drake.types.phase import Phase

#: m, what the scenario asks.
CLEARANCE = 0.02


@pytest.fixture(scope="module")
def planner(scenario_paths) -> CyclePlanner:
    scenario = load_scenario(scenario_paths["stack_four_objects"])
    assert scenario.planning.approach_clearance == CLEARANCE
    return CyclePlanner(scenario, seed=0)


def _cycle_lines(planner: CyclePlanner):
    """(name, X_WO at the line's foot, other objects' poses) of every line."""
    poses = {o.name: o.start.GetDeterministicValue() for o in planner.scenario.objects}
    for obj in planner.scenario.objects:
        X_goal = obj.goal.GetDeterministicValue()
        others = {k: v for k, v in poses.items() if k != obj.name}
        yield obj.name, poses[obj.name], others, Phase.APPROACH
        yield obj.name, X_goal, others, Phase.MOVE
        poses[obj.name] = X_goal


def _tool_clearance(planner: CyclePlanner, name, X_WO, others, height) -> float:
    """Smallest distance (m) of the tool and the held object to the cell.

    The arm at the cup pose X_WO X_OC raised by ``height``, by IK; the
    object attached to the cup; the other objects at ``others``.
    """
    scene = planner.scene
    for X_OC in planner.grasps(name):  # the cup (a hexagon of rims) and its flip
        X_WC = RigidTransform([0.0, 0.0, height]) @ X_WO @ X_OC
        q = planner.ik.solve(X_WC, planner.q_home, planner.q_home)
        if q is not None:
            break
    assert q is not None, (name, height)
    scene.attach(name, X_OC.inverse())
    for obj in planner.scenario.objects:
        X = None if obj.name == name else others[obj.name]
        scene.set_object(obj.name, X, obj.model, None, 0.0)
    found = scene.clearance(q, 0.2)
    tool = int(scene.cup_frame.body().index())
    distances = [
        d
        for d, robot, kind in zip(
            found.distances(),
            found.robot_indices(),
            found.collision_types(),
            strict=True,
        )
        if int(robot) == tool and kind == RobotCollisionType.kEnvironmentCollision
    ]
    return min(distances, default=0.2)


def test_every_auto_line_clears_the_cell_and_one_cm_less_does_not(planner):
    heights = []
    for name, X_WO, others, phase in _cycle_lines(planner):
        planner.object_poses = {**others, name: X_WO}
        h = planner.line_height(name, X_WO, phase)
        heights.append(h)
        top = _tool_clearance(planner, name, X_WO, others, h)
        assert top >= CLEARANCE - 1e-6, (name, phase, h, top)
        lower = _tool_clearance(planner, name, X_WO, others, h - 0.01)
        assert lower < CLEARANCE, (name, phase, h, lower)
    # The lines are not all one height: the geometry decides (the notebook and
    # the carton sit in the bin closer to its walls than the clearance).
    assert len(set(np.round(heights, 3))) > 1
    assert max(heights) < 0.26  # shorter than the paper's lines


def test_numeric_offsets_keep_todays_lines(scenario):
    planner = CyclePlanner(scenario, seed=0)
    assert planner._probe is None
    for obj in scenario.objects:
        X_WO = obj.start.GetDeterministicValue()
        assert planner.line_height(obj.name, X_WO, Phase.APPROACH) == (
            obj.approach_offset
        )


def test_no_clear_line_is_a_one_line_planning_error(scenario_paths, monkeypatch):
    from rt_drake.planning import PlanningError, _line_heights

    monkeypatch.setattr(_line_heights, "MAX_HEIGHT", 0.005)  # 5 mm: never clear
    scenario = load_scenario(scenario_paths["stack_four_objects"])
    with pytest.raises(PlanningError) as info:
        CyclePlanner(scenario, seed=0)
    message = str(info.value)
    assert "\n" not in message
    for words in ("whetstone_box", "approach_offset auto", "0.005 m", "0.02 m"):
        assert words in message, message
