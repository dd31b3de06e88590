"""The jerk-limited retimer's LPs on the compiled dual simplex, warm-started by keys.

:class:`BandLP` solves one retime's sequence of LPs

    minimise c z  subject to  A_ub z <= b_ub,  A_eq z = b_eq,  lower <= z <= upper

with :func:`._dual_simplex.dual_simplex`, whose rows must each span at
most :data:`WIDTH` neighbouring columns in the order ``columns`` (the jerk
LPs' ``z = [x_0..x_N, u_0..u_N]`` interleaved: ``x_0, u_0, x_1, u_1, ...``).
Each LP starts from the last optimum's active set, its rows matched by key
(:func:`._jerk_rows.key`): a cutting-plane method needs no rounds of its
own, since the dual simplex only ever takes the rows its vertex breaks.
The first LP (or one whose last active set lost a row) starts from
:func:`._band_lp_kernels.crash` around the guess (or the last optimum).
The rows are scaled to unit length. An infinite bound becomes an
artificial one: around the guess on a crash start (:data:`RADIUS` times
its largest |x|, or |u|, at least 1), else :data:`BOX` times the largest
finite bound; while an optimum keeps one active, or an infeasibility
proof leans on one, the box is widened (:data:`WIDEN`, three times) and
the LP solved again from there; then it is refused (the LP may be
unbounded). An answer is checked against every row and bound
(:data:`FEASIBLE`) before it is returned; any other outcome returns None
and the status's name, for the caller to solve the LP otherwise
(:class:`._jerk_lp.WarmLP` runs HiGHS).
"""

from __future__ import annotations

import numpy as np
from scipy import sparse

from rt_drake.retiming import _dual_simplex as simplex
from rt_drake.retiming._band_lp_kernels import NOT_HELD, band_solve
from rt_drake.retiming._jerk_rows import RowMatrix

#: Columns a row may span in the solver's column order.
WIDTH = 4
#: Excess of a row or bound at the optimum, relative to ``max(1, |bound|)``.
FEASIBLE = 1e-9
#: Tolerance of a multiplier (the costs are scaled to ``max |c| = 1``).
DUAL = 1e-9
#: An infinite bound's artificial value, times ``max(1, largest finite |bound|)``.
BOX = 1e6
#: On a crash start: its distance from the guess, times ``max(1, largest |x|)``
#: (or |u|) of the guess.
RADIUS = 1.0
#: The factor by which the artificial box widens when it binds.
WIDEN = 100.0
#: Iterations per LP, at most, times the number of columns.
ITERATIONS = 20
_SETTINGS = np.array(
    [WIDTH, FEASIBLE, DUAL, BOX, RADIUS, WIDEN, ITERATIONS], dtype=float
)

_NONE = np.zeros(0)
_NONE_INT = np.zeros(0, dtype=np.int64)
_NAMES = {
    NOT_HELD: "Not feasible within tolerance",
    simplex.INFEASIBLE: "Infeasible",
    simplex.ITERATION_CAP: "Iteration limit",
    simplex.SINGULAR: "Singular active set",
    simplex.ARTIFICIAL: "Unbounded or artificial bound active",
    simplex.TOO_WIDE: "A row spans too many columns",
}


class BandLP:
    """One retime's sequence of LPs on the compiled dual simplex (module docstring)."""

    def __init__(self, columns: np.ndarray | None = None) -> None:
        """``columns``: the solver's column order; None: z = [x, u] interleaved."""
        self._columns = columns
        #: The last optimum's active set: its rows' keys (sorted), its
        #: equality rows, its bounds (j upper, n + j lower), and 1 (0: none).
        self._previous = (_NONE_INT, _NONE_INT, _NONE_INT, np.zeros(1, dtype=np.int64))
        self._guess = _NONE
        #: Simplex iterations, LPs solved, LPs started without an active set.
        self.iterations = 0
        self.solves = 0
        self.cold = 0

    def guess(self, z: np.ndarray) -> None:
        """Centre of the next crash (an LP with no last active set): ``z``."""
        self._guess = np.ascontiguousarray(z, dtype=float)

    def solve(
        self,
        c: np.ndarray,
        A_ub: sparse.csr_matrix | RowMatrix,
        b_ub: np.ndarray,
        keys: np.ndarray,
        A_eq: sparse.csr_matrix,
        b_eq: np.ndarray,
        bounds: np.ndarray,
    ) -> tuple[np.ndarray | None, str]:
        """The optimum z, or None and why (``keys``: (R_ub,) the rows' names)."""
        n = len(c)
        columns = self._columns
        if columns is None or len(columns) != n:
            columns = self._columns = _interleaved(n)
        status, z, previous, steps, cold = band_solve(
            (A_ub.indptr, A_ub.indices, A_ub.data, np.asarray(b_ub, dtype=float)),
            (A_eq.indptr, A_eq.indices, A_eq.data, np.asarray(b_eq, dtype=float)),
            keys, np.ascontiguousarray(bounds, dtype=float),
            np.asarray(c, dtype=float), columns, self._previous,
            self._guess, _SETTINGS,
        )  # fmt: skip
        self._previous = previous
        self.iterations += int(steps)
        self.cold += int(cold)
        self.solves += 1
        if status != simplex.OPTIMAL:
            return None, _NAMES[int(status)]
        self._guess = z  # the next crash's centre, if one is needed
        return z, "Optimal"


def _interleaved(n: int) -> np.ndarray:
    """The column order ``x_0, u_0, x_1, u_1, ...`` of ``z = [x, u]`` (n even)."""
    half = n // 2
    return np.column_stack([np.arange(half), half + np.arange(half)]).ravel()


__all__ = ["BandLP"]
