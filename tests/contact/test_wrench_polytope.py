"""The exact contact wrench set W_c: H-rep vs LP, facets, symmetry, limits."""

from __future__ import annotations

import dataclasses
import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rt_drake.contact import (
    CupParameters,
    contact_wrench_polytope,
    is_realizable,
    is_realizable_lp,
    lp_residual,
    with_suction_force,
)
from rt_drake.contact._cup import (
    friction_pyramid,
    grasp_matrices,
    suction_wrench,
)
from rt_drake.contact._minkowski import minkowski_sum
from rt_drake.contact.wrench_polytope import rotation_symmetry, wrench_scale

GRAVITY_W = np.array([0.0, 0.0, -9.81])

small_cups = st.builds(
    CupParameters,
    radius=st.floats(0.005, 0.05),
    points=st.integers(3, 5),
    friction=st.floats(0.05, 1.0),
    sides=st.integers(3, 5),
    suction_force=st.floats(1.0, 50.0),
    max_normal_force=st.floats(1.0, 50.0),
)


@pytest.fixture(scope="module")
def paper() -> object:
    return contact_wrench_polytope(CupParameters())


def _boundary_points(polytope, count: int, delta: float, rng) -> np.ndarray:
    """Points at +/- delta along the normal of random points of random facets."""
    points = []
    for row in rng.integers(len(polytope.F), size=count):
        F_j, g_j = polytope.F[row], polytope.g[row]
        on = polytope.vertices[np.abs(polytope.vertices @ F_j - g_j) <= 1e-9]
        x = rng.dirichlet(np.ones(len(on))) @ on
        points += [x + delta * F_j, x - delta * F_j]
    return np.array(points)


def test_paper_cup_has_834_facets_and_1779_vertices(paper):
    assert paper.F.shape == (834, 6) and paper.g.shape == (834,)
    assert paper.vertices.shape == (1779, 6)


def test_vertices_satisfy_the_hrep_and_every_row_is_a_facet(paper):
    np.testing.assert_allclose(np.linalg.norm(paper.F, axis=1), 1.0)
    slack = paper.vertices @ paper.F.T - paper.g
    assert slack.max() <= 1e-9
    for j in range(len(paper.F)):
        on = paper.vertices[np.abs(slack[:, j]) <= 1e-9]
        # >= 6 affinely independent vertices: the row is a facet.
        assert np.linalg.svd(on - on[0], compute_uv=False)[4] > 1e-6
    # No duplicate rows.
    rows = np.column_stack([paper.F, paper.g])
    assert len(np.unique(rows.round(6), axis=0)) == len(rows)


@pytest.mark.slow
def test_hrep_agrees_with_lp_in_bulk_and_within_1e6_of_the_boundary(paper):
    rng = np.random.default_rng(7)
    centre = paper.vertices.mean(axis=0)
    picks = (
        rng.dirichlet(np.full(8, 0.3), size=1000)
        @ paper.vertices[rng.integers(len(paper.vertices), size=8)]
    )
    bulk = centre + rng.uniform(0.5, 1.5, size=(1000, 1)) * (picks - centre)
    wrenches = np.vstack([bulk, _boundary_points(paper, 600, 1e-6, rng)])
    margin = np.max(wrenches @ paper.F.T - paper.g, axis=1)
    clear = np.abs(margin) >= 5e-7  # skip the few wrenches near a ridge
    assert clear.sum() >= 2000
    assert 0.2 < np.mean(margin[clear] < 0) < 0.8  # both sides are tested
    residual = lp_residual(wrenches[clear], paper.cup)
    # Outside by delta (unit rows), the LP residual is >= delta / sqrt(6).
    np.testing.assert_array_equal(residual <= 1e-8, margin[clear] < 0)
    np.testing.assert_array_equal(
        is_realizable(wrenches[clear], paper.F, paper.g), margin[clear] < 0
    )


def test_rotating_wrenches_by_2pi_over_m_about_the_axis_maps_the_set_onto_itself(
    paper,
):
    R = rotation_symmetry(paper.cup)
    rotated = np.column_stack([paper.F @ R.T, paper.g])
    original = np.column_stack([paper.F, paper.g])
    assert {tuple(r) for r in rotated.round(8)} == {tuple(r) for r in original.round(8)}
    images = paper.vertices @ R.T
    assert {tuple(v) for v in images.round(8)} == {
        tuple(v) for v in paper.vertices.round(8)
    }


@given(cup=small_cups)
@settings(max_examples=10, deadline=None)
def test_symmetric_enumeration_equals_the_plain_one(cup):
    polytope = contact_wrench_polytope(cup)
    scale = wrench_scale(cup)
    summands = [(friction_pyramid(cup) @ G.T) * scale for G in grasp_matrices(cup)]
    plain = minkowski_sum(summands, suction_wrench(cup) * scale)
    assert len(plain.F) == len(polytope.F)
    assert len(plain.vertices) == len(polytope.vertices)
    assert np.all(plain.vertices / scale @ polytope.F.T <= polytope.g + 1e-9)


@given(cup=small_cups)
@settings(max_examples=10, deadline=None)
def test_small_cups_agree_with_lp(cup):
    polytope = contact_wrench_polytope(cup)
    rng = np.random.default_rng(0)
    wrenches = _boundary_points(polytope, 40, 1e-5, rng)
    margin = np.max(wrenches @ polytope.F.T - polytope.g, axis=1)
    clear = np.abs(margin) >= 5e-6
    lp = is_realizable_lp(wrenches[clear], cup)
    np.testing.assert_array_equal(lp, margin[clear] < 0)


@given(
    points=st.integers(3, 6),
    sides=st.integers(3, 6),
    forces=st.tuples(st.floats(1.0, 50.0), st.floats(1.0, 50.0)),
)
@settings(max_examples=10, deadline=None)
def test_without_friction_no_tangential_force_nor_torque_about_the_axis(
    points, sides, forces
):
    cup = CupParameters(
        points=points,
        sides=sides,
        friction=0.0,
        suction_force=forces[0],
        max_normal_force=forces[1],
    )
    polytope = contact_wrench_polytope(cup)
    # tau_z, f_x, f_y are zero on every vertex, hence on every realizable wrench.
    np.testing.assert_allclose(polytope.vertices[:, [2, 3, 4]], 0.0, atol=1e-9)
    rng = np.random.default_rng(points)
    inside = rng.dirichlet(np.ones(len(polytope.vertices)), 50) @ polytope.vertices
    assert np.all(polytope.contains(inside))
    for axis in (2, 3, 4):
        pushed = inside.copy()
        pushed[:, axis] += 1e-4
        assert not np.any(polytope.contains(pushed))
        assert not np.any(is_realizable_lp(pushed[:5], cup))


@given(cup=small_cups, factor=st.floats(0.1, 10.0))
@settings(max_examples=10, deadline=None)
def test_scaling_suction_and_normal_bound_scales_the_set(cup, factor):
    scaled = dataclasses.replace(
        cup,
        suction_force=cup.suction_force * factor,
        max_normal_force=cup.max_normal_force * factor,
    )
    a, b = contact_wrench_polytope(cup), contact_wrench_polytope(scaled)
    assert len(a.F) == len(b.F) and len(a.vertices) == len(b.vertices)
    # Same facet normals, offsets times the factor; vertices times the factor.
    assert np.all(np.abs(factor * a.vertices @ b.F.T - b.g).min(axis=0) <= 1e-8)
    assert np.all(b.vertices @ b.F.T <= b.g + 1e-9)
    assert np.all(factor * a.vertices @ b.F.T <= b.g + 1e-8 * factor)
    assert np.all(b.vertices / factor @ a.F.T <= a.g + 1e-9)


def _hanging_wrench(mass: float, p_CoOcm_C: np.ndarray) -> np.ndarray:
    """Wrench the cup must exert to hold a still object, cup facing down."""
    R_WC = np.diag([1.0, -1.0, -1.0])  # +z_C points down
    f_C = -mass * R_WC.T @ GRAVITY_W
    return np.hstack([np.cross(p_CoOcm_C, f_C), f_C])


@pytest.mark.parametrize(
    "mass,p_CoOcm_C,held",
    [
        (0.5, [0.0, 0.0, 0.05], True),
        (0.5, [0.01, -0.005, 0.04], True),  # off-centre: the rim takes the torque
        (1.9, [0.0, 0.0, 0.05], True),  # 18.6 N < 20 N of suction
        (2.1, [0.0, 0.0, 0.05], False),  # 20.6 N > 20 N of suction
        (5.0, [0.0, 0.0, 0.05], False),
    ],
)
def test_a_hanging_object_is_held_only_if_suction_can_carry_it(
    paper, mass, p_CoOcm_C, held
):
    w = _hanging_wrench(mass, np.array(p_CoOcm_C))
    assert bool(paper.contains(w)) is held
    assert bool(is_realizable_lp(w, paper.cup)) is held


@given(mass=st.floats(0.01, 5.0), height=st.floats(0.0, 0.2))
@settings(max_examples=30, deadline=None)
def test_hanging_on_axis_is_realizable_iff_weight_below_suction(paper, mass, height):
    weight = 9.81 * mass
    if abs(weight - paper.cup.suction_force) < 1e-6:
        return
    w = _hanging_wrench(mass, np.array([0.0, 0.0, height]))
    assert bool(paper.contains(w)) is (weight < paper.cup.suction_force)


def test_is_realizable_rejects_wrenches_of_the_wrong_shape(paper):
    with pytest.raises(
        ValueError, match=r"wrenches must be a \(..., 6\) array.*shape \(3,\)"
    ):
        is_realizable(np.zeros(3), paper.F, paper.g)


@pytest.mark.parametrize(
    "points,sides,friction", [(4, 4, 0.3), (3, 6, 1.0), (5, 3, 0.5), (4, 4, 0.0)]
)
def test_small_cups_have_the_facets_cdd_finds_from_all_force_combinations(
    points, sides, friction
):
    cdd = pytest.importorskip("cdd")
    cup = CupParameters(points=points, sides=sides, friction=friction)
    polytope = contact_wrench_polytope(cup)
    # Every sum of one pyramid vertex per contact point, plus suction.
    pyramids = [friction_pyramid(cup) @ G.T for G in grasp_matrices(cup)]
    sums = suction_wrench(cup) + np.array(
        [sum(choice) for choice in itertools.product(*pyramids)]
    )
    assert np.all(polytope.contains(sums))
    matrix = cdd.matrix_from_array(
        np.hstack([np.ones((len(sums), 1)), sums]), rep_type=cdd.RepType.GENERATOR
    )
    reference = cdd.copy_inequalities(cdd.polyhedron_from_matrix(matrix))
    rows = np.array(reference.array)
    equalities = len(reference.lin_set)
    keep = [i for i in range(len(rows)) if i not in reference.lin_set]
    F, g = -rows[keep, 1:], rows[keep, 0]
    g, F = g / np.linalg.norm(F, axis=1), F / np.linalg.norm(F, axis=1)[:, None]
    assert len(polytope.F) == len(F) + 2 * equalities
    if equalities == 0:
        mine = {tuple(r) for r in np.column_stack([polytope.F, polytope.g]).round(6)}
        assert mine == {tuple(r) for r in np.column_stack([F, g]).round(6)}


@pytest.mark.parametrize("suction_force", [16.0, 8.0, 30.0])
def test_another_suction_force_translates_the_set(paper, suction_force):
    """The set of a weaker (or stronger) vacuum, derived by translation, equals
    the one enumerated from scratch: same facets (rows matched by normal), same
    offsets, same vertices."""
    derived = with_suction_force(paper, suction_force)
    direct = contact_wrench_polytope(
        dataclasses.replace(CupParameters(), suction_force=suction_force)
    )
    assert derived.cup == direct.cup
    assert derived.F.shape == direct.F.shape
    match = np.argmax(derived.F @ direct.F.T, axis=1)  # unit rows: cosine
    np.testing.assert_allclose(derived.F, direct.F[match], atol=1e-9)
    np.testing.assert_allclose(derived.g, direct.g[match], atol=1e-9)
    order = np.lexsort(np.round(derived.vertices, 9).T)
    order_direct = np.lexsort(np.round(direct.vertices, 9).T)
    np.testing.assert_allclose(
        derived.vertices[order], direct.vertices[order_direct], atol=1e-9
    )
