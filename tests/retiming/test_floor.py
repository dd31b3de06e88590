"""The floor (issue 27): closed forms against independent solvers.

- Velocity and acceleration: a single joint's move is one straight path in
  joint space, which toppra (an independent TOPP-RA) retimes at the limits:
  its duration equals the closed form (to its grid), and any path between
  the same configurations, retimed by toppra, takes at least the floor.
- Jerk: the double-S closed form against a linear program over
  piecewise-constant jerks (scipy's HiGHS), whose least feasible duration
  (bisection) is at least the continuous optimum and close above it.
"""

from __future__ import annotations

import numpy as np
import pytest
import toppra
import toppra.algorithm
import toppra.constraint
from scipy.optimize import linprog

from rt_drake.retiming import (
    JointLimits,
    RetimeInputError,
    joint_floor,
    junction_accelerations,
    junction_speeds,
    rest_to_rest_jerk,
    segment_floor,
)

LIMITS = JointLimits(
    velocity=np.array([2.0, 1.5, 3.0, 4.0, 3.5, 5.0]),
    acceleration=np.array([6.0, 4.0, 9.0, 12.0, 10.0, 15.0]),
)


def toppra_duration(waypoints: np.ndarray, gridpoints: int = 2000) -> float:
    """Time-optimal duration (s) of the cubic spline through ``waypoints``."""
    s = np.linspace(0.0, 1.0, len(waypoints))
    path = toppra.SplineInterpolator(s, waypoints, bc_type="clamped")
    constraints = [
        toppra.constraint.JointVelocityConstraint(
            np.column_stack([-LIMITS.velocity, LIMITS.velocity])
        ),
        toppra.constraint.JointAccelerationConstraint(
            np.column_stack([-LIMITS.acceleration, LIMITS.acceleration])
        ),
    ]
    grid = np.linspace(0.0, 1.0, gridpoints)
    instance = toppra.algorithm.TOPPRA(constraints, path, gridpoints=grid)
    trajectory = instance.compute_trajectory(0.0, 0.0)
    return float(trajectory.duration)


@pytest.mark.parametrize(("joint", "d"), [(0, 2.5), (1, 0.3), (4, 0.05)])
def test_a_single_joint_move_takes_the_closed_form_time(joint, d):
    """Cruise reached (joint 0), not reached (1, 4): toppra agrees to 0.5 %."""
    q_to = np.zeros(6)
    q_to[joint] = d
    floor = segment_floor(np.zeros(6), q_to, LIMITS, 0.0, 0.0)
    line = np.linspace(np.zeros(6), q_to, 5)
    assert toppra_duration(line) == pytest.approx(floor, rel=5e-3)
    v, a = LIMITS.velocity[joint], LIMITS.acceleration[joint]
    reaches = d >= v * v / a
    assert (joint == 0) == reaches


def test_no_path_between_two_configurations_beats_the_floor():
    rng = np.random.default_rng(3)
    for _ in range(6):
        q_from, q_to = rng.uniform(-1.5, 1.5, (2, 6))
        middle = q_from + (q_to - q_from) * np.linspace(0, 1, 5)[1:-1, None]
        middle += rng.normal(0.0, 0.2, middle.shape)
        path = np.vstack([q_from, middle, q_to])
        floor = segment_floor(q_from, q_to, LIMITS, 0.0, 0.0)
        assert toppra_duration(path, 1000) >= floor * (1 - 1e-3)


def test_a_free_end_is_faster_than_a_stop_and_a_bounded_end_between():
    d = np.array([1.0, 0.2, 0.0, 2.0, 0.5, 0.01])
    both = joint_floor(d, LIMITS, np.zeros(6), np.zeros(6))
    one = joint_floor(d, LIMITS, np.zeros(6), np.full(6, np.inf))
    free = joint_floor(d, LIMITS, np.full(6, np.inf), np.full(6, np.inf))
    half = joint_floor(d, LIMITS, np.zeros(6), 0.5 * LIMITS.velocity)
    assert np.all(free <= one) and np.all(one <= both)
    assert np.all(one <= half + 1e-12) and np.all(half <= both)
    np.testing.assert_allclose(free, d / LIMITS.velocity)


def test_junction_speeds_follow_the_tangent():
    step = np.array([0.0, 0.02, -0.01, 1e-7, 0.0, 0.0])
    displacement = np.array([0.5, 0.3, 0.4, 0.2, -0.1, 0.0])
    u = junction_speeds(step, displacement, LIMITS)
    speed = min(1.5 / 0.02, 3.0 / 0.01, 4.0 / 1e-7)  # the line's fastest lambda
    np.testing.assert_allclose(u, [0.0, 0.02 * speed, 0.0, 1e-7 * speed, 0.0, 0.0])
    assert u[1] == pytest.approx(LIMITS.velocity[1])  # the limiting joint


def lp_jerk_time(d: float, v: float, a: float, j: float, steps: int = 60) -> float:
    """Least T (bisection) with piecewise-constant jerk meeting every limit.

    The acceleration, velocity and position at node i are exact integrals of
    the jerks of the steps k < i (n = i - k steps apart): ``h n``,
    ``h^2 (n - 1/2)`` and ``h^3 (n^2 / 2 - n / 2 + 1 / 6)`` times ``j_k``.
    """
    n = np.arange(1, steps + 1)[:, None] - np.arange(steps)[None, :]
    before = n >= 1

    def feasible(T: float) -> bool:
        h = T / steps
        A = np.where(before, h, 0.0)
        V = np.where(before, h * h * (n - 0.5), 0.0)
        P = np.where(before, h**3 * (n * n / 2 - n / 2 + 1 / 6), 0.0)
        result = linprog(
            np.zeros(steps), A_ub=np.vstack([A, -A, V, -V]),
            b_ub=np.concatenate([np.full(2 * steps, a), np.full(2 * steps, v)]),
            A_eq=np.vstack([A[-1], V[-1], P[-1]]), b_eq=[0.0, 0.0, d],
            bounds=[(-j, j)] * steps, method="highs",
        )  # fmt: skip
        return result.status == 0

    low, high = 0.0, 2.0 * rest_to_rest_jerk(np.array(d), v, a, j).item()
    for _ in range(22):
        middle = 0.5 * (low + high)
        low, high = (low, middle) if feasible(middle) else (middle, high)
    return high


@pytest.mark.parametrize(
    ("d", "v", "a", "j"),
    [(2.0, 1.0, 2.0, 10.0), (0.3, 1.0, 2.0, 10.0), (0.02, 1.0, 2.0, 10.0)],
)  # cruise and acceleration limit reached; acceleration only; jerk only
def test_the_double_s_time_is_the_least_a_jerk_profile_needs(d, v, a, j):
    closed = rest_to_rest_jerk(np.array(d), v, a, j).item()
    lp = lp_jerk_time(d, v, a, j)
    # the LP holds the velocity at its nodes only: a hair below is allowed
    assert closed <= lp * (1 + 1e-3)
    assert lp <= 1.01 * closed
    limits = JointLimits(np.full(6, v), np.full(6, a))
    with_jerk = joint_floor(np.full(6, d), limits, 0.0, 0.0, np.full(6, j))
    without = joint_floor(np.full(6, d), limits, 0.0, 0.0)
    assert np.all(with_jerk >= without) and with_jerk[0] == pytest.approx(closed)
    # one end free: between the bound without jerk and rest to rest; when
    # the cruise is reached, the double-S's ramp to v counts once
    free_end = joint_floor(np.full(6, d), limits, 0.0, np.inf, np.full(6, j))
    assert np.all(free_end >= joint_floor(np.full(6, d), limits, 0.0, np.inf))
    assert np.all(free_end <= with_jerk)
    ramp = a / j + v / a
    if d >= v * ramp:
        np.testing.assert_allclose(free_end, d / v + ramp / 2, rtol=1e-9)


def test_junction_accelerations_bound_every_motion_along_the_line():
    """On ``q(s) = delta s + kappa s^2`` (the junction at s = 0), the largest
    ``|q''_j sdot^2 + q'_j sddot|`` over a dense grid of the path states
    that every joint's velocity and acceleration limits allow stays under
    the bound; a joint constant on the line gets 0."""
    delta = np.array([0.0, 0.8, -0.5, 0.1, 0.3, 0.0])
    kappa = np.array([0.0, 0.2, 0.4, -0.3, 0.0, 0.05])
    h = 0.01
    points = np.array([delta * s + kappa * s * s for s in (-2 * h, -h, 0.0)])
    bound = junction_accelerations(points, LIMITS)
    v, a = LIMITS.velocity, LIMITS.acceleration
    sdot = np.linspace(-1.0, 1.0, 401)[:, None] * np.min(v[1:5] / np.abs(delta[1:5]))
    sddot = np.linspace(-1.0, 1.0, 401)[None, :] * 100.0
    states = [np.abs(2 * kappa[j] * sdot**2 + delta[j] * sddot) for j in range(6)]
    feasible = np.all([(x <= a[j]) for j, x in enumerate(states)], axis=0)
    largest = np.array([x[feasible].max() for x in states])
    assert feasible.sum() > 1000  # and the grid holds every feasible sddot:
    assert not feasible[:, 0].any() and not feasible[:, -1].any()
    assert np.all(largest <= bound + 1e-9)
    assert bound[0] == 0.0 and bound[5] > 0.0
    assert np.all(bound <= a) and np.all(bound[1:5] <= 2.0 * largest[1:5] + 1e-9)


@pytest.mark.parametrize(
    ("kwargs", "word"),
    [({"jerk": np.zeros(6)}, "jerk"), ({"speed_from": -1.0}, "end speeds")],
)
def test_bad_floor_inputs_are_refused_by_name(kwargs, word):
    arguments = {"speed_from": 0.0, "speed_to": 0.0, **kwargs}
    with pytest.raises(RetimeInputError, match=word):
        joint_floor(np.ones(6), LIMITS, **arguments)
