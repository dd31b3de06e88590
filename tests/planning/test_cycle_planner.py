"""Twenty random transports (paper Table I): every planned path is sound.

Each query puts the notebook at a start pose sampled in the bin region and
plans APPROACH (from home), REACH and MOVE to a goal pose sampled on the
destination zone. The final splines are checked independently of the
planner's clearance certificate: sampled so that the cup (Drake FK) moves at
most 1 mm between samples, each sample checked by the collision checker
with the phase's objects (MOVE: the notebook attached to the cup).
"""

from __future__ import annotations

import numpy as np
import pytest

from rt_drake.model.scenario import load_scenario
from rt_drake.planning import CyclePlanner, GeometricPath, sample_transports
from rt_drake.types.phase import Phase

#: Plans twenty transports and checks them at 1 mm of cup travel.
pytestmark = pytest.mark.slow

QUERIES = 20
CUP_STEP = 1e-3  # m


def cup_travel_samples(planner: CyclePlanner, path: GeometricPath) -> np.ndarray:
    """Configurations along ``path`` with the cup moving <= 1 mm between them."""
    plant = planner.scene.plant
    context = plant.CreateDefaultContext()
    cup, world = planner.scene.cup_frame, plant.world_frame()

    def cup_positions(q):
        out = []
        for qk in q:
            plant.SetPositions(context, qk)
            out.append(plant.CalcRelativeTransform(context, world, cup).translation())
        return np.array(out)

    s = np.linspace(0.0, 1.0, 2001)
    while True:
        q = path.value(s)
        steps = np.linalg.norm(np.diff(cup_positions(q), axis=0), axis=1)
        if steps.max() <= CUP_STEP:
            return q
        length = np.concatenate([[0.0], np.cumsum(steps)])
        count = int(2 * np.ceil(length[-1] / CUP_STEP)) + len(s)
        s = np.interp(np.linspace(0.0, length[-1], count), length, s)


@pytest.fixture(scope="module")
def transports(scenario_paths):
    scenario = load_scenario(scenario_paths["random_transport"])
    planner = CyclePlanner(scenario, seed=3)
    name = scenario.random_transport.object
    runs = []
    for X_start, X_goal in sample_transports(scenario, QUERIES, seed=3):
        planner.set_object_pose(name, X_start)
        approach = planner.plan_approach(planner.q_home, name)
        reach = planner.plan_reach(approach.q_goal, name)
        move = planner.plan_move(reach.q_goal, name, X_goal, reach=reach)
        samples = {}
        for plan in (approach, reach, move):
            planner.prepare(plan.phase, name, plan.q_start, plan.X_OC)
            q = cup_travel_samples(planner, plan.path)
            free = planner.scene.checker.CheckConfigsCollisionFree(q)
            samples[plan.phase] = (q, np.asarray(free))
        runs.append((X_start, X_goal, approach, reach, move, samples))
    return planner, runs


def test_every_path_is_collision_free_at_1mm_of_cup_travel(transports):
    _, runs = transports
    for *_, samples in runs:
        for phase, (_, free) in samples.items():
            assert free.all(), f"{phase}: {np.count_nonzero(~free)} colliding samples"


def test_every_path_stays_within_the_joint_limits(transports):
    planner, runs = transports
    for *_, samples in runs:
        for q, _ in samples.values():
            assert np.all(q >= planner.scene.lower) and np.all(q <= planner.scene.upper)


def test_paths_chain_and_end_exactly_at_the_ik_poses(transports):
    """Each phase starts where the last ended; the cup poses are the targets."""
    planner, runs = transports
    scene = planner.scene
    for X_start, X_goal, approach, reach, move, _ in runs:
        for a, b in ((approach, reach), (reach, move)):
            # s = 1 evaluates the last cubic at its interval's end: exact to an ulp.
            np.testing.assert_allclose(a.path.value(1.0), a.q_goal, rtol=0, atol=1e-15)
            np.testing.assert_array_equal(b.path.value(0.0), a.q_goal)
        np.testing.assert_array_equal(approach.path.value(0.0), planner.q_home)
        assert reach.X_OC.IsExactlyEqualTo(move.X_OC)
        targets = {
            "approach": (approach.q_goal, X_start @ move.X_OC, 0.2),
            "grasp": (reach.q_goal, X_start @ move.X_OC, 0.0),
            "place": (move.q_goal, X_goal @ move.X_OC, 0.0),
        }
        for what, (q, X_WC, raised) in targets.items():
            error = scene.cup_pose(q).InvertAndCompose(X_WC)
            expected = np.array([0.0, 0.0, raised])
            offset = scene.cup_pose(q).translation() - X_WC.translation()
            np.testing.assert_allclose(
                offset, expected, atol=1e-5, err_msg=what
            )  # IK: 10 um
            assert error.rotation().ToAngleAxis().angle() < 1e-4, what
        np.testing.assert_allclose(
            move.path.deriv(np.array([0.0, 1.0])), 0.0, atol=1e-12
        )


def test_reach_is_a_straight_vertical_descent(transports):
    planner, runs = transports
    for *_, samples in runs:
        q, _ = samples[Phase.REACH]
        p = np.array([planner.scene.cup_pose(qk).translation() for qk in q[::10]])
        lateral = np.linalg.norm(p[:, :2] - p[-1, :2], axis=1)
        assert lateral.max() < 1e-3
        assert np.all(np.diff(p[:, 2]) <= 1e-9)  # never goes back up


def test_a_query_is_deterministic_for_a_seed(transports, scenario_paths):
    _, runs = transports
    X_start, X_goal, approach, reach, move, _ = runs[0]
    scenario = load_scenario(scenario_paths["random_transport"])
    again = CyclePlanner(scenario, seed=3)
    again.set_object_pose("notebook", X_start)
    a = again.plan_approach(again.q_home, "notebook")
    r = again.plan_reach(a.q_goal, "notebook")
    m = again.plan_move(r.q_goal, "notebook", X_goal, reach=r)
    for first, second in ((approach, a), (reach, r), (move, m)):
        np.testing.assert_array_equal(first.path.waypoints, second.path.waypoints)
