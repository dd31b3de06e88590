"""The cup model: parameter validation and the grasp matrices G_i."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rt_drake.contact import CupParameters, grasp_matrices
from rt_drake.contact._cup import (
    contact_positions,
    contact_rotations,
    friction_halfspaces,
    friction_pyramid,
)


def test_defaults_are_the_papers_cup():
    cup = CupParameters()
    assert (cup.radius, cup.points, cup.friction, cup.sides) == (0.0125, 6, 0.3, 4)
    assert (cup.suction_force, cup.max_normal_force) == (20.0, 33.3)


@pytest.mark.parametrize(
    "field,value",
    [
        ("radius", 0.0),
        ("radius", -0.01),
        ("radius", math.nan),
        ("points", 2),
        ("points", 3.5),
        ("friction", -0.1),
        ("friction", math.inf),
        ("sides", 2),
        ("suction_force", 0.0),
        ("max_normal_force", -1.0),
        ("max_normal_force", math.nan),
    ],
)
def test_bad_parameter_raises_value_error_naming_it(field, value):
    with pytest.raises(ValueError, match=field) as error:
        CupParameters(**{field: value})
    assert str(value) in str(error.value)


def test_validate_catches_fields_set_after_construction():
    # yaml_load_typed sets fields one by one on a default instance.
    cup = CupParameters()
    cup.friction = -1.0
    with pytest.raises(ValueError, match="friction"):
        cup.validate()


def test_from_vacuum_multiplies_pressure_and_area():
    cup = CupParameters.from_vacuum(50_000.0, 4e-4, friction=0.5)
    assert cup.suction_force == pytest.approx(20.0) and cup.friction == 0.5
    with pytest.raises(ValueError, match="pressure_pa"):
        CupParameters.from_vacuum(-1.0, 4e-4)


@given(
    points=st.integers(3, 10),
    radius=st.floats(1e-3, 0.1),
    force=st.lists(st.floats(-10, 10), min_size=3, max_size=3),
)
@settings(max_examples=30, deadline=None)
def test_grasp_matrix_gives_the_wrench_of_a_point_force(points, radius, force):
    cup = dataclasses.replace(CupParameters(), points=points, radius=radius)
    f_local = np.array(force)
    for G, p, R in zip(
        grasp_matrices(cup), contact_positions(cup), contact_rotations(cup), strict=True
    ):
        f_C = R @ f_local
        expected = np.hstack([np.cross(p, f_C), f_C])
        np.testing.assert_allclose(G @ f_local, expected, atol=1e-12)
        # Pi's x axis points radially outward, its z axis is C's z.
        np.testing.assert_allclose(R[:, 0], p / radius, atol=1e-12)
        np.testing.assert_allclose(R[:, 2], [0.0, 0.0, 1.0])


@given(sides=st.integers(3, 8), friction=st.floats(0.0, 1.5))
@settings(max_examples=30, deadline=None)
def test_pyramid_vertices_and_halfspaces_describe_the_same_cone(sides, friction):
    cup = dataclasses.replace(CupParameters(), sides=sides, friction=friction)
    A, b = friction_halfspaces(cup)
    vertices = friction_pyramid(cup)
    slack = vertices @ A.T - b
    assert slack.max() <= 1e-9
    if friction > 0.0:  # each vertex of the 3-D pyramid is on >= 3 of its facets
        assert np.all(np.sum(np.abs(slack) <= 1e-9, axis=1) >= 3)


def test_four_sided_cone_is_the_l1_diamond():
    cup = CupParameters(friction=0.3, sides=4)
    A, b = friction_halfspaces(cup)
    rng = np.random.default_rng(0)
    forces = rng.uniform([-15, -15, 0], [15, 15, 33.3], size=(2000, 3))
    diamond = np.abs(forces[:, 0]) + np.abs(forces[:, 1]) <= 0.3 * forces[:, 2]
    np.testing.assert_array_equal(np.all(forces @ A.T <= b + 1e-12, axis=1), diamond)
