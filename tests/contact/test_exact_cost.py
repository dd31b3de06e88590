"""The exact W_c's cost is estimated before computing; too large is refused."""

from __future__ import annotations

import dataclasses
import sys

import numpy as np
import pytest

from rt_drake.contact import CupParameters, contact_wrench_polytope
from rt_drake.contact._cup import (
    friction_pyramid,
    grasp_matrices,
    suction_wrench,
)
from rt_drake.contact._minkowski import minkowski_sum
from rt_drake.contact.exact_cost import (
    DEFAULT_MAX_MEMORY,
    check_exact_cost,
    exact_cost,
)
from rt_drake.contact.wrench_polytope import rotation_symmetry, wrench_scale
from rt_drake.errors import TooLargeError

#: (points, sides) -> candidate vertex combinations counted in the enumeration
#: (benchmarks/BENCHMARKS.md, "Bad input"): the estimate must stay above them.
MEASURED_CODES = {
    (4, 4): 2_814,
    (6, 4): 56_230,
    (8, 4): 1_086_230,
    (9, 4): 4_817_498,
    (12, 4): 408_499_050,
    (6, 3): 14_923,
    (6, 8): 2_246_594,
    (6, 10): 7_958_722,
    (4, 12): 111_032,
    (3, 32): 116_202,
}


@pytest.mark.parametrize("points,sides", sorted(MEASURED_CODES))
def test_the_estimate_bounds_the_measured_enumeration(points, sides):
    cost = exact_cost(CupParameters(points=points, sides=sides))
    measured = MEASURED_CODES[points, sides]
    assert measured <= cost.vertex_codes <= 2.5 * measured


def test_the_paper_cup_is_cheap_and_the_cost_grows_with_points_and_sides():
    paper = exact_cost(CupParameters())
    assert paper.memory < 0.2 * 2**30 and paper.seconds < 2.0
    for name in ("points", "sides"):
        costs = [
            exact_cost(dataclasses.replace(CupParameters(), **{name: n})).memory
            for n in range(4, 12)
        ]
        assert np.all(np.diff(costs) > 0)
    no_friction = exact_cost(CupParameters(points=1000, friction=0.0))
    assert no_friction.memory < 0.2 * 2**30


@pytest.mark.parametrize(
    "points,sides,words",
    [
        (12, 4, ["12 points and 4 sides", "GB", "largest accepted: 10 points"]),
        (6, 64, ["6 points and 64 sides", "12 sides at 6 points"]),
        (40, 4, ["40 points", "no sides at 40 points"]),
    ],
)
def test_too_large_is_refused_up_front_with_the_estimate(
    points, sides, words, monkeypatch
):
    # Refused, not attempted: the vertex enumeration is never entered (it
    # fails the test if called, wherever contact_wrench_polytope finds it).
    calls = []

    def enumeration_entered(*args, **kwargs):
        calls.append(args)
        raise AssertionError("the enumeration was attempted")

    for module in (contact_wrench_polytope.__module__, minkowski_sum.__module__):
        monkeypatch.setattr(sys.modules[module], "minkowski_sum", enumeration_entered)
    cup = CupParameters(points=points, sides=sides)
    with pytest.raises(TooLargeError) as info:
        contact_wrench_polytope(cup)
    assert calls == []
    message = str(info.value)
    assert "estimated" in message and "limit 4 GB" in message
    for word in words:
        assert word in message, (word, message)


def test_the_limit_is_a_parameter():
    cup = CupParameters(points=9)
    assert exact_cost(cup).memory < DEFAULT_MAX_MEMORY
    with pytest.raises(TooLargeError, match="limit 0.3 GB.*largest accepted: 8 points"):
        check_exact_cost(cup, 0.3 * 2**30)


def test_the_enumeration_counts_before_allocating_the_vertex_candidates():
    # The second guard, exact: set a limit the up-front estimate does not see.
    cup = CupParameters(points=5)
    scale = wrench_scale(cup)
    summands = [(friction_pyramid(cup) @ G.T) * scale for G in grasp_matrices(cup)]
    with pytest.raises(TooLargeError, match="candidate vertex combinations"):
        minkowski_sum(
            summands,
            suction_wrench(cup) * scale,
            symmetry=rotation_symmetry(cup),
            max_memory=1e5,
        )
