"""The planner refuses malformed configurations and poses with typed errors."""

from __future__ import annotations

import numpy as np
import pytest
from pydrake.math import RigidTransform

from rt_drake.errors import InputError
from rt_drake.model.scenario import load_scenario
from rt_drake.planning import CyclePlanner
from rt_drake.planning._planning_errors import (
    PlanningError,
    PlanningInputError,
)
from rt_drake.types.phase import Phase


@pytest.fixture(scope="module")
def planner(scenario_paths):
    return CyclePlanner(load_scenario(scenario_paths["random_transport"]), seed=0)


def test_planning_input_errors_are_planning_and_input_errors():
    assert issubclass(PlanningInputError, PlanningError)
    assert issubclass(PlanningInputError, InputError)


@pytest.mark.parametrize(
    "method,q,words",
    [
        (
            "plan_approach",
            "nan",
            ["APPROACH notebook", "6 finite joint positions", "nan"],
        ),
        (
            "plan_approach",
            np.zeros(3),
            ["APPROACH notebook", "got 3 values [0. 0. 0.]"],
        ),
        ("plan_approach", "text", ["APPROACH notebook", "got 'text'"]),
        ("plan_reach", "nan", ["REACH notebook", "configuration q_approach"]),
        ("plan_move", "inf", ["MOVE notebook", "inf"]),
    ],
)
def test_a_malformed_start_is_refused_not_checked_for_collision(
    planner, method, q, words
):
    if isinstance(q, str) and q in ("nan", "inf"):
        value, q = float(q), planner.q_home.copy()
        q[1] = value
    with pytest.raises(PlanningInputError) as info:
        getattr(planner, method)(q, "notebook")
    for word in words:
        assert word in str(info.value), (word, str(info.value))


def test_a_malformed_goal_or_pose_is_refused(planner):
    goal = planner.q_home.copy()
    goal[4] = np.nan
    with pytest.raises(PlanningInputError, match="configuration q_goal.*nan"):
        planner.plan_between(planner.q_home, goal, "notebook")
    nan_pose = RigidTransform(np.array([np.nan, 0.0, 0.0]))
    with pytest.raises(InputError, match="pose of object 'notebook'"):
        planner.set_object_pose("notebook", nan_pose)
    with pytest.raises(PlanningInputError, match="MOVE notebook: cup pose X_WC"):
        planner.configuration_for(nan_pose, planner.q_home, "notebook", Phase.MOVE)


@pytest.mark.parametrize("budget", [0.0, -5.0, np.nan, np.inf, 1e9])
def test_a_budget_that_is_not_a_sane_time_is_refused(scenario_paths, budget):
    scenario = load_scenario(scenario_paths["random_transport"])
    with pytest.raises(InputError, match="planning budget must be in"):
        CyclePlanner(scenario, budget_s=budget)
