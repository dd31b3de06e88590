"""The cycle's motions retimed on their grids, and what the grasp costs them.

:class:`MotionRetimer` holds the arm plant, its joint limits (and those of
a grasp-constrained motion, :func:`~rt_drake.simulation.move_grasp.grasp_limits`),
the grid size and a scratch context, and retimes a path with
:func:`~rt_drake.retiming.retime` on the grid each motion takes.

Grids. TOPP-RA gives one path acceleration per grid segment, so on 100
uniform points it leaves about 6 % of a motion unused where the profile
changes fast (the ends, the turns at the lines). The pick is retimed on an
adaptive grid (:meth:`MotionRetimer.retime_free`): under the acceleration
limits on 400 points placed by a 100-point profile
(:func:`~rt_drake.shaping.retime_adaptive`; 4-6 % shorter); with jerk
limits on ``gridpoints`` points placed by that profile, as a shaped MOVE
(1.5-2 % shorter than on the uniform grid, for 0.00-0.04 s more CPU per
pick, ``tools/pick_jerk_cost.py``), except the staged first pick's REACH,
which is planned while the APPROACH runs and gains 0.5 ms there: it keeps
the uniform grid (``on_profile=False``). A shaped MOVE's jerk-limited retime
takes ``gridpoints`` points placed by the optimiser's final (adaptive,
acceleration-limited) profile (:meth:`MotionRetimer.retime_on_profile`,
:func:`~rt_drake.shaping.adaptive_grid`): as many as the uniform grid, at
about the same CPU, 0.1-4 % shorter. Every grid holds the limits between
its points as any other (:func:`~rt_drake.retiming.retime`).
"""

from __future__ import annotations

import dataclasses

import numpy as np
from pydrake.multibody.plant import MultibodyPlant
from pydrake.systems.framework import Context

from rt_drake.dynamics.cup_frame import CupFrame
from rt_drake.dynamics.wrench import path_wrench_coefficients
from rt_drake.planning import GeometricPath
from rt_drake.retiming import (
    GraspConstraint,
    JointLimits,
    RetimeError,
    RetimeResult,
    retime,
)
from rt_drake.shaping import (
    ADAPTIVE_WEIGHT,
    END_HALVINGS,
    adaptive_grid,
    jerk_grid,
    retime_adaptive,
)

#: Passes of :meth:`MotionRetimer._refined` (the jerk-limited retime's grid).
JERK_GRID_PASSES = 2


@dataclasses.dataclass(frozen=True)
class MotionRetimer:
    """Retimes the cycle's paths (rad) on their grids.

    Attributes:
        plant: the arm plant (the retimer's).
        limits: the joint limits of a motion without a grasp.
        grasp_limits: those of a grasp-constrained motion.
        gridpoints: TOPP-RA's uniform grid size.
        context: a scratch context of ``plant``.
        cup: the cup frame C.
    """

    plant: MultibodyPlant
    limits: JointLimits
    grasp_limits: JointLimits
    gridpoints: int
    context: Context
    cup: CupFrame

    def retime_path(
        self, path: GeometricPath, grasp: GraspConstraint | None
    ) -> RetimeResult:
        """Retime ``path`` under the joint limits (and ``grasp`` if given).

        With ``grasp``, the jerk limits are also tightened by the scenario's
        ``planning.grasp_ramp_s``
        (:func:`~rt_drake.simulation.move_grasp.grasp_limits`). The retimer adds the
        path's knots to the ``gridpoints`` uniform points and holds every
        limit between grid points too.
        """
        return retime(
            self.plant,
            path,
            self.limits if grasp is None else self.grasp_limits,
            grasp,
            gridpoints=self.gridpoints,
            context=self.context,
            cup=self.cup,
        )

    def retime_free(
        self,
        path: GeometricPath,
        on_profile: bool = True,
        profile: RetimeResult | None = None,
    ) -> RetimeResult:
        """Retime ``path`` without a held object (the pick).

        Under the acceleration limits on an adaptive grid
        (:func:`~rt_drake.shaping.retime_adaptive`; ``profile`` if given: that
        retime of ``path`` already done, e.g. the pick shaping's); with jerk
        limits on ``gridpoints`` points placed by that profile
        (:meth:`retime_on_profile`), or, without ``on_profile``, on the
        uniform grid (:meth:`retime_path`). Module docstring.
        """
        if self.limits.jerk is not None and not on_profile:
            return self.retime_path(path, None)
        if profile is None:
            profile = retime_adaptive(
                self.plant,
                path,
                self.limits.without_jerk(),
                None,
                context=self.context,
                cup=self.cup,
            )
        if self.limits.jerk is None:
            return profile
        return self.retime_on_profile(path, None, profile)

    def retime_on_profile(
        self, path: GeometricPath, grasp: GraspConstraint | None, profile: RetimeResult
    ) -> RetimeResult:
        """Retime ``path`` on ``gridpoints`` points placed by ``profile``'s s'(s).

        :func:`~rt_drake.shaping.adaptive_grid` (equal steps of time and of
        the variation of ``s'^2`` along ``profile``, the same path's retime
        under the acceleration limits); if the retimer fails numerically on
        that grid, on the uniform one (:meth:`retime_path`). With ``grasp``,
        under the limits of a grasp-constrained motion, as
        :meth:`retime_path` (``planning.grasp_ramp_s``).
        """
        grid = adaptive_grid(
            profile.gridpoints, profile.sd, self.gridpoints, ADAPTIVE_WEIGHT
        )
        limits = self.limits if grasp is None else self.grasp_limits
        try:
            result = self._retime_on(path, grasp, limits, grid)
        except RetimeError:
            return self.retime_path(path, grasp)
        if limits.jerk is None:
            return result
        return self._refined(path, grasp, limits, grid, result)

    def _refined(
        self,
        path: GeometricPath,
        grasp: GraspConstraint | None,
        limits: JointLimits,
        grid: np.ndarray,
        result: RetimeResult,
    ) -> RetimeResult:
        """``result`` retimed again on its :func:`~rt_drake.shaping.jerk_grid`, twice.

        Each pass refines the last pass's grid (the first also halves its
        end segments at rest, :data:`~rt_drake.shaping.END_HALVINGS` times;
        if the retimer refuses those ends, the pass runs again without
        them) and starts its LPs from the shortest profile so far
        (``jerk_start``); the shortest of the three (each holds every
        limit). A pass the retimer refuses otherwise, or that adds no point,
        ends the refinement.
        """
        best = result
        halvings = END_HALVINGS  # the ends in the first pass that runs
        passes = 0
        while passes < JERK_GRID_PASSES:
            refined = jerk_grid(best.gridpoints, best.sd, grid, end_halvings=halvings)
            if len(refined) <= len(grid):
                break
            try:
                again = self._retime_on(path, grasp, limits, refined, start=best)
            except RetimeError:
                if halvings == 0:
                    break
                halvings = 0  # ends too fine for the LPs: the pass without them
                continue
            passes += 1
            halvings = 0
            if again.duration < best.duration:
                best = again
            grid = refined
        return best

    def _retime_on(
        self,
        path: GeometricPath,
        grasp: GraspConstraint | None,
        limits: JointLimits,
        grid: np.ndarray,
        start: RetimeResult | None = None,
    ) -> RetimeResult:
        """:func:`~rt_drake.retiming.retime` on ``grid``, LPs from ``start``."""
        return retime(
            self.plant,
            path,
            limits,
            grasp,
            gridpoints=grid,
            context=self.context,
            cup=self.cup,
            jerk_start=start,
        )

    def grasp_price(
        self,
        path: GeometricPath,
        grasp: GraspConstraint,
        with_grasp: RetimeResult | None = None,
    ) -> float:
        """What ``grasp`` costs on ``path`` (s): the duration with it less without.

        At the acceleration limits (no jerk limits): with the grasp by
        :func:`~rt_drake.shaping.retime_adaptive` (``with_grasp``: that retime
        already done, e.g. the optimiser's), without it on the same grid
        points, so that both solve the same discretisation and the price is
        never negative (on grids of their own the two differed by up to
        5 ms either way). A report figure, not part of the motion: its wall
        time is not counted as planning.
        """
        plain = dataclasses.replace(self.limits, jerk=None)
        if with_grasp is None:
            with_grasp = retime_adaptive(
                self.plant, path, plain, grasp, context=self.context, cup=self.cup
            )
        without = retime(
            self.plant,
            path,
            plain,
            None,
            gridpoints=with_grasp.gridpoints,
            context=self.context,
            cup=self.cup,
        )
        return with_grasp.duration - without.duration

    def velocity_bound(self, path: GeometricPath, s: np.ndarray) -> np.ndarray:
        """Largest s' (1/s) the joint velocity limits allow at each s."""
        dq = np.abs(path.deriv(s))
        with np.errstate(divide="ignore"):
            return np.min(self.limits.velocity / dq, axis=1)

    def grasp_margin(
        self, path: GeometricPath, result: RetimeResult, grasp: GraspConstraint
    ) -> np.ndarray:
        """``min_r (g_r - F_r w) / g_r`` at each grid point of ``result``.

        w is the wrench ``grasp``'s object needs along ``path`` timed by
        ``result`` (``a u + b x + c``, with the segment's u; the last grid
        point takes the last segment's u). Negative: the grasp constraint is
        violated there.
        """
        s = result.gridpoints
        a, b, c = path_wrench_coefficients(
            self.plant,
            grasp.held,
            path.value(s),
            path.deriv(s),
            path.deriv2(s),
            self.context,
            self.cup,
        )
        u = np.append(result.sdd, result.sdd[-1])[:, None]
        if result.path_acceleration is not None:  # jerk-limited: s'' at s_i
            u = result.path_acceleration[:, None]
        x = (result.sd**2)[:, None]
        w = a * u + b * x + c
        return np.min((grasp.g - w @ grasp.F.T) / grasp.g, axis=1)


__all__ = ["MotionRetimer"]
