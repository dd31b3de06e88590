"""Multi-cup tools: the exact tool wrench set against independent references.

References: the candidate enumeration of ``minkowski_sum`` (another exact
algorithm), an LP over every cup's rim forces placed in the tool frame from
the contact points (``lp_residual``), and the statics of a carton.
"""

from __future__ import annotations

import numpy as np
import pytest

import rt_drake.contact._adjacency as adjacency
import rt_drake.contact._cache as cache
from rt_drake.contact import (
    CupMount,
    CupParameters,
    ToolParameterError,
    ToolParameters,
    ToolWrenchSet,
    TooManyFacetsError,
    cache_path,
    cached_wrench_polytope,
    contact_wrench_polytope,
    guided_approximation,
    is_realizable,
    is_realizable_lp,
    load_polytope,
    lp_residual,
    object_wrench_sampler,
    tool_symmetry,
    tool_wrench_polytope,
)
from rt_drake.contact._adjacency import minkowski_sum_walk
from rt_drake.contact._minkowski import minkowski_sum
from rt_drake.contact.tool_polytope import tool_summands
from rt_drake.contact.wrench_polytope import wrench_scale
from rt_drake.errors import InputError, RtDrakeError

GRAVITY = 9.81


def _rotation_y(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def _pair(cup: CupParameters, gap: float = 0.12, tilt: float = 0.0) -> ToolParameters:
    """Two cups on T's x axis, ``gap`` apart, tilted by +/- ``tilt`` about y."""
    return ToolParameters(
        cups=[
            CupMount(cup, _rotation_y(tilt), [gap / 2, 0.0, 0.0]),
            CupMount(cup, _rotation_y(-tilt), [-gap / 2, 0.0, 0.01 * (tilt != 0)]),
        ]
    )


#: Coplanar, symmetric under a half turn about T's z (4-point rims).
SYMMETRIC = _pair(CupParameters(points=4, sides=3))
#: Cups tilted towards each other, one raised: no symmetry.
TILTED = _pair(CupParameters(points=3, sides=3), tilt=0.3)
#: No friction: the set is 3-dimensional (affine hull rows).
FRICTIONLESS = _pair(CupParameters(points=4, friction=0.0))


@pytest.fixture(scope="module")
def symmetric():
    return tool_wrench_polytope(SYMMETRIC)


@pytest.fixture(scope="module")
def tilted():
    return tool_wrench_polytope(TILTED)


def _rows(F: np.ndarray, g: np.ndarray) -> set[tuple[float, ...]]:
    return {tuple(r) for r in np.column_stack([F, g]).round(7)}


def _points(vertices: np.ndarray) -> set[tuple[float, ...]]:
    return {tuple(v) for v in vertices.round(7)}


def _boundary_points(polytope, count: int, rng) -> tuple[np.ndarray, np.ndarray]:
    """Points on random facets pushed out and in along the unit row.

    The push is 1e-6 of the largest vertex coordinate (mixed N, N*m units).
    """
    delta = 1e-6 * np.abs(polytope.vertices).max()
    outside, inside = [], []
    for row in rng.integers(len(polytope.F), size=count):
        F_j, g_j = polytope.F[row], polytope.g[row]
        on = polytope.vertices[np.abs(polytope.vertices @ F_j - g_j) <= 1e-9]
        x = rng.dirichlet(np.ones(len(on))) @ on
        outside.append(x + delta * F_j)
        inside.append(x - delta * F_j)
    return np.array(outside), np.array(inside)


# --- One cup ----------------------------------------------------------------


def test_one_cup_at_the_tool_origin_is_the_cup_set():
    cup = CupParameters()
    tool = tool_wrench_polytope(ToolParameters.single(cup))
    alone = contact_wrench_polytope(cup)
    assert tool.F.shape == (834, 6) and tool.vertices.shape == (1779, 6)
    assert _rows(tool.F, tool.g) == _rows(alone.F, alone.g)
    assert _points(tool.vertices) == _points(alone.vertices)


def test_one_posed_cup_is_the_walk_over_its_mapped_pyramids():
    # Mapped cup set (F Ad^-1, Ad v) against the walk over the pyramids in T.
    mount = CupMount(CupParameters(points=5), _rotation_y(0.4), [0.03, -0.02, 0.05])
    tool = ToolParameters(cups=[mount])
    mapped = tool_wrench_polytope(tool)
    scale = wrench_scale(tool)
    summands, offset = tool_summands(tool)
    walked = minkowski_sum_walk([s * scale for s in summands], offset * scale)
    F = walked.F * scale
    norms = np.linalg.norm(F, axis=1)
    assert _rows(mapped.F, mapped.g) == _rows(F / norms[:, None], walked.g / norms)
    assert _points(mapped.vertices) == _points(walked.vertices / scale)


# --- The walk against the enumeration --------------------------------------


@pytest.mark.parametrize("seed", range(12))
def test_walk_equals_enumeration_on_random_sums(seed):
    rng = np.random.default_rng(seed)
    summands = []
    for _ in range(int(rng.integers(2, 6))):
        dim = int(rng.integers(1, 4))
        points = rng.normal(size=(int(rng.integers(dim + 1, dim + 4)), dim))
        summands.append(points @ rng.normal(size=(dim, 6)) + rng.normal(size=6))
    offset = rng.normal(size=6)
    walked, enumerated = (
        minkowski_sum_walk(summands, offset),
        minkowski_sum(summands, offset),
    )
    assert walked.equalities == enumerated.equalities
    assert _rows(walked.F, walked.g) == _rows(enumerated.F, enumerated.g)
    assert _points(walked.vertices) == _points(enumerated.vertices)


def _scaled_summands(tool: ToolParameters) -> tuple[list[np.ndarray], np.ndarray]:
    """The tool's summands and offset in the walk's scaled units."""
    scale = wrench_scale(tool)
    summands, offset = tool_summands(tool)
    return [s * scale for s in summands], offset * scale


@pytest.fixture(scope="module")
def enumerations() -> dict[int, object]:
    """The enumeration ``minkowski_sum`` per tool (by ``id``), computed once:
    the symmetric and tilted tools are walked twice, with other limits."""
    return {}


@pytest.mark.slow
@pytest.mark.parametrize(
    ("tool", "hard_limit"),
    [
        (SYMMETRIC, adjacency.HARD_LIMIT),
        (TILTED, adjacency.HARD_LIMIT),
        (FRICTIONLESS, adjacency.HARD_LIMIT),
        # 20 "tipping" facets skipped (their normals span 3 dimensions):
        (SYMMETRIC, 200),
        # hard facets spanning 6 dimensions: the walk runs again without limit
        (TILTED, 20),
    ],
    ids=["symmetric", "tilted", "frictionless", "symmetric-skip", "tilted-rerun"],
)
def test_two_cup_walk_equals_enumeration(tool, hard_limit, monkeypatch, enumerations):
    monkeypatch.setattr(adjacency, "HARD_LIMIT", hard_limit)
    summands, offset = _scaled_summands(tool)
    walked = minkowski_sum_walk(summands, offset, symmetry=tool_symmetry(tool))
    if id(tool) not in enumerations:  # the reference, once per tool
        enumerations[id(tool)] = minkowski_sum(summands, offset)
    enumerated = enumerations[id(tool)]
    assert walked.equalities == enumerated.equalities
    assert _rows(walked.F, walked.g) == _rows(enumerated.F, enumerated.g)
    assert _points(walked.vertices) == _points(enumerated.vertices)


def test_symmetry_is_found_only_where_it_holds():
    half_turn = np.diag([-1.0, -1.0, 1.0, -1.0, -1.0, 1.0])
    np.testing.assert_allclose(tool_symmetry(SYMMETRIC), half_turn, atol=1e-12)
    assert tool_symmetry(TILTED) is None
    assert tool_symmetry(_pair(CupParameters(points=3))) is None  # 3-point rims
    uneven = ToolParameters(
        cups=[
            CupMount(CupParameters(), p_TC=[0.06, 0.0, 0.0]),
            CupMount(CupParameters(suction_force=25.0), p_TC=[-0.06, 0.0, 0.0]),
        ]
    )
    assert tool_symmetry(uneven) is None


# --- The H-representation ----------------------------------------------------


@pytest.mark.parametrize("name", ["symmetric", "tilted"])
def test_vertices_satisfy_the_hrep_and_every_row_is_a_facet(name, request):
    polytope = request.getfixturevalue(name)
    np.testing.assert_allclose(np.linalg.norm(polytope.F, axis=1), 1.0)
    slack = polytope.vertices @ polytope.F.T - polytope.g
    assert slack.max() <= 1e-9
    tight = np.abs(slack) <= 1e-9
    assert tight.sum(axis=0).min() >= 5  # a facet's worth of vertices in 6-D
    for j in range(len(polytope.F)):
        on = polytope.vertices[tight[:, j]]
        assert np.linalg.matrix_rank(on[1:] - on[0], tol=1e-7) == 5
    # A vertex is where 6 independent rows meet.
    assert min(np.linalg.matrix_rank(polytope.F[t], tol=1e-7) for t in tight) == 6


def test_frictionless_pair_is_three_dimensional_with_affine_hull_rows():
    polytope = tool_wrench_polytope(FRICTIONLESS)
    rng = np.random.default_rng(3)
    # Only f_z and the torques about x and y are possible without friction.
    inside = rng.dirichlet(np.ones(len(polytope.vertices)), 40) @ polytope.vertices
    np.testing.assert_allclose(inside[:, [2, 3, 4]], 0.0, atol=1e-9)
    assert polytope.contains(inside).all()
    assert is_realizable_lp(inside, FRICTIONLESS).all()
    sideways = inside + np.array([0.0, 0.0, 0.0, 1e-4, 0.0, 0.0])
    assert not polytope.contains(sideways).any()
    assert not is_realizable_lp(sideways, FRICTIONLESS).any()


# --- Agreement with the LP over all rim forces -------------------------------


@pytest.mark.parametrize(
    ("name", "tool"), [("symmetric", SYMMETRIC), ("tilted", TILTED)]
)
def test_hrep_agrees_with_the_lp_on_random_wrenches(name, tool, request):
    polytope = request.getfixturevalue(name)
    rng = np.random.default_rng(0)
    low, high = polytope.vertices.min(axis=0), polytope.vertices.max(axis=0)
    wrenches = rng.uniform(low, high, size=(300, 6))
    # Shrink half of them toward a point of the set: both answers occur.
    centre = polytope.vertices.mean(axis=0)
    wrenches[::2] = centre + 0.3 * (wrenches[::2] - centre)
    by_hrep = polytope.contains(wrenches, tol=1e-9)
    by_lp = is_realizable_lp(wrenches, tool)
    assert 30 < by_hrep.sum() < 270
    np.testing.assert_array_equal(by_hrep, by_lp)


@pytest.mark.parametrize(
    ("name", "tool"), [("symmetric", SYMMETRIC), ("tilted", TILTED)]
)
def test_hrep_agrees_with_the_lp_next_to_the_boundary(name, tool, request):
    polytope = request.getfixturevalue(name)
    outside, inside = _boundary_points(polytope, 60, np.random.default_rng(1))
    assert not polytope.contains(outside, tol=0.0).any()
    assert polytope.contains(inside, tol=0.0).all()
    assert np.all(lp_residual(outside, tool) > 1e-8)
    assert is_realizable_lp(inside, tool).all()


# --- A carton one cup cannot hold --------------------------------------------


def _carton_wrench(p_CoM: np.ndarray, mass: float = 1.8) -> np.ndarray:
    """Wrench [tau; f] the cups exert to hold the carton at rest, about the frame.

    The frame's +z points down (into the carton), so gravity on the carton is
    ``+m g z`` and the cups must pull with ``f = (0, 0, -m g)``, at the CoM.
    """
    f = np.array([0.0, 0.0, -mass * GRAVITY])
    return np.concatenate([np.cross(p_CoM, f), f])


def test_two_cups_hold_a_carton_that_one_cup_cannot(symmetric):
    # 0.40 x 0.30 x 0.10 m, 1.8 kg, picked on top by cups 0.12 m apart,
    # symmetric about the CoM; T midway between the cups on the contact face.
    # The cups of SYMMETRIC: the paper cup's radius, suction and normal bound
    # on a 4-point rim (the paper's 6-point pair takes 40 s more to make; the
    # statics are the same: the one cup fails on the carton's torque).
    tool = SYMMETRIC
    cup = tool.cups[0].cup
    assert tool.cups[1].cup == cup
    assert tool.cups[0].p_TC[0] - tool.cups[1].p_TC[0] == pytest.approx(0.12)
    held_by_two = _carton_wrench(np.array([0.0, 0.0, 0.05]))
    held_by_one = _carton_wrench(np.array([-0.06, 0.0, 0.05]))  # in cup 0's frame
    one = contact_wrench_polytope(cup)
    assert not is_realizable(held_by_one, one.F, one.g)
    assert lp_residual(held_by_one, cup) > 1e-3
    two = symmetric  # tool_wrench_polytope(SYMMETRIC)
    assert is_realizable(held_by_two, two.F, two.g)
    assert is_realizable_lp(held_by_two, tool)


# --- Cache --------------------------------------------------------------------


def test_cache_round_trip_and_the_key_covers_every_pose(tmp_path, monkeypatch):
    tool = FRICTIONLESS
    first = cached_wrench_polytope(tool, tmp_path)
    assert cache_path(tool, tmp_path).is_file()

    def fail(tool):
        raise AssertionError("recomputed although cached")

    monkeypatch.setattr(cache, "tool_wrench_polytope", fail)
    second = cached_wrench_polytope(tool, tmp_path)
    np.testing.assert_array_equal(second.F, first.F)
    np.testing.assert_array_equal(second.g, first.g)
    np.testing.assert_array_equal(second.vertices, first.vertices)
    assert second.cup is tool
    monkeypatch.undo()
    moved = ToolParameters(
        cups=[tool.cups[0], CupMount(tool.cups[1].cup, p_TC=[-0.06, 0.001, 0.0])]
    )
    turned = ToolParameters(
        cups=[
            tool.cups[0],
            CupMount(tool.cups[1].cup, _rotation_y(1e-9), [-0.06, 0, 0]),
        ]
    )
    paths = {cache_path(t, tmp_path) for t in (tool, moved, turned)}
    assert len(paths) == 3
    # A file written for another tool is never loaded.
    cache_path(moved, tmp_path).write_bytes(cache_path(tool, tmp_path).read_bytes())
    with pytest.raises(InputError, match="written for another tool"):
        load_polytope(cache_path(moved, tmp_path), moved)
    # A cup and the one-cup tool at its frame are cached apart.
    cup = tool.cups[0].cup
    assert cache_path(cup, tmp_path) != cache_path(ToolParameters.single(cup), tmp_path)


# --- Bad input -----------------------------------------------------------------


def test_bad_tools_raise_one_line_errors_naming_the_value():
    cup = CupParameters()
    with pytest.raises(ToolParameterError, match="at least one cup, got 0"):
        ToolParameters(cups=[])
    with pytest.raises(ToolParameterError, match="rotation.*det"):
        CupMount(cup, R_TC=np.diag([1.0, 1.0, 2.0]))
    with pytest.raises(ToolParameterError, match="rotation"):
        CupMount(cup, R_TC=np.diag([1.0, -1.0, 1.0]))  # a reflection
    with pytest.raises(ToolParameterError, match=r"p_TC must be 3 finite.*nan"):
        CupMount(cup, p_TC=[0.0, float("nan"), 0.0])
    with pytest.raises(ToolParameterError, match="cup 1: expected a CupMount"):
        ToolParameters(cups=[CupMount(cup), cup])
    bad = CupParameters()
    tool = ToolParameters(cups=[CupMount(cup), CupMount(bad, p_TC=[0.1, 0, 0])])
    bad.radius = -0.01
    with pytest.raises(ToolParameterError) as error:
        tool_wrench_polytope(tool)
    assert str(error.value) == "cup 1: radius must be in [0.0001, 0.5] m, got -0.01"
    assert isinstance(error.value, ValueError)


# --- Inner approximation without the facets --------------------------------------


def test_guided_approximation_from_support_and_lp_is_inside_the_exact_set(symmetric):
    samples = object_wrench_sampler(mass=0.5, p_CoOcm_C=(0.0, 0.0, 0.05), seed=1)(300)
    approx = guided_approximation(ToolWrenchSet(SYMMETRIC), samples, 30, seed=0)
    # Sound: its vertices (so the whole hull) lie in the exact W_T.
    assert symmetric.contains(approx.vertices, tol=1e-9).all()
    # The LP and the exact H-rep reject the same guiding samples.
    assert approx.rejected == int((~symmetric.contains(samples)).sum())
    covered = np.all(samples @ approx.F.T <= approx.g + 1e-9, axis=1)
    assert covered.sum() == approx.covered
    assert symmetric.contains(samples[covered]).all()
    assert 0 < approx.covered <= approx.samples


def test_a_walk_past_max_facets_stops_with_a_typed_error():
    with pytest.raises(TooManyFacetsError, match="more than 100 facets") as error:
        tool_wrench_polytope(SYMMETRIC, max_facets=100)
    assert error.value.found > 100
    assert isinstance(error.value, RtDrakeError)
