"""CMA-ES over the path family's parameters, within a number of evaluations.

CMA-ES (the ``cmaes`` package, Hansen's algorithm) samples each generation
around its mean, ranks the candidates by the objective
(:mod:`._objective`) and adapts mean, step size and covariance. It needs no
gradients, which suits TOPP-RA's piecewise-smooth duration: finite-difference
descent on the same objective stalled at 0.79-0.82 of the spline path's
duration where CMA-ES reached 0.73-0.80 with as many evaluations.

The search evaluates x = 0 (the via points at the spline path's corners)
and the warm starts (:mod:`._starts`), starts at the best of them, runs
whole generations until ``max_evaluations`` candidates have been scored and
returns the feasible candidates with the lowest durations, best first. It
reads no clock: the same objective and seed give the same candidates
whatever the machine's load.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

import numpy as np


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
    max_evaluations: int,
    sigma: float,
    seed: int,
    population: int | None = None,
    keep: int = 4,
    x0: np.ndarray | None = None,
) -> SearchResult:
    """Minimise ``objective`` from the best of x = 0 and ``x0``, ``max_evaluations``.

    Args:
        objective: Maps a batch x (P, dim) to (values (P,), feasible (P,)).
        dim: Number of parameters.
        max_evaluations: No generation starts once this many candidates
            (the first batch included) have been scored.
        sigma: Initial step size, in units of x.
        seed: Seed of CMA-ES's sampler.
        population: Candidates per generation (default: 4 + 3 ln dim).
        keep: How many feasible candidates to return.
        x0: (S, dim) warm starts evaluated with x = 0 in the first batch;
            CMA-ES starts at the best of them.
    """
    start = (
        np.zeros((1, dim))
        if x0 is None
        else np.vstack([np.zeros(dim), np.reshape(x0, (-1, dim))])
    )
    values, feasible = objective(start)
    mean = start[int(np.argmin(values))]
    # Imported here: cmaes loads scipy.stats, about a fifth of the import
    # time of every process that loads the simulation.
    from cmaes import CMA

    optimizer = CMA(mean=mean, sigma=sigma, seed=seed, population_size=population)
    best = [Candidate(start[i], float(values[i])) for i in np.flatnonzero(feasible)]
    best = sorted(best, key=lambda c: c.duration)[:keep]
    evaluations, generations = len(start), 0
    while evaluations < max_evaluations:
        x = np.array([optimizer.ask() for _ in range(optimizer.population_size)])
        values, feasible = objective(x)
        evaluations += len(x)
        generations += 1
        optimizer.tell(list(zip(x, values, strict=True)))
        best += [Candidate(x[i], float(values[i])) for i in np.flatnonzero(feasible)]
        best = sorted(best, key=lambda c: c.duration)[:keep]
    return SearchResult(best, evaluations, generations)


__all__ = ["Candidate", "SearchResult", "cma_search"]
