"""The grasp rows of one held object: selection, stage rows, exactness check.

:class:`ObjectRows` is what :func:`~rt_drake.retiming.retime` does with the
grasp of a single object (see :mod:`._solve` for the argument): the rows that
ray shooting selects at the grid points (:func:`.stage_rows.rest_and_candidates`),
enforced at the grid points and the segments' midpoints; after each solve
every row is evaluated at every wrench the stage LPs enforced
(:func:`.stage_rows.wrench_ratios`, at :meth:`._between.Segments.enforced_wrenches`)
and the rows it missed are added. Between grid points the rows near their
bound (the check's ``screen``) go to :func:`._between.refinement_points`,
which adds grid points where one is exceeded.
:class:`~._robust_grasp.SetRows` does the same for a set of objects.
"""

from __future__ import annotations

import weakref
from typing import NamedTuple

import numpy as np
from toppra.constraint import LinearConstraint

from rt_drake.retiming import stage_rows as R
from rt_drake.retiming._at_rest import check_grasp_at_rest
from rt_drake.retiming._between import (
    ROW_SCREEN,
    grasp_midpoint_rows,
)
from rt_drake.retiming._row_groups import RowGroups
from rt_drake.retiming._samples import PathSamples
from rt_drake.retiming._segments import Segments
from rt_drake.retiming.limits import GraspConstraint
from rt_drake.retiming.passes import AffineConstraint

#: Grasp rows violated by more than this (N or N m) are added and re-solved.
ROW_TOLERANCE = 1e-9

#: The rows of each grasp grouped for the exactness check, kept while the
#: grasp lives (a GraspConstraint is immutable and hashed by identity).
_GROUPS: weakref.WeakKeyDictionary[GraspConstraint, RowGroups] = (
    weakref.WeakKeyDictionary()
)


class Check(NamedTuple):
    """The exactness check of one solve.

    Attributes:
        added: Whether rows were added (solve again).
        ratio: (G,) the largest ``F_k w / g_k`` at each grid point (the
            acceleration of the segment that starts there).
        screen: Where to look between grid points: each row's largest
            ``F_k w / g_k`` over the wrenches enforced (R,), exact where above
            ``1 - ROW_SCREEN`` (for a set of objects, an upper bound of its
            worst object's).
    """

    added: bool
    ratio: np.ndarray
    screen: np.ndarray


class ObjectRows:
    """Grasp rows of one object (module docstring).

    Attributes:
        grasp: The constraint.
        normals: (6, R) ``(F / g)ᵀ``.
        selected: Rows chosen by ray shooting so far (every solve starts from
            them).
        rows: The rows of the current solve (``selected`` plus repairs).
        repairs: Times the current solve added rows.
        groups: The rows grouped for the exactness check (at the first
            check of the first retime with this grasp, then reused by every
            later one: :func:`.stage_rows.wrench_groups`; any grouping gives the
            same results, the wrenches only weight the split).
    """

    robust = False

    def __init__(self, grasp: GraspConstraint) -> None:
        self.grasp = grasp
        self.normals = R.normalised_rows(grasp.F, grasp.g)
        self.selected = np.zeros(0, dtype=int)
        self.rows = self.selected
        self.repairs = 0
        self.groups: RowGroups | None = _GROUPS.get(grasp)

    def add(self, samples: PathSamples) -> None:
        """Check holding at rest at new samples; select their rows."""
        assert samples.wrench is not None
        rest, rows = R.rest_and_candidates(*samples.wrench, self.normals, samples.x_cap)
        check_grasp_at_rest(samples.s, rest, samples.wrench.c, self.grasp)
        self.selected = (
            rows if not self.selected.size else np.union1d(self.selected, rows)
        )

    def begin(self) -> None:
        """Start a solve from the selection."""
        self.rows, self.repairs = self.selected, 0

    def constraints(
        self, samples: PathSamples, segments: Segments
    ) -> list[LinearConstraint]:
        """The rows at the grid points and at the segments' midpoints."""
        assert samples.wrench is not None
        F, g = self.grasp.F[self.rows], self.grasp.g[self.rows]
        return [
            AffineConstraint(*samples.wrench, F, g),
            grasp_midpoint_rows(segments, samples.wrench, F, g),
        ]

    def widen(self) -> bool:
        """After an uncontrollable solve: confirm with every row (once)."""
        if len(self.rows) < len(self.grasp.g):
            self.rows = np.arange(len(self.grasp.g))
            self.repairs += 1
            return True
        return False

    def check(
        self, samples: PathSamples, segments: Segments, x: np.ndarray, u: np.ndarray
    ) -> Check:
        """Every row at every enforced wrench; add the rows missed."""
        assert samples.wrench is not None
        enforced = segments.enforced_wrenches(samples.wrench, x, u)
        if self.groups is None:  # grouped at the first check, then reused
            self.groups = R.wrench_groups(enforced, self.normals, self.grasp.g)
            _GROUPS[self.grasp] = self.groups
        ratio, violated, row_max = R.wrench_ratios(
            enforced,
            self.normals,
            self.grasp.g,
            ROW_TOLERANCE,
            1.0 - ROW_SCREEN,
            self.groups,
            exact=len(samples.s),  # the margins need the grid points' maxima
        )
        missed = np.setdiff1d(violated, self.rows) if violated.size else violated
        if missed.size:
            self.rows = np.union1d(self.rows, missed)
            self.repairs += 1
        return Check(bool(missed.size), ratio[: len(samples.s)], row_max)

    @property
    def row_count(self) -> int:
        """Rows the last solve used."""
        return len(self.rows)

    @property
    def object_count(self) -> int:
        """Objects whose rows the LPs used."""
        return 1


__all__ = ["ROW_TOLERANCE", "Check", "ObjectRows"]
