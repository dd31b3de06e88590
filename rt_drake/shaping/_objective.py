"""The search's objective: coarse duration plus penalties, for a batch of x.

For the paths of the family at parameters x (P, d), the value (s, lower is
better) is the coarse TOPP-RA duration (:mod:`._surrogate`; 10 s if the
retimer would reject the path) plus penalties that grow with the violation,
so that CMA-ES still ranks infeasible candidates, evaluated at
:data:`SAMPLES` values of s:

- tilt above the bound: ``1 + 10 (tilt - bound)`` (rad);
- a joint beyond its limit: ``1 + 10 excess`` (rad);
- clearance below the threshold between the vertical end segments:
  ``0.5 + 20 (threshold - d)`` (m), with d the smallest lower bound of the
  clearance estimate between consecutive samples
  (:meth:`.ClearanceModel.swept`: the samples' clearance less half the
  largest motion of the carried body between them), so that a thin wall
  between two samples is not missed.

The clearance threshold is the margin, or 80 % of the same bound along the
spline path (between its first and last waypoint intervals) and of the
clearance at the tops of the vertical segments if that is smaller: a grasp
close to a wall cannot keep the margin at the start. (Estimating the
clearance of the better half of a batch only, as before, let unchecked
paths outrank checked ones that a wall penalised, and misled CMA-ES where
walls bind; the estimate costs about 0.06 ms a path.) Paths whose coarse
duration with the grasp rows found so far already exceeds the best feasible
one are not checked for missed rows (:meth:`CoarseRetimer.evaluate`).
"""

from __future__ import annotations

import numpy as np

from rt_drake.shaping._clearance import ClearanceModel
from rt_drake.shaping._family import PathFamily
from rt_drake.shaping._spline import (
    chord_knots_batch,
    evaluate_splines,
)
from rt_drake.shaping._surrogate import CoarseRetimer
from rt_drake.types.path import GeometricPath

#: Samples of s per path for the penalties.
SAMPLES = 64
#: m, clearances above the margin plus this count as this (module docstring).
CUTOFF_EXTRA = 0.06
#: s, the value of a path the retimer rejects.
REJECTED = 10.0


class Objective:
    """Callable ``x (P, d) -> (values (P,), feasible (P,) bool)``.

    Args:
        family: The paths.
        surrogate: Their coarse retimer.
        clearance: The scene's clearance model.
        lower, upper: Joint limits (rad).
        tilt_bound: Largest cup tilt (rad).
        margin: Clearance (m) to keep (see the module docstring).
        spline: The planner's path, for the clearance threshold.
        span: The part of ``spline`` (s) whose clearance sets the threshold
            (None: between its first and last waypoint intervals).
    """

    def __init__(
        self,
        family: PathFamily,
        surrogate: CoarseRetimer,
        clearance: ClearanceModel,
        lower: np.ndarray,
        upper: np.ndarray,
        tilt_bound: float,
        margin: float,
        spline: GeometricPath,
        span: tuple[float, float] | None = None,
    ) -> None:
        self.family = family
        self.surrogate = surrogate
        self.clearance = clearance
        self.lower, self.upper = lower, upper
        self.tilt_bound = tilt_bound
        self.s = np.linspace(0.0, 1.0, SAMPLES)
        # Clearances are capped at the cutoff: far above the threshold plus
        # half a body's motion between samples, so that the cap never binds.
        self.cutoff = margin + CUTOFF_EXTRA
        tops = family.tops
        s_0, s_1 = (spline.knots[1], spline.knots[-2]) if span is None else span
        inner = self.s[(self.s > s_0) & (self.s < s_1)]
        along = family.chain.cup_pose(spline.value(inner))
        reference = np.concatenate(
            [
                clearance.clearance(tops, self.cutoff),
                clearance.swept(*along, self.cutoff),
            ]
        )
        self.threshold = min(margin, 0.8 * float(reference.min()))
        self._down = family.chain.gravity_W / np.linalg.norm(family.chain.gravity_W)
        #: s, the shortest feasible duration so far: worse paths are not
        #: checked for missed grasp rows (their duration is a lower bound).
        self.best = np.inf

    def __call__(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Values (s) and feasibility of the paths at parameters x (P, d)."""
        W = self.family.waypoints(x)
        durations, exact, used = self.surrogate.evaluate(W, self.best)
        q = evaluate_splines(W, self.s)[0]
        R_WC, p_WC = self.family.chain.cup_pose(q)
        tilt = np.arccos(np.clip(R_WC[..., :, 2] @ self._down, -1.0, 1.0)).max(1)
        penalty = np.where(
            tilt > self.tilt_bound, 1.0 + 10.0 * (tilt - self.tilt_bound), 0.0
        )
        beyond = np.maximum(q - self.upper, self.lower - q).max(axis=(1, 2))
        penalty += np.where(beyond > 0.0, 1.0 + 10.0 * beyond, 0.0)
        rejected = ~np.isfinite(durations)
        first, last = len(self.family.up), len(self.family.down)
        knots = chord_knots_batch(W)
        inner = (self.s > knots[:, first, None]) & (self.s < knots[:, -1 - last, None])
        inner = inner[:, :-1] & inner[:, 1:]  # segments between inner samples
        d = self.clearance.swept(R_WC, p_WC, self.cutoff, floor=self.threshold)
        deficit = self.threshold - np.where(inner, d, np.inf).min(axis=1)
        penalty += np.where(deficit > 0.0, 0.5 + 20.0 * deficit, 0.0)
        values = np.where(rejected, REJECTED, durations) + penalty
        feasible = (penalty == 0.0) & ~rejected & exact
        self.surrogate.share_rows(used[feasible])
        if feasible.any():
            self.best = min(self.best, float(durations[feasible].min()))
        return values, feasible


__all__ = ["CUTOFF_EXTRA", "Objective", "REJECTED", "SAMPLES"]
