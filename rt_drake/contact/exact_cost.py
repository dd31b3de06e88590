"""Memory and time the exact W_c will take, estimated before computing it.

The enumeration of :mod:`rt_drake.contact._minkowski` grows steeply with the
number m of contact points and the number k of sides of the friction polygon
(m = 10, k = 4 takes 1.4 GB and 1.5-4 min; m = 12 would need 30 GB; k = 64
at m = 6 far more than any machine has). :func:`exact_cost` estimates, from
m and k alone, the two stages' needs:

- facets: one candidate normal per choice of faces of the summands, grouped
  by rotation orbit: ``C = [x^5] (1 + 2k x + (k+1) x^2 + x^3)^m / m``
  (edges, 2-faces, the pyramid itself), exact; the largest group of
  candidates, ``K`` (a product of face counts, e.g. ``(2k)^5``), is held at
  once at about 400 bytes per candidate (basis, reflections, products).
- vertices: every combination of one vertex per summand on a seed facet is
  a candidate vertex, about ``T = 1.5 m (k + 4) k^(m-1)`` of them (a fit to
  the counts for m = 3..12, k = 3..32, 1.5 times above them: see
  BENCHMARKS.md), at about 70 bytes each (codes, sorting, decoding).

Memory ``= 100 MB + max(400 K, 70 T) + 48 C`` bytes; time ``= 4 us C + 3 us
T`` on one core (measured 3-6 us per candidate normal, 1-5 us per vertex
combination, more as the number of facets grows). With friction 0 the summands
are segments and the set is 3-dimensional: the cost is negligible.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from typing import NamedTuple

from rt_drake.contact._cup import (
    COUNT_RANGES,
    CupParameters,
)
from rt_drake.errors import TooLargeError

#: Default memory limit of the exact enumeration, bytes (the machines that
#: run rt-drake have 8 GB and more).
DEFAULT_MAX_MEMORY = 4 * 2**30
#: Bytes per candidate normal of the largest group held at once.
BYTES_PER_CANDIDATE = 400
#: Bytes per candidate vertex combination.
BYTES_PER_VERTEX_CODE = 70
#: Bytes of everything else (interpreter, numpy, scipy).
BASE_BYTES = 100 * 2**20


class ExactCost(NamedTuple):
    """Estimated needs of :func:`~rt_drake.contact.contact_wrench_polytope`.

    Attributes:
        memory: Peak memory, bytes.
        seconds: Time on one core, s.
        candidates: Candidate facet normals (exact).
        vertex_codes: Candidate vertex combinations (estimated).
    """

    memory: float
    seconds: float
    candidates: float
    vertex_codes: float


def exact_cost(cup: CupParameters) -> ExactCost:
    """Estimate the memory and time of the exact W_c of ``cup``."""
    m, k = cup.points, cup.sides
    if cup.friction == 0.0:  # segments: a 3-D set, C(m, 2) candidates
        return ExactCost(float(BASE_BYTES), 0.01, m * (m - 1) / 2, float(m))
    counts = {1: 2 * k, 2: k + 1, 3: 1}  # edges, 2-faces, the pyramid
    candidates = _coefficient([1, 2 * k, k + 1, 1], m, 5) / m
    largest = max(
        math.prod(counts[q] for q in dims)
        for parts in range(1, min(m, 5) + 1)
        for dims in itertools.combinations_with_replacement((1, 2, 3), parts)
        if sum(dims) == 5
    )
    codes = 1.5 * m * (k + 4) * math.exp(min((m - 1) * math.log(k), 600.0))
    memory = (
        BASE_BYTES
        + max(BYTES_PER_CANDIDATE * largest, BYTES_PER_VERTEX_CODE * codes)
        + 48 * candidates
    )
    return ExactCost(memory, 4e-6 * candidates + 3e-6 * codes, candidates, codes)


def check_exact_cost(
    cup: CupParameters, max_memory: float = DEFAULT_MAX_MEMORY
) -> ExactCost:
    """Return the estimate, or raise TooLargeError if it exceeds ``max_memory``.

    The message gives the estimate, the limit, and the largest number of
    points (at this cup's sides) and of sides (at its points) accepted.
    """
    cost = exact_cost(cup)
    if cost.memory <= max_memory:
        return cost
    points = _largest(cup, "points", max_memory)
    sides = _largest(cup, "sides", max_memory)
    raise TooLargeError(
        f"the exact wrench polytope of a cup with {cup.points} points and "
        f"{cup.sides} sides needs an estimated {gigabytes(cost.memory)} of memory "
        f"and {_duration(cost.seconds)} (limit {gigabytes(max_memory)}); the "
        f"largest accepted: {points or 'no'} points at {cup.sides} sides, "
        f"{sides or 'no'} sides at {cup.points} points"
    )


def gigabytes(size: float) -> str:
    """``size`` bytes as ``"1.4 GB"`` (GiB), or ``"3e+12 GB"`` when huge."""
    value = size / 2**30
    return f"{value:.3g} GB" if value < 1e6 else f"{value:.1e} GB"


def _largest(cup: CupParameters, name: str, max_memory: float) -> int | None:
    """The largest value of ``points`` or ``sides`` within ``max_memory``."""
    low, high = COUNT_RANGES[name]
    best = None
    for value in range(low, high + 1):
        trial = dataclasses.replace(cup, **{name: value})
        if exact_cost(trial).memory > max_memory:
            break
        best = value
    return best


def _coefficient(polynomial: list[int], power: int, degree: int) -> float:
    """``[x^degree] polynomial(x)^power``, by repeated truncated products."""
    result = [1] + [0] * degree
    for _ in range(power):
        result = [
            sum(
                result[i] * polynomial[d - i]
                for i in range(d + 1)
                if d - i < len(polynomial)
            )
            for d in range(degree + 1)
        ]
    return float(result[degree])


def _duration(seconds: float) -> str:
    if seconds < 120:
        return f"about {seconds:.0f} s"
    if seconds < 7200:
        return f"about {seconds / 60:.0f} min"
    return f"about {seconds / 3600:.2g} h"


__all__ = [
    "DEFAULT_MAX_MEMORY",
    "ExactCost",
    "check_exact_cost",
    "exact_cost",
    "gigabytes",
]
