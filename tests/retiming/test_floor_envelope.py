"""The jerk-limited floor with bounded end states against Ruckig and the retimer.

Ruckig (time-optimal, jerk-limited, one joint between given states) is the
independent reference: from any state inside the floor's start and end sets
it needs at least the floor, and where the floor says it is exact (a long
move from rest, one end free) it needs no more. The retimer's jerk-limited
motions between rest configurations take at least the floor too.
"""

from __future__ import annotations

import numpy as np
import pytest
from ruckig import InputParameter, Result, Ruckig
from ruckig import Trajectory as RuckigTrajectory

from rt_drake.retiming import JointLimits, joint_floor, rest_to_rest_jerk, retime

#: One joint like this arm's J1: v, a, and the jerk that reaches a in 50 ms.
V, A, J = 3.93, 19.7, 394.7


def ruckig_time(
    d: float, start: tuple[float, float], end: tuple[float, float]
) -> float:
    """Ruckig's least time (s) from ``(0, *start)`` to ``(d, *end)``, (v, a)."""
    setup = InputParameter(1)
    setup.current_position, setup.target_position = [0.0], [d]
    setup.current_velocity, setup.current_acceleration = [start[0]], [start[1]]
    setup.target_velocity, setup.target_acceleration = [end[0]], [end[1]]
    setup.max_velocity, setup.max_acceleration, setup.max_jerk = [V], [A], [J]
    trajectory = RuckigTrajectory(1)
    assert Ruckig(1).calculate(setup, trajectory) in (Result.Working, Result.Finished)
    return trajectory.duration


def reachable(v: float, a: float, side: int) -> bool:
    """Whether ``(v, a)`` can start (side 1) or end (-1) a motion under V."""
    return v + max(side * a, 0.0) ** 2 / (2 * J) <= V


def floor(d: float, start, end) -> float:  # noqa: ANN001
    """The joint's floor: ``start``, ``end`` = (largest speed, acceleration)."""
    limits = JointLimits(np.array([V]), np.array([A]))
    (u0, a0), (u1, a1) = start, end
    return joint_floor(np.array([d]), limits, u0, u1, np.array([J]), a0, a1).item()


def test_from_rest_to_rest_the_floor_is_the_double_s():
    """Long moves (the cruise reached): exact; short ones: below, within 10 %."""
    for d in (1.5, 1.0, 0.5, 0.1, 0.01):
        reference = ruckig_time(d, (0.0, 0.0), (0.0, 0.0))
        assert rest_to_rest_jerk(np.array(d), V, A, J).item() == pytest.approx(
            reference, rel=1e-9
        )
        assert floor(d, (0.0, 0.0), (0.0, 0.0)) == pytest.approx(reference, rel=1e-9)
        bound = floor(d, (0.0, 0.0), (1e-6, 1e-6))  # the envelope alone
        assert 0.9 * reference <= bound <= reference * (1 + 1e-9)
        if d >= 1.0:
            assert bound == pytest.approx(reference, rel=1e-6)


@pytest.mark.parametrize("d", [1.5, 0.3])
def test_from_rest_to_a_free_end_the_floor_is_the_fastest_motion(d):
    """The greedy profile ends at full speed with no acceleration when the
    move is long (d = 1.5): Ruckig to that state takes the floor. Shorter,
    its end state is unknown here: every end Ruckig reaches takes longer."""
    free = (np.inf, np.inf)
    bound = floor(d, (0.0, 0.0), free)
    ramp = A / J + V / A  # the double-S's ramp to V, its lost distance V ramp / 2
    if d >= V * ramp:
        assert bound == pytest.approx(d / V + ramp / 2, rel=1e-9)
        assert ruckig_time(d, (0.0, 0.0), (V, 0.0)) == pytest.approx(bound, rel=1e-6)
    ends = [(v, a) for v in np.linspace(0.0, V, 7) for a in np.linspace(-A, A, 7)]
    times = [ruckig_time(d, (0.0, 0.0), end) for end in ends if reachable(*end, -1)]
    assert min(times) >= bound * (1 - 1e-9)
    assert min(times) <= 1.05 * bound  # a grid of ends comes close


def test_no_motion_from_inside_the_end_sets_beats_the_floor():
    """Random bounds and random states inside them (velocity possibly away
    from the goal), 120 cases: Ruckig's time is never below the floor."""
    rng = np.random.default_rng(7)
    closest = np.inf
    for _ in range(120):
        d = rng.choice([rng.uniform(0.0, 0.05), rng.uniform(0.05, 2.0)])
        u0, u1 = rng.uniform(0.0, V, 2) * rng.choice([0.0, 0.01, 1.0], 2)
        a0, a1 = rng.uniform(0.0, A, 2) * rng.choice([0.0, 0.01, 1.0], 2)
        bound = floor(d, (u0, a0), (u1, a1))
        # states in the sets: v <= u toward the goal, a <= a0, braking <= a1
        start = (rng.uniform(-0.2 * V, u0), rng.uniform(-A, a0))
        end = (rng.uniform(-0.2 * V, u1), rng.uniform(-a1, A))
        if not (reachable(*start, 1) and reachable(*end, -1)):
            continue  # no motion starts or ends there without exceeding V
        reference = ruckig_time(d, start, end)
        assert reference >= bound * (1 - 1e-9), (d, start, end, bound, reference)
        closest = min(closest, reference / bound)
    assert closest < 1.1  # some cases come close: the bound is not idle


def test_a_joint_nearly_at_rest_at_both_ends_loses_little():
    """J1 at the top of a vertical line: 1e-4 rad/s and 0.01 rad/s^2 at most
    (the cycle's carry, 1.5 rad): within 0.1 % of rest to rest."""
    near = (1e-4, 1e-2)
    reference = ruckig_time(1.5, (0.0, 0.0), (0.0, 0.0))
    bound = floor(1.5, near, near)
    assert reference * 0.999 <= bound <= reference
    assert ruckig_time(1.5, near, (near[0], -near[1])) >= bound


@pytest.mark.parametrize("joint", [0, 2, 4])
def test_a_jerk_limited_retime_takes_at_least_the_floor(plant, scenario, joint):
    """A straight line in joint space between two rest configurations, one
    joint moving far, the others little, retimed under the jerk limits: it
    takes at least the floor of its ends with the jerk (above the floor
    without it), and the retimer comes within a few percent of it."""
    plain = JointLimits.from_plant(plant, scenario.robot)
    limits = JointLimits(
        plain.velocity, plain.acceleration, jerk=20 * plain.acceleration
    )
    rng = np.random.default_rng(joint)
    home = np.array([0.0, 0.35, 1.75, 0.0, 1.04, 0.0])
    step = rng.uniform(-0.05, 0.05, 6)
    step[joint] = -0.9  # joint 5 from 1.04 rad: its limit is 1.66
    waypoints = home + np.linspace(0.0, 1.0, 5)[:, None] * step
    duration = retime(plant, waypoints, limits).duration
    with_jerk = joint_floor(step, plain, 0.0, 0.0, limits.jerk).max()
    without = joint_floor(step, plain, 0.0, 0.0).max()
    assert duration >= with_jerk > without
    assert duration <= 1.05 * with_jerk
