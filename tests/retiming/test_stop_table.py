"""rt_drake.retiming: protective stops computed ahead (``stop_table``).

References independent of the stop code: the path spline rebuilt with
scipy, Drake's Newton-Euler wrench and the plant's limits at 1 kHz
(``check_trajectory``), the joint jerk by finite differences of the 1 kHz
samples' accelerations, and the MOVE's own trajectory at each instant.
"""

from __future__ import annotations

import numpy as np
import pytest
from grasp_paths import BACK
from stop_helpers import (
    back_spline,
    jerk_by_differences,
    notebook_fixtures,
)

from rt_drake import stop_table
from rt_drake.retiming import (
    RetimeInputError,
    check_trajectory,
    protective_stop,
)

#: Period of the table (s): coarse, so the test stays cheap.
PERIOD = 0.15


limits, grasp, move = notebook_fixtures(jerk=True)


@pytest.fixture(scope="module")
def table(plant, limits, grasp, move):
    return stop_table(plant, BACK, limits, move, PERIOD, grasp)


def test_the_instants_are_every_period_then_the_end(move, table):
    start, end = move.trajectory.start_time(), move.trajectory.end_time()
    expected = np.append(np.arange(start, end, PERIOD), end)
    np.testing.assert_allclose(table.times, expected, atol=1e-12)
    assert len(table.stops) == len(table.times)
    for t, stop in zip(table.times, table.stops, strict=True):
        assert stop.start_time == pytest.approx(t, abs=1e-12)


def test_every_stop_of_the_table_rests_on_the_path_in_the_grasp_set(
    plant, limits, grasp, table
):
    spline = back_spline()
    moving = 0
    for stop in table.stops:
        whole, end = stop.trajectory, stop.end_time
        for order in (1, 2):
            assert np.abs(whole.EvalDerivative(end, order)).max() < 1e-6
        assert np.allclose(whole.value(end).ravel(), spline(stop.s_stop), atol=1e-9)
        if stop.duration <= 1e-5:
            continue
        moving += 1
        check = check_trajectory(plant, stop.stop, limits, grasp)
        assert check.passed(), check.summary()
        jerk = jerk_by_differences(stop.stop, stop.start_time, end)
        assert np.max(np.abs(jerk) / limits.jerk) <= 1.0 + 1e-3
    assert moving >= 3


def test_a_trip_takes_the_stop_at_the_next_instant_from_the_moves_own_state(
    move, table
):
    rng = np.random.default_rng(0)
    start, end = move.trajectory.start_time(), move.trajectory.end_time()
    for t in [start, end, *rng.uniform(start, end, 6), float(table.times[2])]:
        stop = table.at(t)
        k = int(np.flatnonzero(table.times >= t - 1e-12)[0])
        assert stop is table.stops[k]
        assert t <= stop.start_time < t + PERIOD + 1e-12
        for order in (0, 1, 2):
            np.testing.assert_allclose(
                stop.stop.EvalDerivative(stop.start_time, order),
                move.trajectory.EvalDerivative(stop.start_time, order),
                atol=1e-7,
            )


def test_a_stop_of_the_table_is_as_fast_as_one_computed_alone(
    plant, limits, grasp, move, table
):
    """The table's search starts from the previous instant's stop; alone,
    from a simulated braking's. Where a stop exists is not monotone in the
    distance near the shortest one, so the two can differ by a few per cent
    (up to 4.5 % at 10 ms on bench_stop.py's first path)."""
    for k in (1, 2):
        t = float(table.times[k])
        alone = protective_stop(plant, BACK, limits, move, t, grasp)
        assert table.stops[k].duration == pytest.approx(alone.duration, rel=0.05)


def test_a_trip_outside_the_move_is_refused(table):
    with pytest.raises(RetimeInputError, match=r"stop table: t must be .* got float"):
        table.at(float(table.times[-1]) + 0.01)
