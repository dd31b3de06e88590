"""Planning ahead: the same paths as planning each phase in turn, and the clock.

A two-object cycle (the first two boxes of the stacking task) runs with the
sequencer planning ahead; a fresh motion source with the same seed then
plans the same cycle sequentially, without a simulation. Every path must be
identical. The records must add up on the simulated clock of
:mod:`rt_drake.simulation.motion`. Neither depends on the physics (the paths
are planned from planned configurations; the clock runs on the sequencer's
8 ms ticks), so the plant steps 4 ms, a third of the CPU of 1 ms.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from rt_drake.simulation import (
    OnlineMotions,
    PendingMotion,
    StationOptions,
    run_cycle,
)
from rt_drake.simulation.motion import Motion, PhasePart, PlanTimes
from rt_drake.types.phase import Phase

#: A two-object cycle with the planner and retimer: tens of seconds.
pytestmark = pytest.mark.slow


#: s of wall time the second object's pick and MOVE are said to take (their
#: real times replaced): planning its MOVE when the pick starts moving could
#: not hide it; planning it right after the pick, during the first MOVE and
#: DETACH, does.
SLOW_PICK_S, SLOW_MOVE_S = 1.0, 3.0


def _slowed(motion: Motion, plan_s: float) -> Motion:
    """``motion`` said to have taken ``plan_s`` s to plan (its parts alike)."""
    parts = tuple(
        dataclasses.replace(p, times=PlanTimes(plan_s=plan_s / len(motion.parts)))
        for p in motion.parts
    )
    return dataclasses.replace(motion, times=PlanTimes(plan_s=plan_s), parts=parts)


class Recording:
    """A motion source that remembers every motion it handed out, in order.

    The second object's motions are handed out :func:`_slowed`.
    """

    def __init__(self, motions, first):
        self._motions = motions
        self._first = first
        self.log = []

    def pick(self, q_start, obj, retreat):
        motion = self._motions.pick(q_start, obj, retreat)
        self.log.append(("pick", obj.name, motion))
        return motion if obj.name == self._first else _slowed(motion, SLOW_PICK_S)

    def move(self, q_start, obj, pick):
        motion = self._motions.move(q_start, obj, pick)
        self.log.append(("move", obj.name, motion))
        return motion if obj.name == self._first else _slowed(motion, SLOW_MOVE_S)


@pytest.fixture(scope="module")
def two_objects(scenario):
    return dataclasses.replace(scenario, objects=scenario.objects[:2])


@pytest.fixture(scope="module")
def pipelined_run(two_objects):
    source = Recording(OnlineMotions(two_objects, seed=3), two_objects.objects[0].name)
    coarse = StationOptions(time_step=4e-3)  # a divisor of the 8 ms ticks
    result = run_cycle(two_objects, source, options=coarse, max_sim_time=30.0)
    return source.log, result


def test_pipelined_planning_gives_the_paths_of_sequential_planning(
    two_objects, pipelined_run
):
    log, _ = pipelined_run
    sequential = OnlineMotions(two_objects, seed=3)
    q = sequential.q_home
    expected = []
    for index, obj in enumerate(two_objects.objects):
        pick = sequential.pick(q, obj, retreat=index > 0)
        move = sequential.move(pick.q_end, obj, pick)
        expected += [("pick", obj.name, pick), ("move", obj.name, move)]
        q = move.q_end
    assert [(k, n) for k, n, _ in log] == [(k, n) for k, n, _ in expected]
    for (kind, name, got), (_, _, want) in zip(log, expected, strict=True):
        np.testing.assert_array_equal(
            got.planned.path.waypoints, want.planned.path.waypoints, err_msg=kind
        )
        assert got.duration == pytest.approx(want.duration, rel=1e-12), (kind, name)


def test_records_add_up_on_the_simulated_clock(pipelined_run):
    log, result = pipelined_run
    waits = [r.plan_on_critical_path_s for r in result.records]
    assert all(w >= 0.0 for w in waits)
    # The first pick has nothing before it to hide behind: the arm waits for
    # its straight APPROACH (staged), not for the REACH planned behind it.
    first_pick = log[0][2]
    assert first_pick.staged
    approach = first_pick.plan_times(Phase.APPROACH).total_s
    assert result.records[0].plan_wait_s[Phase.APPROACH] == pytest.approx(
        max(approach, first_pick.times.total_s - first_pick.phase_end(Phase.APPROACH))
    )
    assert approach < first_pick.times.total_s
    total = sum(sum(r.exec_s.values()) for r in result.records) + sum(waits)
    # Phases switch on the sequencer's 8 ms ticks; the cycle ends on one.
    assert result.sim_time == pytest.approx(total, abs=0.01)
    # The Table II rows are kept: every phase's plan time was recorded.
    for record in result.records:
        assert set(record.plan_times) == {Phase.APPROACH, Phase.REACH, Phase.MOVE}


def test_the_next_objects_move_is_planned_right_after_its_pick(pipelined_run):
    """The second pick is requested when the first MOVE starts (t0), its MOVE
    as soon as the planner is free: ready at t0 + 1 s + 3 s, so the second
    MOVE waits only for what is left when it is needed; requested when the
    pick starts moving, it would wait about 3 s - pick - ATTACH (~1.1 s)."""
    _, result = pipelined_run
    first, second = result.records
    A, R, M = Phase.APPROACH, Phase.REACH, Phase.MOVE
    t0 = (
        first.plan_wait_s[A]
        + first.exec_s[A]
        + first.exec_s[R]
        + first.exec_s[Phase.ATTACH]
        + first.plan_wait_s[M]
    )
    needed = (
        t0
        + first.exec_s[M]
        + first.exec_s[Phase.DETACH]
        + second.plan_wait_s[A]
        + second.exec_s[A]
        + second.exec_s[R]
        + second.exec_s[Phase.ATTACH]
    )
    ready = t0 + SLOW_PICK_S + SLOW_MOVE_S
    # 8 ms ticks: each phase switch is late by up to one tick
    assert second.plan_wait_s[M] == pytest.approx(max(0.0, ready - needed), abs=0.05)
    late = SLOW_MOVE_S - (
        second.exec_s[A] + second.exec_s[R] + second.exec_s[Phase.ATTACH]
    )
    assert second.plan_wait_s[M] < late - 0.5


def test_a_phase_waits_only_for_what_did_not_fit():
    motion = Motion(trajectory=None, times=PlanTimes(plan_s=0.3, retime_s=0.1))
    pending = PendingMotion(motion, requested_at=2.0)
    assert pending.ready_at == pytest.approx(2.4)
    assert pending.wait_s(needed_at=2.1) == pytest.approx(0.3)
    assert pending.wait_s(needed_at=2.4) == 0.0
    assert pending.wait_s(needed_at=3.5) == 0.0


@pytest.mark.parametrize(("reach_s", "start"), [(0.15, 2.02), (0.9, 2.0 + 0.92 - 0.6)])
def test_a_staged_motion_starts_once_its_first_part_is_ready(reach_s, start):
    """APPROACH ready after 0.02 s and begun at once; REACH planned after it
    (``reach_s``) and begun 0.6 s into the motion: the arm starts at 2.02 s
    unless the REACH would not be ready at its start, then late by as much."""
    parts = (
        PhasePart(Phase.APPROACH, 0.6, PlanTimes(plan_s=0.015, retime_s=0.005)),
        PhasePart(Phase.REACH, 0.75, PlanTimes(plan_s=0.05, retime_s=reach_s - 0.05)),
    )
    times = PlanTimes(plan_s=0.065, retime_s=reach_s - 0.045)
    staged = Motion(trajectory=None, times=times, parts=parts, staged=True)
    pending = PendingMotion(staged, requested_at=2.0)
    assert pending.start_at == pytest.approx(start)
    assert pending.wait_s(needed_at=2.0) == pytest.approx(start - 2.0)
    assert pending.ready_at == pytest.approx(2.0 + 0.02 + reach_s)  # planner busy
    # The same motion not staged: the arm waits for all of it.
    whole = Motion(trajectory=None, times=times, parts=parts)
    assert PendingMotion(whole, 2.0).wait_s(2.0) == pytest.approx(0.02 + reach_s)
