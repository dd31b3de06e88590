"""TOPP-RA's reachability passes (toppra 0.6.10) over its Cython seidel LP.

Constraints are toppra ``LinearConstraint`` objects with precomputed
coefficients: :class:`AffineConstraint` is ``F (a_i u + b_i x + c_i) <= g``
with one constant F, g (``identical``) and a, b, c given per grid point,
converted to the interpolation discretization by toppra's
``canlinear_colloc_to_interpolate``; :class:`XBound` carries ``0 <= x <=
x_max(s_i)`` (the joint velocity limits). toppra's ``seidelWrapper`` solves
each stage's 2-variable LP.

:func:`reachability` runs the algorithm of ``toppra.algorithm.TOPPRA``
(``compute_parameterization``): the backward pass of controllable sets K_i,
then the greedy forward pass with toppra's numerical safeguards (x_{i+1}
reduced by 1e-8 or 0.01 % and clamped into K_{i+1}; a failed step retried
with x_i reduced). ``engine="toppra"`` calls toppra's class itself;
``engine="lean"`` runs the same steps without its per-stage Python
bookkeeping (about 3x faster here), without the LP for min K_i while K_{i+1}
contains 0 ((u, x) = (0, 0) is then admissible at stage i: the retimer
checked that object and arm can be held at rest at every grid point, so
min K_i = 0), and retries an LP that seidel reports infeasible once from a
cold start (see :func:`_lean`; toppra's class fails such paths).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple

import numpy as np
import toppra
from toppra.algorithm import TOPPRA
from toppra.constants import MAX_TRIES, SMALL, TINY
from toppra.constraint import DiscretizationType, LinearConstraint
from toppra.constraint.linear_constraint import canlinear_colloc_to_interpolate
from toppra.solverwrapper.cy_seidel_solverwrapper import seidelWrapper


class AffineConstraint(LinearConstraint):
    """``F (a_i u + b_i x + c_i) <= g`` at each grid point s_i.

    Args:
        a, b, c: (G, m) coefficients at the G grid points.
        F: (k, m) constant rows; g: (k,) constant bounds.
    """

    def __init__(
        self, a: np.ndarray, b: np.ndarray, c: np.ndarray, F: np.ndarray, g: np.ndarray
    ) -> None:
        super().__init__()
        self.discretization_type = DiscretizationType.Interpolation
        self.identical = True
        self._coefficients = (a, b, c, F, g)

    def compute_constraint_params(self, path, gridpoints, *args, **kwargs):  # noqa: D102
        return canlinear_colloc_to_interpolate(
            *self._coefficients, None, None, np.asarray(gridpoints), identical=True
        )


class XBound(LinearConstraint):
    """``x_lo(s_i) <= x <= x_hi(s_i)``; x_bound is (G, 2)."""

    def __init__(self, x_bound: np.ndarray) -> None:
        super().__init__()
        self._x_bound = x_bound

    def compute_constraint_params(self, path, gridpoints, *args, **kwargs):  # noqa: D102
        return None, None, None, None, None, None, self._x_bound


class Reachability(NamedTuple):
    """Result of the passes.

    Attributes:
        x: (N+1,) ``x_i = s'(s_i)^2`` (1/s^2), None if not controllable.
        u: (N,) ``u_i = s''`` chosen by stage i (1/s^2), None likewise.
        K: (N+1, 2) controllable sets of x.
        failed_stage: Stage whose controllable set came out empty (0 also
            when the start velocity is outside K_0); None if controllable.
    """

    x: np.ndarray | None
    u: np.ndarray | None
    K: np.ndarray
    failed_stage: int | None


def reachability(
    constraints: list[LinearConstraint],
    path: toppra.SplineInterpolator | None,
    gridpoints: np.ndarray,
    sd_start: float = 0.0,
    sd_end: float = 0.0,
    engine: str = "lean",
) -> Reachability:
    """Run TOPP-RA (see the module docstring).

    Args:
        constraints: Precomputed toppra constraints (they ignore ``path``).
        path: The toppra path; only ``engine="toppra"`` needs it.
        gridpoints: (N+1,) grid s_i.
        sd_start: Path velocity at s = 0 (1/s).
        sd_end: Path velocity at s = 1 (1/s).
        engine: "lean" or "toppra".
    """
    if engine == "toppra":
        algorithm = TOPPRA(constraints, path, gridpoints, solver_wrapper="seidel")
        sdd, sd, _, K = algorithm.compute_parameterization(
            sd_start, sd_end, return_data=True
        )
        if sd is None or np.isnan(sd).any():
            bad = np.flatnonzero(np.isnan(K).any(axis=1))
            return Reachability(None, None, K, int(bad.max()) if bad.size else 0)
        return Reachability(sd**2, sdd, K, None)
    if engine != "lean":
        raise ValueError(f"engine must be 'lean' or 'toppra', got {engine!r}")
    return _lean(
        lambda: seidelWrapper(constraints, path, gridpoints, solve_lp1d=True),
        np.diff(gridpoints),
        sd_start,
        sd_end,
    )


def _lean(
    make: Callable[[], seidelWrapper], ds: np.ndarray, sd_start: float, sd_end: float
) -> Reachability:
    """Run the TOPPRA passes (module docstring) on a fresh seidel wrapper.

    toppra's seidel LP warm-starts from the rows active in the previous LP;
    with nearly degenerate rows (e.g. at a path end, where q'(s) = 0) that
    start can make it report a feasible LP infeasible (toppra's own TOPPRA
    class then fails the path). An LP that comes back NaN is therefore solved
    once more on a new wrapper (a cold start) before it counts as infeasible.
    """
    solve = make().solve_stagewise_optim

    def cold(*args) -> list[float]:
        nonlocal solve
        solve = make().solve_stagewise_optim
        return solve(*args)

    stages = len(ds)
    nan = math.nan
    g_up = np.array([1e-9, -1.0])
    g_down = -g_up
    low, high = [0.0] * (stages + 1), [0.0] * (stages + 1)
    low[stages] = high[stages] = sd_end**2
    for i in range(stages - 1, -1, -1):
        low_next, high_next = low[i + 1], high[i + 1]
        upper = solve(i, None, g_up, nan, nan, low_next, high_next)[1]
        if upper != upper:  # NaN
            upper = cold(i, None, g_up, nan, nan, low_next, high_next)[1]
        lower = 0.0
        if low_next > 0.0:
            lower = solve(i, None, g_down, nan, nan, low_next, high_next)[1]
            if lower != lower:
                lower = cold(i, None, g_down, nan, nan, low_next, high_next)[1]
        if upper != upper or lower != lower:
            K = np.column_stack([low, high])
            K[: i + 1] = nan
            return Reachability(None, None, K, i)
        low[i], high[i] = (0.0 if 0.0 > lower else lower), upper  # max(lower, 0)
    K = np.column_stack([low, high])
    x = [0.0] * (stages + 1)
    x[0] = sd_start**2
    if x[0] + SMALL < low[0] or high[0] + SMALL < x[0]:
        return Reachability(None, None, K, 0)
    u = [0.0] * stages
    g_forward = np.array([0.0, -1.0])
    two_ds = (2.0 * ds).tolist()
    i = tries = 0
    while i < stages:
        x_i, low_next, high_next = x[i], low[i + 1], high[i + 1]
        g_forward[0] = -two_ds[i]
        step = solve(i, None, g_forward, x_i, x_i, low_next, high_next)[0]
        if step != step and tries == 0:
            step = cold(i, None, g_forward, x_i, x_i, low_next, high_next)[0]
        if step != step:
            if tries == MAX_TRIES:
                return Reachability(None, None, K, i)
            x[i] = max(x_i - TINY, 0.999 * x_i)
            tries += 1
            continue
        tries = 0
        u[i] = step
        x_next = x_i + two_ds[i] * step
        # The builtins' semantics (first argument on ties), without their calls:
        # x_next = max(x_next - TINY, 0.9999 x_next), clamped into K_{i+1}.
        reduced = x_next - TINY
        x_next = 0.9999 * x_next
        x_next = x_next if x_next > reduced else reduced
        x_next = x_next if x_next > low_next else low_next
        x[i + 1] = x_next if x_next < high_next else high_next
        i += 1
    return Reachability(np.array(x), np.array(u), K, None)


__all__ = ["AffineConstraint", "Reachability", "XBound", "reachability"]
