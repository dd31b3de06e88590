"""Joint paths and grasps the retiming tests share (rad).

``BACK``: a MOVE-like swing from the VS-060's home on which the notebook's
grasp binds (retimed without the grasp, the notebook slips by 20 %:
tests/retiming/test_solve.py). ``OBJECTS``, ``object_grasps`` and
``joint_steps``: the shipped objects' grasps and the random paths of the
retimer's property tests (test_solve.py, test_bunched_knots.py).
"""

from __future__ import annotations

import numpy as np
from hypothesis import strategies as st

from rt_drake.model.held import held_object_of
from rt_drake.retiming import GraspConstraint

#: The VS-060's home configuration (rad), the shipped scenarios' ``robot.home``.
HOME = np.array([0.0, 0.35, 1.75, 0.0, 1.04, 0.0])
BACK = np.array(
    [
        HOME,
        HOME + [-0.4, 0.1, -0.2, 0.0, 0.1, -0.5],
        HOME + [-1.2, -0.1, 0.2, 0, -0.1, -0.8],
    ]
)

#: The shipped scenarios' objects the retiming tests hold under the cup.
OBJECTS = ["notebook", "carton_box", "whetstone_box"]


def object_grasps(scenario) -> dict[str, GraspConstraint]:
    """The grasp constraint of each of ``OBJECTS`` under the scenario's cup."""
    return {
        name: GraspConstraint.for_cup(
            held_object_of(scenario.object(name)), scenario.cup
        )
        for name in OBJECTS
    }


def joint_steps(max_steps: int) -> st.SearchStrategy[list[list[float]]]:
    """1 to ``max_steps`` joint-space steps (6 joints, each in [-0.5, 0.5] rad):
    a random path is ``HOME`` followed by their cumulative sums."""
    joint = st.floats(-0.5, 0.5)
    step = st.lists(joint, min_size=6, max_size=6)
    return st.lists(step, min_size=1, max_size=max_steps)
