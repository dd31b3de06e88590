"""The search's objective: TOPP-RA durations of many paths on a coarse grid.

For each candidate path (clamped chord-length spline through waypoints) this
is classic TOPP-RA on a grid of ``M`` points (uniform, or given), under the joint
velocity and acceleration limits and the exact grasp constraint ``F (a u + b
x + c) <= g`` at the grid points: the retimer's rows (ray shooting, then the
exactness check that adds any violated row and solves again) and its
compiled passes, with the path and the wrench coefficients of all
candidates from one batched evaluation (:mod:`._spline`, :mod:`.cup_chain`)
instead of Drake queries per grid point, about ten times cheaper per
candidate.

It ranks candidates; it does not certify them. :func:`rt_drake.retime`,
which retimes the returned path, also holds the limits between grid points
(the path's knots in its grid, joint rows inside segments, the grasp at
midpoints), so its durations are a little longer than these on the same
grid (equal when nothing binds between grid points; tested).

With ``ends`` (:class:`EndGrid`), each candidate gets its own grid: ``E``
points at equal steps of s over ``[0, f s_up]`` and over ``[1 - f (1 -
s_down), 1]``, ``s_up`` and ``s_down`` its own knots at the tops of the
vertical end segments (the family's waypoints ``m`` and ``K - 1 - m``), and
the ``M`` points mapped affinely from [0, 1] onto the span between (``M +
2 E`` points in all). The lift, the set-down and the sharp turns above them
are then resolved wherever the candidate puts them: on a grid fixed for all
candidates they fall between one or two points, where the search's
shaped paths hide most of what the fixed grid underestimates. It ranks
the KTO reference's paths against the shaped ones more often as the final
retime does, but did not make the search's results better on both seeds
measured, so it is off by default (BENCHMARKS.md, "A search score that
ranks as the final retime does").

The duration of a profile ``x_i = s'(s_i)^2`` is ``T = sum_i 2 ds_i /
(sqrt(x_i) + sqrt(x_{i+1}))`` (s). A candidate the retimer would reject
(grasp lost at rest, not controllable) gets ``inf``.

This module is the one place that uses the retimer's internals
(``rt_drake.retiming.seidel``, ``.passes`` and ``.rows``).
"""

from __future__ import annotations

import dataclasses

import numpy as np
from numba import njit

from rt_drake.retiming import seidel
from rt_drake.retiming import stage_rows as R
from rt_drake.retiming.limits import GraspConstraint, JointLimits
from rt_drake.retiming.passes import VAR_BOUND
from rt_drake.retiming.seidel import kernel_array
from rt_drake.shaping._spline import chord_knots_batch, evaluate_splines
from rt_drake.shaping.cup_chain import CupChain

#: N or N m: grasp rows violated by more than this are added (as the retimer).
ROW_TOLERANCE = 1e-9
#: Largest share of s of an end span of :class:`EndGrid`.
MAX_END_SPAN = 0.3


@dataclasses.dataclass(frozen=True)
class EndGrid:
    """Where a candidate's own grid points go: over its vertical ends.

    Attributes:
        points: E, points over each end span.
        span: f, each end span as a multiple of its vertical segment's
            share of s (the span is at most 0.3).
        vertical_points: m, waypoints on each vertical segment (the tops
            are the knots m and K - 1 - m).
    """

    points: int
    span: float
    vertical_points: int

    def grids(self, s: np.ndarray, knots: np.ndarray) -> np.ndarray:
        """Each path's grid (P, M + 2E) from the shared s (M,) and its knots (P, K)."""
        m, E = self.vertical_points, self.points
        steps = np.arange(1, E + 1) / E
        up = np.minimum(self.span * knots[:, m], MAX_END_SPAN)
        down = np.minimum(self.span * (1.0 - knots[:, -1 - m]), MAX_END_SPAN)
        first = up[:, None] * steps
        last = 1.0 - down[:, None] * steps[::-1]
        inner = up[:, None] + (1.0 - down - up)[:, None] * s[None, 1:-1]
        zeros, ones = np.zeros((len(knots), 1)), np.ones((len(knots), 1))
        return np.concatenate([zeros, first, inner, last, ones], axis=1)


class CoarseRetimer:
    """TOPP-RA durations of candidate paths on a uniform grid of ``gridpoints``.

    The grasp rows start as ``initial_rows`` (e.g. those ray shooting picks
    on the spline path) and grow, shared by all later candidates, whenever
    the exactness check finds a violated row; so each duration is the one
    TOPP-RA gives with every row.

    Args:
        chain: Batched kinematics of the arm's cup.
        limits: Joint velocity and acceleration limits (torques ignored).
        grasp: Held object and grasp polytope; None: nothing held (the
            pick), the joint limits only.
        gridpoints: Grid size M (>= 2), uniform, or the M points.
        initial_rows: Indices of grasp rows to start from.
        ends: Each candidate's points over its vertical ends (None: none).
    """

    def __init__(
        self,
        chain: CupChain,
        limits: JointLimits,
        grasp: GraspConstraint | None,
        gridpoints: int | np.ndarray,
        initial_rows: np.ndarray | None = None,
        ends: EndGrid | None = None,
    ) -> None:
        self.s = (
            np.linspace(0.0, 1.0, int(gridpoints))
            if np.ndim(gridpoints) == 0
            else np.asarray(gridpoints, dtype=float)
        )
        if len(self.s) < 2:
            raise ValueError(f"need >= 2 grid points, got {gridpoints}")
        self.chain = chain
        self.limits = limits
        self.grasp = grasp
        self.ends = ends
        n = limits.num_joints
        self._box = np.vstack([np.eye(n), -np.eye(n)])
        self._acceleration = np.tile(limits.acceleration, 2)
        self._velocity = kernel_array(limits.velocity)
        F, g = (np.zeros((0, 6)), np.ones(0)) if grasp is None else (grasp.F, grasp.g)
        self._normals = R.normalised_rows(F, g)
        self._F, self._g = kernel_array(F), kernel_array(g)
        self.rows = np.zeros(len(g), dtype=np.bool_)
        if initial_rows is not None:
            self.rows[np.asarray(initial_rows, dtype=int)] = True

    def select_rows(self, waypoints: np.ndarray) -> None:
        """Add the rows ray shooting picks on the paths through waypoints (P, K, n)."""
        if self.grasp is None:
            return
        q, dq, ddq = evaluate_splines(waypoints, self.s)
        a, b, c = self.chain.wrench_coefficients(self.grasp.held, q, dq, ddq)
        for p in range(len(q)):
            with np.errstate(divide="ignore"):
                x_cap = np.min(self.limits.velocity**2 / dq[p] ** 2, axis=1)
            _, rows = R.rest_and_candidates(a[p], b[p], c[p], self._normals, x_cap)
            self.rows[rows] = True

    def durations(self, waypoints: np.ndarray) -> np.ndarray:
        """Durations (s) of the paths through waypoints (P, K, n); inf: rejected."""
        return self.evaluate(waypoints)[0]

    def evaluate(
        self, waypoints: np.ndarray, bound: float = np.inf
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Durations of the paths through waypoints (P, K, n), with details.

        Args:
            waypoints: (P, K, n) joint waypoints (rad).
            bound: s; a path whose duration with the rows so far is already
                at least this is not checked for missed rows (adding rows
                only lengthens it): its duration is then a lower bound.

        Returns:
            ``(durations (P,), exact (P,) bool, used (P, R) bool)``: inf for a
            rejected path; whether the duration is TOPP-RA's with every row;
            the grasp rows each solve used.
        """
        return self._solve(waypoints, bound)[:3]

    def profile(self, waypoints: np.ndarray) -> tuple[float, np.ndarray]:
        """Duration (s) and profile ``x_i = s'(s_i)^2`` (1/s^2) of one path.

        Args:
            waypoints: (K, n) joint waypoints (rad) of the path.

        Returns:
            ``(T, x)``, x at the path's grid (:meth:`grids`); T is inf (and x
            zeros) if the path is rejected.
        """
        durations, _, _, x = self._solve(np.asarray(waypoints, float)[None], np.inf)
        return float(durations[0]), x[0]

    def grids(self, waypoints: np.ndarray) -> np.ndarray:
        """The grid of each path through waypoints (P, K, n): (P, M + 2E) or (1, M).

        ``s`` itself (one row, shared) without ``ends``, else each path's own
        (module docstring).
        """
        if self.ends is None:
            return self.s[None]
        return self.ends.grids(self.s, chord_knots_batch(waypoints))

    def _solve(
        self, waypoints: np.ndarray, bound: float
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """:meth:`evaluate`'s results and the profiles x (P, M') (zeros: rejected)."""
        grids = self.grids(waypoints)
        q, dq, ddq = evaluate_splines(waypoints, grids)
        if self.grasp is None:  # no wrench: rows of zero length
            a = b = c = np.zeros((*q.shape[:2], 6))
        else:
            a, b, c = self.chain.wrench_coefficients(self.grasp.held, q, dq, ddq)
        out = np.empty(len(q))
        exact = np.zeros(len(q), dtype=np.bool_)
        used = np.zeros((len(q), len(self.rows)), dtype=np.bool_)
        x = np.zeros((len(q), grids.shape[1]))
        _batch_durations(
            dq, ddq, *(kernel_array(v) for v in (a, b, c)),
            self._velocity, kernel_array(self._box), kernel_array(self._acceleration),
            self._F, self._g, self._normals, self.rows, np.diff(grids, axis=1),
            float(bound), out, exact, used, x,
        )  # fmt: skip
        return out, exact, used, x

    def share_rows(self, used: np.ndarray) -> None:
        """Add rows some paths needed (``used`` (P, R) from :meth:`evaluate`).

        Later batches then start from them instead of finding them again by
        the exactness check (each find costs one more TOPP-RA solve). Paths
        that needed every row (failed solves) are left out.
        """
        partial = used[used.sum(axis=1) < used.shape[1]]
        if len(partial):
            self.rows |= partial.any(axis=0)


@njit(cache=True)
def _batch_durations(  # noqa: D417
    dq, ddq, a, b, c, vel, box, acc, F, g, n, mask, ds, bound, out, exact, used, xs
):
    """TOPP-RA duration (and profile ``xs``) of each candidate (see evaluate).

    ``ds`` (P, M - 1): each candidate's grid steps, or (1, M - 1) shared.
    """
    P, M, dof = dq.shape
    zeros = np.zeros((M, dof))
    rows_total = F.shape[0]
    for p in range(P):
        step = ds[p] if ds.shape[0] > 1 else ds[0]
        local = mask.copy()
        # at rest: every row's slack positive at every grid point
        if rows_total > 0 and np.dot(np.ascontiguousarray(c[p]), n).max() >= 1.0:
            out[p] = np.inf
            exact[p] = True
            continue
        lo = np.empty((M, 2))
        hi = np.empty((M, 2))
        for i in range(M):
            cap = np.inf
            for j in range(dof):
                d2 = dq[p, i, j] * dq[p, i, j]
                if d2 > 0.0:
                    cap = min(cap, vel[j] * vel[j] / d2)
            lo[i, 0], lo[i, 1] = -VAR_BOUND, 0.0
            hi[i, 0], hi[i, 1] = VAR_BOUND, min(VAR_BOUND, cap)
        while True:
            selected = np.flatnonzero(local)
            width = 2 + 2 * box.shape[0] + 2 * selected.shape[0]
            A = np.zeros((M, width))
            B = np.zeros((M, width))
            C = np.full((M, width), -1.0)
            column = seidel.project(dq[p], ddq[p], zeros, box, acc, step, A, B, C, 2)
            seidel.project(
                a[p], b[p], c[p], F[selected], g[selected], step, A, B, C, column
            )
            x, u, _, failed = seidel.passes(A, B, C, lo, hi, step, 0.0, 0.0)
            if failed >= 0:
                if selected.shape[0] == rows_total:
                    out[p] = np.inf
                    exact[p] = True
                    break
                local[:] = True
                continue
            total = 0.0
            for i in range(M - 1):
                total += (
                    2.0
                    * step[i]
                    / (np.sqrt(max(x[i], 0.0)) + np.sqrt(max(x[i + 1], 0.0)))
                )
            out[p] = total
            xs[p] = x
            if total >= bound:
                break  # a lower bound, already no better than the bound
            if rows_total == 0:  # nothing held: exact as it is
                exact[p] = True
                used[p] = local
                break
            enforced = np.empty((2 * (M - 1), 6))
            for i in range(M - 1):
                x_next = x[i] + 2.0 * step[i] * u[i]
                for j in range(6):
                    here = a[p, i, j] * u[i] + b[p, i, j] * x[i] + c[p, i, j]
                    enforced[2 * i, j] = here
                    enforced[2 * i + 1, j] = (
                        a[p, i + 1, j] * u[i] + b[p, i + 1, j] * x_next + c[p, i + 1, j]
                    )
            values = np.dot(enforced, n)
            missed = False
            for r in range(values.shape[0]):
                for k in range(rows_total):
                    if not local[k] and g[k] * (values[r, k] - 1.0) > ROW_TOLERANCE:
                        local[k] = True
                        missed = True
            if missed:
                continue
            exact[p] = True
            used[p] = local
            break


__all__ = ["MAX_END_SPAN", "CoarseRetimer", "EndGrid"]
