"""The guided approximation: inside W_c, covering its guiding samples."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rt_drake.contact import (
    CupParameters,
    contact_wrench_polytope,
    guided_approximation,
    object_wrench_sampler,
)


@pytest.fixture(scope="module")
def paper():
    return contact_wrench_polytope(CupParameters())


@given(
    max_vertices=st.integers(7, 40),
    mass=st.floats(0.1, 1.5),
    seed=st.integers(0, 1000),
)
@settings(max_examples=8, deadline=None)
def test_approximation_is_inside_the_exact_set_and_covers_as_reported(
    paper, max_vertices, mass, seed
):
    samples = object_wrench_sampler(mass=mass, seed=seed)(600)
    approx = guided_approximation(paper, samples, max_vertices, seed=seed)
    assert 7 <= len(approx.vertices) <= max_vertices
    # Its vertices, and everything its H-rep accepts, are realizable.
    assert np.all(paper.contains(approx.vertices))
    assert np.all(approx.vertices @ approx.F.T <= approx.g + 1e-9)
    rng = np.random.default_rng(seed)
    probes = (
        rng.dirichlet(np.full(6, 0.5), 3000)
        @ paper.vertices[rng.integers(len(paper.vertices), size=6)]
    )
    probes = np.vstack([probes, samples])
    accepted = np.all(probes @ approx.F.T <= approx.g + 1e-9, axis=1)
    assert np.all(paper.contains(probes[accepted], tol=1e-8))
    # The coverage it reports is the coverage of its H-rep.
    realizable = samples[paper.contains(samples, tol=0.0)]
    covered = np.all(realizable @ approx.F.T <= approx.g + 1e-9, axis=1).sum()
    assert approx.covered == covered and approx.samples == len(realizable)
    assert approx.rejected == len(samples) - len(realizable)
    assert approx.fraction == pytest.approx(covered / len(realizable))


def test_more_vertices_cover_more_samples(paper):
    sampler = object_wrench_sampler(mass=0.55, seed=3)
    samples = sampler(1500)
    fractions = [
        guided_approximation(paper, samples, n, seed=0).fraction for n in (10, 25, 50)
    ]
    assert fractions[0] < fractions[1] <= fractions[2]
    assert fractions[2] > 0.9


def test_callable_guide_is_called_with_the_sample_count(paper):
    counts = []

    def guide(count: int) -> np.ndarray:
        counts.append(count)
        return object_wrench_sampler(seed=1)(count)

    approx = guided_approximation(paper, guide, 12, sample_count=321)
    assert counts == [321]
    assert approx.samples + approx.rejected == 321


def test_degenerate_guides_are_completed_by_vertices(paper):
    # All samples equal: the simplex takes 6 vertices of W_c.
    samples = np.tile(paper.vertices.mean(axis=0), (50, 1))
    approx = guided_approximation(paper, samples, 10)
    assert approx.covered == approx.samples == 50


@pytest.mark.parametrize(
    "samples,max_vertices,words",
    [
        (np.zeros((10, 6)), 6, "max_vertices"),
        (np.zeros((10, 5)), 10, "(N, 6)"),
        (np.full((10, 6), np.nan), 10, "NaN"),
        (np.tile([0, 0, 0, 0, 0, 1e3], (10, 1)), 10, "none of the 10"),
    ],
)
def test_bad_arguments_raise_value_error(paper, samples, max_vertices, words):
    with pytest.raises(ValueError, match=words.replace("(", r"\(").replace(")", r"\)")):
        guided_approximation(paper, samples, max_vertices)
