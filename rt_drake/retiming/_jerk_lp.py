"""The jerk-limited retimer's LPs, solved by HiGHS and started from the last basis.

Consecutive LPs of a retime (:mod:`._jerk`) differ little: the jerk rows'
coefficients move with the previous profile, and rows are added between
rounds. Each row carries a key (:func:`._jerk_rows.key`); the next LP starts
from the previous optimal basis (HiGHS's basic variables, each nonbasic one
at its bound), matched row by row through the keys (new rows basic, i.e.
their slack in the basis; the columns keep their status). The rows a sub-LP
leaves out were basic, so the count stays right and HiGHS takes the basis
as it is (no "alien" repair); a warm LP takes a few dual simplex iterations
instead of several hundred. Rows enter as cutting planes
(:meth:`WarmLP.solve`): an LP first takes those tight at its start, then
those its optimum breaks. The LP is

    minimise c z  subject to  A_ub z <= b_ub,  A_eq z = b_eq,  lower <= z <= upper.
"""

from __future__ import annotations

import highspy
import numpy as np
from scipy import sparse

from rt_drake.retiming._band_lp import BandLP
from rt_drake.retiming._jerk_row_kernels import csr_product, csr_rows
from rt_drake.retiming._jerk_rows import RowMatrix

_STATUS = np.array(
    [highspy.HighsBasisStatus(v) for v in range(5)], dtype=object
)  # kLower, kBasic, kUpper, kZero, kNonbasic
_BASIC = 1
#: Relative distance to a bound under which a crash start makes a row nonbasic
#: (and the first sub-LP takes it).
GUESS = 1e-2
#: Relative distance to a bound at the last optimum under which the next
#: LP's first sub-LP takes a row (its basic rows near a bound: many grasp
#: rows at a point are; those it then breaks join as cuts).
WARM_GUESS = 1e-3
#: Relative excess (over ``max(1, |bound|)``) of a row that a sub-LP's
#: optimum may leave before the row joins (HiGHS's primal tolerance).
FEASIBLE = 1e-7


class WarmLP:
    """One retime's sequence of LPs (not thread-safe).

    Each LP goes to the compiled dual simplex (:class:`._band_lp.BandLP`)
    first, unless ``compiled`` is False; an LP it does not answer (see
    there), and every LP when ``compiled`` is False, goes to HiGHS.
    """

    def __init__(self, compiled: bool = True) -> None:
        """``compiled``: try :class:`._band_lp.BandLP` before HiGHS."""
        self._band = BandLP() if compiled else None
        #: LPs the compiled solver did not answer (solved by HiGHS).
        self.fallbacks = 0
        self._solver: highspy.Highs | None = None  # made when first needed
        #: The last LP's inequality rows (keys, in the model's order) and
        #: their basis statuses; its equality rows' and columns' statuses.
        self._keys: np.ndarray | None = None
        self._rows = np.zeros(0, dtype=int)
        self._eq = np.zeros(0, dtype=int)
        self._cols = np.zeros(0, dtype=int)
        self._start: np.ndarray | None = None
        self._head = 0  # inequality rows passed with the model
        #: Simplex iterations and sub-LPs so far.
        self.iterations = 0
        self.solves = 0

    @property
    def _highs(self) -> highspy.Highs:
        """HiGHS, made on first use (the compiled solver answers most retimes)."""
        if self._solver is None:
            highs = self._solver = highspy.Highs()
            highs.setOptionValue("output_flag", False)
            highs.setOptionValue("presolve", "off")
            highs.setOptionValue("solver", "simplex")
            highs.setOptionValue("simplex_dual_edge_weight_strategy", 1)  # Devex
        return self._solver

    @_highs.setter
    def _highs(self, highs: highspy.Highs) -> None:
        """Use ``highs`` (tests wrap HiGHS to make it misbehave)."""
        self._solver = highs

    def guess(self, z: np.ndarray) -> None:
        """Start the first LP near ``z`` (rows tight there in, and nonbasic)."""
        self._start = np.asarray(z, dtype=float)
        if self._band is not None:
            self._band.guess(self._start)

    def solve(
        self,
        c: np.ndarray,
        A_ub: sparse.csr_matrix | RowMatrix,
        b_ub: np.ndarray,
        keys: np.ndarray,
        A_eq: sparse.csr_matrix,
        b_eq: np.ndarray,
        bounds: np.ndarray,
        always: np.ndarray,
    ) -> tuple[np.ndarray | None, str]:
        """The optimum z, or None and HiGHS's model status when there is none.

        ``keys``: (R_ub,) distinct names of the rows of ``A_ub``; the
        equality rows keep their order from one LP to the next. ``bounds``:
        (n, 2) lower and upper bounds of z (inf for none). ``always``:
        (R_ub,) rows every sub-LP takes (enough to bound it).

        Cutting planes: the first sub-LP takes ``always``, the rows within
        :data:`WARM_GUESS` of their bound at the last optimum (or within
        :data:`GUESS` at the guess) and those that point breaks; the
        rows its optimum breaks by more than :data:`FEASIBLE` are added
        (HiGHS keeps its basis) and it is solved again, until none is
        broken: then its optimum is the LP's.
        """
        if self._band is not None:
            z, _ = self._band.solve(c, A_ub, b_ub, keys, A_eq, b_eq, bounds)
            if z is not None:
                self._keys, self._start = None, z  # HiGHS, if next: near z
                return z, "Optimal"
            self.fallbacks += 1
        working = always.copy()
        slack = np.maximum(1.0, np.abs(b_ub))
        if self._start is not None:
            near = GUESS if self._keys is None else WARM_GUESS
            working |= _product(A_ub, self._start) >= b_ub - near * slack
        if self._keys is not None:
            working |= _member(keys, self._keys[self._rows != _BASIC])
        order = np.flatnonzero(working)
        z, status = self._load(c, A_ub, order, b_ub, keys, A_eq, b_eq, bounds)
        while True:
            if z is None:
                if working.all():
                    self._keys = None
                    return None, status
                working[:] = True  # a sub-LP unbounded: take every row
                order = np.arange(len(b_ub))
                z, status = self._load(c, A_ub, order, b_ub, keys, A_eq, b_eq, bounds)
                continue
            broken = self._cuts(working, _product(A_ub, z), b_ub, slack, keys)
            if not broken.size:
                break
            working[broken] = True
            order = np.concatenate([order, broken])
            start, index, value = _rows_of(A_ub, broken)
            self._highs.addRows(
                len(broken), np.full(len(broken), -np.inf), b_ub[broken],
                len(index), start[:-1], index, value,
            )  # fmt: skip
            z, status = self._run()
        # The next LP's basis: this optimum's, HiGHS's basic variables and
        # the bound each nonbasic one is at. The model's rows: the first
        # sub-LP's inequalities, the equalities, then the cuts added
        # (``order`` lists the inequalities likewise).
        assert z is not None
        head, eq = self._head, len(b_eq)
        # (highspy's stubs omit getBasicVariables: the binding has it)
        basic = np.asarray(self._highs.getBasicVariables()[1])  # type: ignore[attr-defined]
        row_value = np.asarray(self._highs.getSolution().row_value)
        row_lower = np.full(len(row_value), -np.inf)
        row_upper = np.concatenate([b_ub[order[:head]], b_eq, b_ub[order[head:]]])
        row_lower[head : head + eq] = b_eq
        rows = _status(row_value, row_lower, row_upper, -1 - basic[basic < 0])
        self._rows = np.concatenate([rows[:head], rows[head + eq :]])
        self._eq = rows[head : head + eq]
        self._cols = _status(z, bounds[:, 0], bounds[:, 1], basic[basic >= 0])
        self._keys = keys[order]
        self._start = z
        return z, status

    def _cuts(
        self,
        working: np.ndarray,
        value: np.ndarray,
        b_ub: np.ndarray,
        slack: np.ndarray,
        keys: np.ndarray,
    ) -> np.ndarray:
        """The rows that join after a sub-LP: those its optimum breaks.

        ``value``: (R_ub,) ``A_ub z`` at its optimum; a row out of the
        sub-LP (``~working``) breaks when ``value > b_ub + FEASIBLE *
        slack`` (``slack = max(1, |b_ub|)``). ``keys`` name the rows (a
        subclass may add others with them: ``benchmarks/bench_jerk_replay.py``).
        """
        return np.flatnonzero(~working & (value > b_ub + FEASIBLE * slack))

    def _load(
        self,
        c: np.ndarray,
        A_ub: sparse.csr_matrix | RowMatrix,
        order: np.ndarray,
        b_ub: np.ndarray,
        keys: np.ndarray,
        A_eq: sparse.csr_matrix,
        b_eq: np.ndarray,
        bounds: np.ndarray,
    ) -> tuple[np.ndarray | None, str]:
        """Pass the sub-LP (the rows ``order`` of A_ub, then A_eq) to HiGHS, run.

        It starts from the last basis or the guess.
        """
        b_ub, keys = b_ub[order], keys[order]
        start, index, value = _rows_of(A_ub, order)
        n = A_ub.shape[1]
        m = len(order) + A_eq.shape[0]
        start = np.concatenate([start[:-1], start[-1] + A_eq.indptr[:-1]])
        index = np.concatenate([index, A_eq.indices]).astype(np.int32)
        value = np.concatenate([value, A_eq.data]).astype(float)
        lower = np.concatenate([np.full(len(b_ub), -np.inf), b_eq])
        upper = np.concatenate([b_ub, b_eq])
        self._head = len(b_ub)
        self._highs.passModel(
            n, m, len(index), int(highspy.MatrixFormat.kRowwise),
            int(highspy.ObjSense.kMinimize), 0.0,
            np.asarray(c, dtype=float), np.asarray(bounds[:, 0], dtype=float),
            np.asarray(bounds[:, 1], dtype=float), lower, upper,
            start.astype(np.int32), index, value,
            np.zeros(n, dtype=np.int32),  # continuous
        )  # fmt: skip
        cols = rows = None
        if self._keys is not None:
            eq = np.full(len(b_eq), _BASIC)
            eq[: len(self._eq)] = self._eq[: len(b_eq)]
            cols, rows = self._cols, np.concatenate([self._row_status(keys), eq])
        elif self._start is not None:  # crash: the rows within GUESS of a bound
            cols = _at_bound(self._start, bounds[:, 0], bounds[:, 1], GUESS)
            value_at = np.concatenate(
                [_product(A_ub, self._start)[order], _product(A_eq, self._start)]
            )
            rows = _at_bound(value_at, lower, upper, GUESS)
        if cols is not None and rows is not None:
            basis = highspy.HighsBasis()
            basis.col_status = _STATUS[cols].tolist()
            basis.row_status = _STATUS[rows].tolist()
            # A basis carried over keeps its count (the rows left out were
            # basic, new ones are): HiGHS takes it as it is. The crash start
            # (or a count gone wrong) is "alien": HiGHS repairs it.
            basic = np.count_nonzero(rows == _BASIC) + np.count_nonzero(cols == _BASIC)
            basis.alien = self._keys is None or basic != m
            self._highs.setBasis(basis)
        return self._run()

    def _run(self) -> tuple[np.ndarray | None, str]:
        """Run HiGHS on its model: the optimum, or None and the model status."""
        highs = self._highs
        for warm in (True, False):
            if not warm:
                # No answer from the warm start (e.g. "Not Set" after a basis
                # it could not repair, on one Table I MOVE under the bellows
                # scenario): the same model once more from scratch.
                highs.clearSolver()
            highs.run()
            status = highs.getModelStatus()
            self.iterations += int(highs.getInfoValue("simplex_iteration_count")[1])
            self.solves += 1
            if status in _ANSWERS:
                break
        if status != highspy.HighsModelStatus.kOptimal:
            return None, highs.modelStatusToString(status)
        return np.asarray(highs.getSolution().col_value), "Optimal"

    def _row_status(self, keys: np.ndarray) -> np.ndarray:
        """The last LP's status of each row with the same key; basic if new."""
        assert self._keys is not None
        order = np.argsort(self._keys)
        sorted_keys = self._keys[order]
        at = np.clip(np.searchsorted(sorted_keys, keys), 0, len(order) - 1)
        found = sorted_keys[at] == keys
        status = np.full(len(keys), _BASIC)
        status[found] = self._rows[order[at[found]]]
        return status


#: HiGHS's statuses that answer the LP (the others retry from scratch).
_ANSWERS = (
    highspy.HighsModelStatus.kOptimal,
    highspy.HighsModelStatus.kInfeasible,
    highspy.HighsModelStatus.kUnbounded,
    highspy.HighsModelStatus.kUnboundedOrInfeasible,
)


def _member(keys: np.ndarray, of: np.ndarray) -> np.ndarray:
    """``np.isin(keys, of)`` for int64 keys, by a binary search in ``of`` sorted."""
    if not of.size:
        return np.zeros(len(keys), dtype=bool)
    ordered = np.sort(of)
    at = np.minimum(np.searchsorted(ordered, keys), len(ordered) - 1)
    return ordered[at] == keys


def _rows_of(
    A: sparse.csr_matrix | RowMatrix, rows: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The rows ``rows`` of A in CSR form: starts (len(rows) + 1,), indices, values.

    The same arrays as ``A[rows]``'s (entries in their order within a row),
    without scipy's indexing; indices and starts as int32 (HiGHS's).
    """
    return csr_rows(A.indptr, A.indices, A.data, np.asarray(rows, dtype=np.int64))


def _product(A: sparse.csr_matrix | RowMatrix, z: np.ndarray) -> np.ndarray:
    """``A @ z`` (the same sums as scipy's), without scipy's dispatch."""
    return csr_product(A.indptr, A.indices, A.data, np.asarray(z, dtype=float))


def _status(
    value: np.ndarray, lower: np.ndarray, upper: np.ndarray, basic: np.ndarray
) -> np.ndarray:
    """Basis status codes of a basis: 1 for ``basic`` (indices), else its bound.

    A nonbasic variable or row is at the nearer of its bounds (0 lower, 2
    upper); 3 (zero) if it has none.
    """
    with np.errstate(invalid="ignore"):
        status = np.where(value - lower <= upper - value, 0, 2)
    status[np.isinf(lower) & np.isinf(upper)] = 3
    status[np.isinf(lower) & np.isfinite(upper)] = 2
    status[np.isfinite(lower) & np.isinf(upper)] = 0
    status[basic] = _BASIC
    return status


def _at_bound(
    value: np.ndarray, lower: np.ndarray, upper: np.ndarray, tolerance: float = 1e-9
) -> np.ndarray:
    """Basis status codes: 0 at the lower bound, 2 at (or over) the upper, 1 else.

    Within ``tolerance`` relative to ``max(1, |bound|)``.
    """
    status = np.full(len(value), _BASIC)
    with np.errstate(invalid="ignore"):
        status[value <= lower + tolerance * np.maximum(1.0, np.abs(lower))] = 0
        status[value >= upper - tolerance * np.maximum(1.0, np.abs(upper))] = 2
    return status


__all__ = ["WarmLP"]
