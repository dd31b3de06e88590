"""The straight APPROACH: the checked joint-space line to the approach pose, or None.

The planner's line from home to above the first box of the paper's stack
must be a straight segment in joint space ending at the approach goal the
planner itself solves; with another box put where the cup passes halfway
(the collision checker confirms the hit), there is no straight APPROACH.
"""

from __future__ import annotations

import numpy as np
from pydrake.math import RigidTransform

from rt_drake.planning import CyclePlanner
from rt_drake.types.phase import Phase


def test_the_straight_approach_is_a_line_or_none_when_blocked(scenario):
    planner = CyclePlanner(scenario)
    name, other = scenario.objects[0].name, scenario.objects[1].name
    planned = planner.straight_approach(planner.q_home, name)
    assert planned is not None and planned.phase is Phase.APPROACH
    goal = planner.approach_goal(planner.q_home, name)
    np.testing.assert_array_equal(planned.q_start, planner.q_home)
    np.testing.assert_array_equal(planned.q_goal, goal.q_goal)
    step = goal.q_goal - planner.q_home
    q = planned.path.value(np.linspace(0.0, 1.0, 101))
    share = (q - planner.q_home) @ step / (step @ step)
    np.testing.assert_allclose(q, planner.q_home + np.outer(share, step), atol=1e-12)
    assert share.min() >= -1e-12 and share.max() <= 1.0 + 1e-12
    # A box where the cup passes halfway: the line is blocked.
    q_mid = planned.path.value(0.5)
    X_mid = planner.scene.cup_pose(q_mid)
    planner.set_object_pose(other, RigidTransform(X_mid.translation()))
    assert planner.straight_approach(planner.q_home, name) is None
    assert not planner.scene.is_free(q_mid)
