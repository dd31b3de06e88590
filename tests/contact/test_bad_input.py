"""The Drake-free contact layer refuses bad values with typed one-line errors."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from rt_drake.contact import (
    CupParameters,
    WrenchPolytope,
    cached_wrench_polytope,
    guided_approximation,
    is_realizable,
    object_wrench_sampler,
)
from rt_drake.contact._cup import PARAMETER_RANGES
from rt_drake.contact.wrench_polytope import check_polytope
from rt_drake.errors import InputError


@pytest.fixture(scope="module")
def W():
    return cached_wrench_polytope(CupParameters(points=4), use_cache=False)


@pytest.mark.parametrize(
    "field,value",
    [
        ("radius", 1e-300),
        ("radius", 1e300),
        ("radius", 0.0),
        ("friction", 1e300),
        ("friction", -0.1),
        ("suction_force", 1e-300),
        ("suction_force", 1e300),
        ("max_normal_force", 0.0),
        ("max_normal_force", 1e300),
        ("points", 2),
        ("points", 100_000),
        ("sides", 10**6),
    ],
)
def test_each_cup_parameter_has_a_physical_range(field, value):
    with pytest.raises(InputError) as info:
        CupParameters(**{field: value})
    message = str(info.value)
    assert message.startswith(f"cup {field} must be in [") and repr(value) in message


def test_the_range_edges_are_accepted():
    for field, (low, high) in PARAMETER_RANGES.items():
        CupParameters(**{field: low})
        CupParameters(**{field: high})


@pytest.mark.parametrize(
    "wrench,words",
    [
        (np.full(6, np.nan), ["wrenches must be a (..., 6) array of finite", "nan"]),
        ([0, 0, 0, 0, 0, np.inf], ["finite", "inf"]),
        (np.zeros(5), ["wrenches", "(..., 6)", "shape (5,)"]),
    ],
)
def test_is_realizable_refuses_what_it_cannot_answer(W, wrench, words):
    with pytest.raises(InputError) as info:
        is_realizable(wrench, W.F, W.g)
    for word in words:
        assert word in str(info.value)


def test_is_realizable_refuses_a_corrupted_h_representation(W):
    F = W.F.copy()
    F[3] = 0.0  # 0 <= g accepts every wrench: not a constraint
    with pytest.raises(InputError, match="is_realizable: F row 3 is zero"):
        is_realizable(np.zeros(6), F, W.g)
    F[3, 0] = np.nan
    with pytest.raises(
        InputError, match=r"F must be a \(rows, 6\) array of finite .* nan at \(3, 0\)"
    ):
        is_realizable(np.zeros(6), F, W.g)
    with pytest.raises(InputError, match="g must be a .* finite numbers"):
        is_realizable(np.zeros(6), W.F, np.full_like(W.g, np.nan))
    with pytest.raises(
        InputError, match="tol must be a finite number >= 0, got float nan"
    ):
        is_realizable(np.zeros(6), W.F, W.g, tol=np.nan)


def test_a_polytope_whose_vertices_break_its_rows_is_refused(W):
    check_polytope(W)  # the real one is consistent
    shifted = dataclasses.replace(W, g=W.g - 1.0)
    with pytest.raises(InputError, match="violate their own H-representation"):
        check_polytope(shifted)
    with pytest.raises(InputError, match="vertices .* not finite"):
        check_polytope(
            dataclasses.replace(W, vertices=np.full_like(W.vertices, np.inf))
        )
    assert isinstance(W, WrenchPolytope)


@pytest.mark.parametrize(
    "kwargs,words",
    [
        ({"max_vertices": 10**8}, ["max_vertices must be in [7, 200]"]),
        ({"max_vertices": 12, "sample_count": 10**9}, ["sample_count"]),
        ({"max_vertices": 12, "seed": -1}, ["seed must be an integer >= 0"]),
        ({"max_vertices": 12, "tol": np.nan}, ["tol"]),
    ],
)
def test_the_approximation_refuses_sizes_it_cannot_afford(W, kwargs, words):
    sampler = object_wrench_sampler(mass=0.3)
    with pytest.raises(InputError) as info:
        guided_approximation(W, sampler, **kwargs)
    for word in words:
        assert word in str(info.value)


def test_the_sampler_refuses_a_negative_seed():
    with pytest.raises(InputError, match="seed"):
        object_wrench_sampler(seed=-1)


def test_is_realizable_takes_lists_as_numpy_would(W):
    rng = np.random.default_rng(1)
    wrenches = rng.normal(scale=[0.1, 0.1, 0.02, 3.0, 3.0, 15.0], size=(40, 6))
    expected = np.all(wrenches @ W.F.T <= W.g + 1e-9, axis=1)  # F w <= g
    assert 0 < expected.sum() < len(expected)
    got = is_realizable(wrenches.tolist(), W.F.tolist(), W.g.tolist())
    assert np.array_equal(got, expected)


@pytest.mark.parametrize("cup", [None, "paper cup", {"radius": 0.0125}])
def test_the_exact_polytope_of_something_not_a_cup_is_refused(cup):
    from rt_drake.contact import contact_wrench_polytope

    with pytest.raises(InputError) as info:
        contact_wrench_polytope(cup)
    message = str(info.value)
    assert message.startswith("contact_wrench_polytope: cup must be a CupParameters")
    assert type(cup).__name__ in message or "None" in message
