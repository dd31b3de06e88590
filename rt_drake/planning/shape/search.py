"""CMA-ES over the path family's parameters, until a deadline.

CMA-ES (the ``cmaes`` package, Hansen's algorithm) samples each generation
around its mean, ranks the candidates by the objective
(:mod:`.objective`) and adapts mean, step size and covariance. It needs no
gradients, which suits TOPP-RA's piecewise-smooth duration: finite-difference
descent on the same objective stalled at 0.79-0.82 of the spline path's
duration where CMA-ES reached 0.73-0.80 with as many evaluations.

The search starts at x = 0 (the via points at the spline path's corners),
stops at the deadline (or after ``max_evaluations``) and returns the
feasible candidates with the lowest durations, best first.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

import numpy as np
from cmaes import CMA


@dataclasses.dataclass(frozen=True)
class Candidate:
    """A feasible candidate: parameters x and its coarse duration (s)."""

    x: np.ndarray
    duration: float


@dataclasses.dataclass(frozen=True)
class SearchResult:
    """The best feasible candidates (best first), evaluations and generations."""

    candidates: list[Candidate]
    evaluations: int
    generations: int


def cma_search(
    objective: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]],
    dim: int,
    expired: Callable[[], bool],
    sigma: float,
    seed: int,
    population: int | None = None,
    keep: int = 4,
    max_evaluations: int | None = None,
) -> SearchResult:
    """Minimise ``objective`` from x = 0 until ``expired()``.

    Args:
        objective: Maps a batch x (P, dim) to (values (P,), feasible (P,)).
        dim: Number of parameters.
        expired: True once the search must stop (checked per generation).
        sigma: Initial step size, in units of x.
        seed: Seed of CMA-ES's sampler.
        population: Candidates per generation (default: 4 + 3 ln dim).
        keep: How many feasible candidates to return.
        max_evaluations: Stop after this many evaluations as well.
    """
    optimizer = CMA(
        mean=np.zeros(dim), sigma=sigma, seed=seed, population_size=population
    )
    x0 = np.zeros((1, dim))
    values, feasible = objective(x0)
    best = [Candidate(x0[0], float(values[0]))] if feasible[0] else []
    evaluations, generations = 1, 0
    while not expired():
        if max_evaluations is not None and evaluations >= max_evaluations:
            break
        x = np.array([optimizer.ask() for _ in range(optimizer.population_size)])
        values, feasible = objective(x)
        evaluations += len(x)
        generations += 1
        optimizer.tell(list(zip(x, values, strict=True)))
        best += [Candidate(x[i], float(values[i])) for i in np.flatnonzero(feasible)]
        best = sorted(best, key=lambda c: c.duration)[:keep]
    return SearchResult(best, evaluations, generations)


__all__ = ["Candidate", "SearchResult", "cma_search"]
