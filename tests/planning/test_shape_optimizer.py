"""The MOVE path optimiser (issue 13): properties of its paths and its parts.

Optimised MOVEs of random transports (planner and CMA-ES seeded, the search
bounded by a number of paths, not by time, so results do not depend on the
machine) are checked independently of the optimiser's own certification:
collisions by the checker every 1 mm of cup travel with the load attached,
the ends and the vertical segments and the tilt by Drake's forward
kinematics, durations by the retimer.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from pydrake.common.schema import Transform
from pydrake.math import RigidTransform

from rt_drake import (
    CyclePlanner,
    GeometricPath,
    GraspConstraint,
    JointLimits,
    PlannedPath,
    cached_wrench_polytope,
    load_scenario,
    make_arm_plant,
    retime,
)
from rt_drake.model.held import held_object_of
from rt_drake.planning import PlanTiming, sample_transports
from rt_drake.shaping import (
    MoveOptimizer,
    MoveOptimizerOptions,
    optimize_move,
    retime_adaptive,
    warm_up,
)
from rt_drake.types.phase import Phase

CUP_STEP = 1e-3  # m
OPTIONS = MoveOptimizerOptions(max_evaluations=80, max_tilt_deg=30.0)


@dataclasses.dataclass
class Setup:
    scenario: object
    planner: CyclePlanner
    plant: object
    limits: JointLimits
    name: str


@pytest.fixture(scope="module")
def setup(scenario_paths) -> Setup:
    warm_up()
    scenario = load_scenario(scenario_paths["random_transport"])
    plant = make_arm_plant(scenario)
    return Setup(
        scenario,
        CyclePlanner(scenario, seed=5),
        plant,
        JointLimits.from_plant(plant, scenario.robot),
        scenario.random_transport.object,
    )


def grasp_for(setup: Setup, X_OC: RigidTransform) -> GraspConstraint:
    obj = dataclasses.replace(setup.scenario.object(setup.name), grasp=Transform(X_OC))
    polytope = cached_wrench_polytope(setup.scenario.cup)
    return GraspConstraint(held_object_of(obj), polytope.F, polytope.g)


def reach(setup: Setup, X_start) -> PlannedPath:
    """APPROACH and REACH from home to the object at X_start."""
    planner, name = setup.planner, setup.name
    planner.set_object_pose(name, X_start)
    approach = planner.plan_approach(planner.q_home, name)
    return planner.plan_reach(approach.q_goal, name)


def plan(setup: Setup, X_start, X_goal) -> tuple[np.ndarray, PlannedPath]:
    reached = reach(setup, X_start)
    q_grasp = reached.q_goal
    return q_grasp, setup.planner.plan_move(q_grasp, setup.name, X_goal, reach=reached)


@pytest.fixture(scope="module")
def moves(setup):
    """Three optimised MOVEs (max tilt 30 deg) and one kept vertical."""
    out = []
    transports = sample_transports(setup.scenario, 3, seed=11)
    for index, (X_start, X_goal) in enumerate(transports):
        q_grasp, spline = plan(setup, X_start, X_goal)
        grasp = grasp_for(setup, spline.X_OC)
        options = OPTIONS
        if index == 2:
            options = dataclasses.replace(OPTIONS, max_tilt_deg=0.0)
        result = optimize_move(
            setup.planner, setup.plant, q_grasp, setup.name, grasp, setup.limits,
            options, X_goal, spline=spline,
        )  # fmt: skip
        out.append((q_grasp, spline, grasp, options, result))
    return out


def cup_poses(planner: CyclePlanner, q: np.ndarray) -> list[RigidTransform]:
    return [planner.scene.cup_pose(qk) for qk in q]


def travel_samples(planner: CyclePlanner, path: GeometricPath) -> np.ndarray:
    """Configurations along path, the cup (Drake FK) moving <= 1 mm between them."""
    s = np.linspace(0.0, 1.0, 2001)
    while True:
        q = path.value(s)
        p = np.array([X.translation() for X in cup_poses(planner, q)])
        steps = np.linalg.norm(np.diff(p, axis=0), axis=1)
        if steps.max() <= CUP_STEP:
            return q
        length = np.concatenate([[0.0], np.cumsum(steps)])
        count = int(2 * np.ceil(length[-1] / CUP_STEP)) + len(s)
        s = np.interp(np.linspace(0.0, length[-1], count), length, s)


def tilt_deg(planner: CyclePlanner, q: np.ndarray) -> np.ndarray:
    z = np.array([X.rotation().col(2) for X in cup_poses(planner, q)])
    return np.degrees(np.arccos(np.clip(-z[:, 2], -1.0, 1.0)))


@pytest.mark.slow
def test_optimiser_shortens_these_moves(moves):
    assert sum(result.improved for *_, result in moves) >= 2


@pytest.mark.slow
def test_path_is_collision_free_with_the_load(setup, moves):
    planner = setup.planner
    for q_grasp, spline, _, _, result in moves:
        planner.prepare(Phase.MOVE, setup.name, q_grasp, spline.X_OC)
        samples = travel_samples(planner, result.path)
        assert all(planner.scene.within_limits(q) for q in samples)
        assert all(planner.scene.is_free(q) for q in samples[1:-1])


@pytest.mark.slow
def test_path_starts_at_grasp_and_ends_at_place(moves):
    for q_grasp, spline, _, _, result in moves:
        np.testing.assert_array_equal(result.path.waypoints[0], q_grasp)
        np.testing.assert_array_equal(result.path.waypoints[-1], spline.q_goal)


@pytest.mark.slow
def test_end_segments_are_vertical(setup, moves):
    """The cup drifts < 1 mm sideways over the first and last 3 cm of height."""
    planner = setup.planner
    for *_, options, result in moves:
        if not result.improved:
            continue
        s = np.linspace(0.0, 1.0, 20001)
        q = result.path.value(s)
        p = np.array([X.translation() for X in cup_poses(planner, q)])
        for end, ends in ((p[0], slice(None)), (p[-1], slice(None, None, -1))):
            height = p[ends, 2] - end[2]
            rising = np.argmax(height >= options.vertical_height - 1e-6)
            segment = p[ends][: rising + 1]
            drift = np.linalg.norm(segment[:, :2] - end[:2], axis=1).max()
            assert drift < 1e-3


@pytest.mark.slow
def test_never_longer_than_the_spline_path(setup, moves):
    for _, spline, grasp, options, result in moves:
        assert result.duration <= result.spline_duration
        again = retime_adaptive(
            setup.plant, spline.path, setup.limits, grasp, options.final_gridpoints
        )
        assert again.duration == pytest.approx(result.spline_duration, rel=1e-12)
        mine = retime_adaptive(
            setup.plant, result.path, setup.limits, grasp, options.final_gridpoints
        )
        assert mine.duration == pytest.approx(result.duration, rel=1e-12)


@pytest.mark.slow
def test_tilt_stays_within_the_bound(setup, moves):
    for *_, options, result in moves:
        tilt = tilt_deg(setup.planner, result.path.value(np.linspace(0, 1, 3001)))
        bound = max(options.max_tilt_deg, 0.5)
        assert tilt.max() <= bound + 1e-6
        assert result.max_tilt_deg == pytest.approx(tilt.max(), abs=0.05)


@pytest.mark.slow
def test_zero_tilt_keeps_the_cup_vertical(setup, moves):
    *_, options, result = moves[2]
    assert options.max_tilt_deg == 0.0
    tilt = tilt_deg(setup.planner, result.path.value(np.linspace(0, 1, 3001)))
    assert tilt.max() <= 0.5


@pytest.mark.slow
def test_discretization_loss_at_most_half_a_percent(setup, moves):
    """The adaptive 400-point retime within 0.5 % of 1000 uniform points."""
    for _, spline, grasp, options, result in moves:
        for path in (spline.path, result.path):
            adaptive = retime_adaptive(
                setup.plant, path, setup.limits, grasp, options.final_gridpoints
            )
            fine = retime(setup.plant, path, setup.limits, grasp, 1000)
            assert adaptive.duration <= 1.005 * fine.duration


@pytest.mark.slow
def test_no_faster_path_returns_the_spline_path(setup):
    """A 6 cm vertical lift: the straight spline cannot be beaten."""
    planner, name = setup.planner, setup.name
    X_start, _ = sample_transports(setup.scenario, 1, seed=11)[0]
    grasped = reach(setup, X_start)
    q_grasp = grasped.q_goal
    X_WC = planner.scene.cup_pose(q_grasp)
    line = [q_grasp]
    for height in np.linspace(0.01, 0.06, 6):
        target = RigidTransform([0.0, 0.0, height]) @ X_WC
        line.append(planner.ik.solve(target, line[-1], line[-1]))
    straight = PlannedPath(
        Phase.MOVE, name, GeometricPath.from_waypoints(np.array(line)), np.array(line),
        grasped.X_OC, PlanTiming(check_s=0.02),
    )  # fmt: skip
    result = optimize_move(
        planner, setup.plant, q_grasp, name, grasp_for(setup, grasped.X_OC),
        setup.limits, OPTIONS, spline=straight,
    )  # fmt: skip
    assert not result.improved
    assert result.path is straight.path
    assert result.duration == result.spline_duration


def test_search_grid_is_at_equal_steps_of_the_spline_paths_time(setup, moves):
    """The search's grid points are reached at equal times by the retimed spline.

    The times are read off the retimed trajectory (Drake's q(t), sampled
    every 0.1 ms) at the configurations nearest the path's at the grid
    points, not from the profile's quadrature that places them.
    """
    optimizer = MoveOptimizer(setup.plant, setup.limits, OPTIONS)
    uniform = dataclasses.replace(OPTIONS, search_grid_weight=None)
    for _, spline, _, _, result in moves:
        baseline = result.spline_retimed
        grid = optimizer.search_grid(baseline)
        assert (
            MoveOptimizer(setup.plant, setup.limits, uniform).search_grid(baseline)
            == OPTIONS.search_gridpoints
        )
        assert grid[0] == 0.0 and grid[-1] == 1.0 and np.all(np.diff(grid) > 0.0)
        assert len(grid) == OPTIONS.search_gridpoints
        t = np.arange(0.0, baseline.duration, 1e-4)
        q_t = np.array([baseline.trajectory.value(tk).ravel() for tk in t])
        q_s = spline.path.value(grid)
        nearest = np.argmin(
            np.linalg.norm(q_s[:, None, :] - q_t[None, :, :], axis=2), axis=1
        )
        steps = np.diff(t[nearest])
        expected = baseline.duration / (len(grid) - 1)
        np.testing.assert_allclose(steps, expected, rtol=0.05, atol=2e-4)


def test_kernels_only_take_the_layout_warm_up_compiles(moves):
    """No timed MOVE compiles: every kernel specialisation is C-ordered and writeable.

    numba compiles one specialisation per array layout and writeability;
    ``warm_up`` compiles C-ordered writeable arrays. An F-ordered or read-only
    argument (e.g. a Drake pose matrix, a fancy-indexed column block) would
    compile anew inside the first optimised MOVE of a cycle (seconds of
    planning on the critical path).
    """
    from numba.core import types

    from rt_drake.dynamics import chain_kernels as _chain_kernels
    from rt_drake.shaping._clearance import _clearance
    from rt_drake.shaping._spline import _splines
    from rt_drake.shaping._surrogate import _batch_durations

    warm_up()
    kernels = (
        _chain_kernels.frames,
        _chain_kernels.accelerations,
        _chain_kernels.wrench_terms,
        _splines,
        _batch_durations,
        _clearance,
    )
    for kernel in kernels:
        assert kernel.signatures, kernel
        for signature in kernel.signatures:
            for argument in signature:
                if isinstance(argument, types.Array):
                    assert argument.layout == "C" and argument.mutable, (
                        kernel.py_func.__name__,
                        signature,
                    )


def test_played_keeps_a_path_that_plays_no_slower_than_the_spline(setup, moves):
    """With ``played`` (here: the retimer under the robot's jerk limits at
    100 uniform points, called directly), the returned MOVE's played retime
    is that of its path, and no slower than the spline path's."""
    _, spline, grasp, options, _ = moves[0]
    plant = setup.plant
    jerky = JointLimits.from_plant(plant, setup.scenario.robot, jerk=True)
    assert jerky.jerk is not None  # the shipped scenario sets jerk limits

    def played(path, profile):
        return retime(plant, path, jerky, grasp, gridpoints=100)

    optimizer = MoveOptimizer(plant, setup.limits, options)
    result = optimizer.optimize(setup.planner, spline, grasp, played=played)
    assert result.played is not None and result.spline_played is not None
    reference = retime(plant, spline.path, jerky, grasp, gridpoints=100)
    assert result.spline_played.duration == reference.duration
    kept = retime(plant, result.path, jerky, grasp, gridpoints=100)
    assert result.played.duration == kept.duration
    assert result.improved  # this transport's shaped path also plays faster
    assert result.played.duration < reference.duration


def test_played_that_slows_every_candidate_keeps_the_spline_path(setup, moves):
    """A ``played`` under which every candidate is slower than the spline path
    (candidates at a quarter of the limits: twice the time) must return the
    spline path, though each candidate is faster at the full limits."""
    _, spline, grasp, options, shaped = moves[0]
    assert shaped.improved  # without ``played`` this MOVE is shaped
    plant = setup.plant
    slow = JointLimits(setup.limits.velocity / 4.0, setup.limits.acceleration / 16.0)

    def played(path, profile):
        if path is spline.path:
            return profile
        return retime(plant, path, slow, grasp, gridpoints=100)

    optimizer = MoveOptimizer(plant, setup.limits, options)
    result = optimizer.optimize(setup.planner, spline, grasp, played=played)
    assert not result.improved
    assert result.path is spline.path
    assert result.rejected and all("not shorter" in r for r in result.rejected)
