"""Guided inner approximation of the contact wrench set (paper Section II-D).

W_c can have hundreds to thousands of facets. The paper approximates it by
the convex hull H of a few points Y of W_c chosen to cover "guiding samples",
wrenches likely to occur in execution:

1. keep the guiding samples that lie in W_c (``F w <= g``);
2. start Y from 7 affinely independent samples (a 6-simplex);
3. take the facet h* of H = conv(Y) with the most samples outside it;
4. add to Y the vertex of W_c farthest beyond h*;
5. repeat 3-4 until Y has ``max_vertices`` points, or every sample is covered.

Since Y is in W_c, H is inside W_c: every wrench H accepts is realizable.
The hull is kept by qhull in scaled coordinates ``[torque / r; force]`` (N),
which is also the metric of "farthest"; the result is mapped back to wrenches
``[torque; force]`` on the object, about and in the cup frame C, as unit rows.

The same works for a multi-cup tool's set W_T (in the tool frame T, scaled by
the tool's length): from its exact polytope, or, when that is too large, from
a :class:`~rt_drake.contact.tool_polytope.ToolWrenchSet`, whose membership
is the LP over all rim forces and whose farthest point beyond h* is its
support point in h*'s direction (a vertex of W_T, found without facets).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

import numpy as np
from scipy.spatial import ConvexHull

from rt_drake import arguments
from rt_drake.contact.tool_polytope import ToolWrenchSet
from rt_drake.contact.wrench_polytope import (
    WrenchPolytope,
    is_realizable,
    wrench_scale,
)
from rt_drake.errors import InputError

#: Largest ``max_vertices`` accepted: the hull of N points in 6-D has up to
#: O(N^3) facets, each tested against every sample at every step.
MAX_VERTICES = 200
#: Largest number of guiding samples accepted (200 vertices from 20 000
#: samples take about 20 s; from 100 000, 80 s).
MAX_SAMPLES = 20_000

#: Random directions whose support points seed the initial simplex when the
#: set is given by its support function.
_POOL = 256


@dataclasses.dataclass(frozen=True)
class GuidedApproximation:
    """An inner approximation ``{w : F w <= g} = conv(vertices)`` of W_c.

    Attributes:
        F: (rows, 6) unit rows (qhull facets, coplanar ones merged).
        g: (rows,) offsets, N*m / N.
        vertices: (count, 6) vertices of the hull, ``[torque; force]``.
        covered: Guiding samples inside W_c that the hull also contains.
        samples: Guiding samples inside W_c.
        rejected: Guiding samples outside W_c (dropped in step 1).
    """

    F: np.ndarray
    g: np.ndarray
    vertices: np.ndarray
    covered: int
    samples: int
    rejected: int

    @property
    def fraction(self) -> float:
        """Fraction of the (realizable) guiding samples the hull contains."""
        return self.covered / self.samples


def _affine_distance(points: np.ndarray, simplex: list[np.ndarray]) -> np.ndarray:
    """Return the distance of each point to the affine hull of ``simplex``."""
    origin = simplex[0]
    if len(simplex) == 1:
        return np.linalg.norm(points - origin, axis=1)
    q, _ = np.linalg.qr((np.array(simplex[1:]) - origin).T)
    offsets = points - origin
    return np.linalg.norm(offsets - (offsets @ q) @ q.T, axis=1)


def _initial_simplex(
    samples: np.ndarray, vertices: np.ndarray, rng: np.random.Generator, atol: float
) -> list[np.ndarray]:
    """Return 7 affinely independent points (a 6-simplex).

    Random samples if they span 6-D, else samples and then vertices of W_c
    farthest from the affine hull of the points so far.
    """
    for _ in range(50 if len(samples) >= 7 else 0):
        pick = samples[rng.choice(len(samples), 7, replace=False)]
        if np.linalg.svd(pick[1:] - pick[0], compute_uv=False)[-1] > atol:
            return list(pick)
    simplex = [samples[rng.integers(len(samples))]]
    for pool in (samples, vertices):
        while len(simplex) < 7:
            distance = _affine_distance(pool, simplex)
            if distance.max() <= atol:
                break
            simplex.append(pool[np.argmax(distance)])
    return simplex


def _outside_counts(samples: np.ndarray, equations: np.ndarray, atol: float):
    """Per facet ``[a, b]``, the number of samples with ``a . s + b > atol``.

    In chunks of samples, so memory stays bounded (samples x facets floats
    would not: 100 000 samples and 10 000 facets are 8 GB).
    """
    counts = np.zeros(len(equations), dtype=np.int64)
    chunk = max(1, 2**22 // max(len(equations), 1))  # (chunk, facets): 32 MB
    for start in range(0, len(samples), chunk):
        block = samples[start : start + chunk] @ equations[:, :-1].T
        counts += np.sum(block + equations[:, -1] > atol, axis=0)
    return counts


def _support(
    polytope: WrenchPolytope | ToolWrenchSet, directions: np.ndarray, scale: np.ndarray
) -> np.ndarray:
    """Return the point of the set maximising each scaled direction, scaled.

    ``(S w) . n = w . (S n)``: the raw direction is ``S n``.
    """
    if isinstance(polytope, ToolWrenchSet):
        return polytope.support(directions * scale) * scale
    vertices = polytope.vertices * scale
    return vertices[np.argmax(directions @ vertices.T, axis=1)]


def guided_approximation(
    polytope: WrenchPolytope | ToolWrenchSet,
    guiding_samples: np.ndarray | Callable[[int], np.ndarray],
    max_vertices: int,
    seed: int = 0,
    sample_count: int = 2000,
    tol: float = 1e-9,
) -> GuidedApproximation:
    """Approximate W_c from inside by the hull of at most ``max_vertices`` points.

    Args:
        polytope: The exact W_c (or W_T), or a tool's set given by its support
            function and LP (:class:`ToolWrenchSet`).
        guiding_samples: (N, 6) wrenches ``[torque; force]`` in C, or a callable
            ``count -> (count, 6)`` called once with ``sample_count``.
        max_vertices: Largest number of points of Y (>= 7).
        seed: Seed of the choice of the initial simplex.
        sample_count: Samples drawn when ``guiding_samples`` is a callable.
        tol: Allowed violation of a unit row for a sample to count as covered
            (N*m / N, like ``F w - g``).

    Raises:
        InputError: On bad arguments, or when no guiding sample lies in the set.
    """
    for name, value, high in (
        ("max_vertices", max_vertices, MAX_VERTICES),
        ("sample_count", sample_count, MAX_SAMPLES),
    ):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
            raise InputError(f"{name} must be an integer, got {value!r}")
        low = 7 if name == "max_vertices" else 1  # a 6-simplex; one sample
        if not low <= value <= high:
            raise InputError(f"{name} must be in [{low}, {high}], got {value}")
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise InputError(f"seed must be an integer >= 0, got {seed!r}")
    where = "guided_approximation"
    arguments.instance(
        polytope, "polytope", (WrenchPolytope, ToolWrenchSet), where=where
    )
    arguments.number(tol, "tol", where=where, low=0.0)
    if callable(guiding_samples):
        guiding_samples = guiding_samples(sample_count)
    wrenches = arguments.array(
        guiding_samples, "guiding_samples", ("N", 6), where=where, finite=False
    )
    if (
        wrenches.ndim != 2
        or wrenches.shape[1] != 6
        or not 1 <= len(wrenches) <= MAX_SAMPLES
    ):
        raise InputError(
            f"guiding samples must be (N, 6) wrenches, 1 <= N <= {MAX_SAMPLES}, "
            f"got {wrenches.shape}"
        )
    if not np.all(np.isfinite(wrenches)):
        raise InputError("guiding samples contain NaN or inf")
    if isinstance(polytope, ToolWrenchSet):
        inside = polytope.contains(wrenches)
    else:
        inside = polytope.contains(wrenches, tol=0.0)
    if not inside.any():
        raise InputError(f"none of the {len(wrenches)} guiding samples lies in W_c")
    scale = wrench_scale(polytope.cup)
    rng = np.random.default_rng(seed)
    samples = wrenches[inside] * scale
    if isinstance(polytope, ToolWrenchSet):
        vertices = _support(polytope, rng.normal(size=(_POOL, 6)), scale)
    else:
        vertices = polytope.vertices * scale
    atol = tol * max(1.0, float(np.abs(vertices).max()))
    points = _initial_simplex(samples, vertices, rng, atol)
    while True:
        hull = ConvexHull(np.array(points))
        if len(points) >= max_vertices:
            break
        counts = _outside_counts(samples, hull.equations, atol)
        if counts.max() == 0:
            break  # every sample is covered
        face = hull.equations[np.argmax(counts)]
        farthest = _support(polytope, face[None, :-1], scale)[0]
        if farthest @ face[:-1] + face[-1] <= atol:
            break  # cannot happen in exact arithmetic: samples lie in W_c
        points.append(farthest)
    F = hull.equations[:, :-1] * scale
    norms = np.linalg.norm(F, axis=1)
    rows = np.column_stack([F / norms[:, None], -hull.equations[:, -1] / norms])
    _, first = np.unique(rows.round(12), axis=0, return_index=True)
    rows = rows[np.sort(first)]
    F, g = rows[:, :-1], rows[:, -1]
    covered = int(is_realizable(wrenches[inside], F, g, tol).sum())
    return GuidedApproximation(
        F=F,
        g=g,
        vertices=hull.points[hull.vertices] / scale,
        covered=covered,
        samples=int(inside.sum()),
        rejected=int(len(wrenches) - inside.sum()),
    )
