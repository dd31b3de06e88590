"""TOPP-RA's reachability passes (toppra 0.6.10) with precomputed constraints.

Constraints carry precomputed coefficients: :class:`AffineConstraint` is
``F (a_i u + b_i x + c_i) <= g`` with one constant F, g and a, b, c given per
grid point; :class:`XBound` carries ``0 <= x <= x_max(s_i)`` (the joint
velocity limits). Both are toppra ``LinearConstraint`` objects, so toppra
itself can run them.

:func:`reachability` runs the algorithm of ``toppra.algorithm.TOPPRA``
(``compute_parameterization``): the backward pass of controllable sets K_i,
then the greedy forward pass with toppra's numerical safeguards (x_{i+1}
reduced by 1e-8 or 0.01 % and clamped into K_{i+1}; a failed step retried
with x_i reduced), on the interpolation discretization.

- :attr:`Engine.COMPILED` (default): :func:`stage_rows` projects the
  constraints to the rows of every stage's 2-variable LP and
  :func:`rt_drake.retiming.seidel.passes` runs both passes compiled (numba),
  with toppra's seidel LP transcribed. It
  skips the LP for min K_i while K_{i+1} contains 0 ((u, x) = (0, 0) is then
  admissible at stage i: the retimer checked that object and arm can be held
  at rest at every grid point, so min K_i = 0), and retries an LP found
  infeasible once without its warm start (toppra 0.6.10's warm start can
  report a feasible LP infeasible, and its TOPPRA class then fails the path).
  Its LP drops two absolute tolerances of toppra's that called feasible
  stage LPs infeasible on rows of small coefficients (a joint that barely
  moves, so ``|q'|, |q''| ~ 1e-5``; grasp rows of norm 0.01 at an angle of
  1e-7): see :mod:`rt_drake.retiming.seidel`; on every LP toppra's rules
  solve, the answer is unchanged to the bit.
- :attr:`Engine.TOPPRA`: toppra's own ``TOPPRA`` class with its seidel wrapper
  (the reference).
"""

from __future__ import annotations

import enum
from typing import NamedTuple

import numpy as np
import toppra
from toppra.algorithm import TOPPRA
from toppra.constraint import DiscretizationType, LinearConstraint
from toppra.constraint.linear_constraint import canlinear_colloc_to_interpolate

from rt_drake.retiming import seidel
from rt_drake.retiming._retime_errors import RetimeInputError

#: toppra's box on (u, x) at every stage (cy_seidel_solverwrapper VAR_MIN/MAX).
VAR_BOUND = 1e8


class Engine(enum.Enum):
    """Which implementation runs TOPP-RA's passes (see the module docstring).

    Both give the same profile (tests compare them to 1e-9).
    """

    #: rt_drake's compiled passes (numba), the default.
    COMPILED = "compiled"
    #: toppra's own ``TOPPRA`` class (the reference; slower).
    TOPPRA = "toppra"

    @classmethod
    def of(cls, engine: Engine | str) -> Engine:
        """``engine`` as an :class:`Engine`; its value (``"toppra"``) also works.

        Raises:
            RetimeInputError: naming ``engine``, the value and the allowed ones.
        """
        if isinstance(engine, cls):
            return engine
        if isinstance(engine, str):
            for member in cls:
                if engine == member.value:
                    return member
        allowed = ", ".join(f"Engine.{m.name} ({m.value!r})" for m in cls)
        raise RetimeInputError(f"engine must be one of {allowed}, got {engine!r}")


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
        # Writable C-contiguous float64: the array type the kernels compile for.
        self.coefficients = tuple(seidel.kernel_array(v) for v in (a, b, c, F, g))

    def compute_constraint_params(self, path, gridpoints, *args, **kwargs):  # noqa: D102
        return canlinear_colloc_to_interpolate(
            *self.coefficients, None, None, np.asarray(gridpoints), identical=True
        )


class XBound(LinearConstraint):
    """``x_lo(s_i) <= x <= x_hi(s_i)``; x_bound is (G, 2)."""

    def __init__(self, x_bound: np.ndarray) -> None:
        super().__init__()
        self.x_bound = seidel.kernel_array(x_bound)

    def compute_constraint_params(self, path, gridpoints, *args, **kwargs):  # noqa: D102
        return None, None, None, None, None, None, self.x_bound


class StageRows(LinearConstraint):
    """Rows ``A_i u + B_i x + C_i <= 0`` of stage i's own (u_i, x_i), i < N.

    For constraints at points inside segment i (the retimer's cuts between
    grid points, :mod:`._between`), expressed in the stage's variables; a row
    with ``A = B = 0, C = -1`` is inactive. Toppra sees them as collocation
    constraints ``I (a_i u + b_i x + c_i) <= 0`` (the last grid point has
    none).

    Args:
        A, B, C: (N, k) rows of the N stages.
    """

    def __init__(self, A: np.ndarray, B: np.ndarray, C: np.ndarray) -> None:
        super().__init__()
        self.discretization_type = DiscretizationType.Collocation
        self.identical = True
        self.rows = tuple(seidel.kernel_array(v) for v in (A, B, C))

    def compute_constraint_params(self, path, gridpoints, *args, **kwargs):  # noqa: D102
        width = self.rows[0].shape[1]
        inactive = [np.zeros((1, width)), np.zeros((1, width)), -np.ones((1, width))]
        a, b, c = (
            np.vstack([rows, last])
            for rows, last in zip(self.rows, inactive, strict=True)
        )
        return a, b, c, np.eye(width), np.zeros(width), None, None


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


class StageLPs(NamedTuple):
    """Every stage's LP: rows ``A u + B x + C <= 0``, box ``lo <= (u, x) <= hi``.

    Attributes:
        A, B, C: (N+1, R); rows 0, 1 are left for the next controllable set
            and the last stage's rows are inactive (0 u + 0 x - 1 <= 0).
        lo, hi: (N+1, 2) boxes on (u, x): toppra's +-1e8 and the x bounds.
    """

    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    lo: np.ndarray
    hi: np.ndarray


def reachability(
    constraints: list[LinearConstraint],
    path: toppra.SplineInterpolator | None,
    gridpoints: np.ndarray,
    sd_start: float = 0.0,
    sd_end: float = 0.0,
    engine: Engine = Engine.COMPILED,
    base: StageLPs | None = None,
) -> Reachability:
    """Run TOPP-RA (see the module docstring).

    Args:
        constraints: Precomputed toppra constraints (they ignore ``path``).
        path: The toppra path; only :attr:`Engine.TOPPRA` needs it.
        gridpoints: (N+1,) grid s_i.
        sd_start: Path velocity at s = 0 (1/s).
        sd_end: Path velocity at s = 1 (1/s).
        engine: Which passes run (an :class:`Engine` or its value).
        base: Constraints already projected by :func:`stage_rows` on this
            grid, which come before ``constraints`` (compiled engine only:
            constraints fixed while others change are projected once).
    """
    engine = Engine.of(engine)
    if engine is Engine.TOPPRA:
        algorithm = TOPPRA(constraints, path, gridpoints, solver_wrapper="seidel")
        sdd, sd, _, K = algorithm.compute_parameterization(
            sd_start, sd_end, return_data=True
        )
        if sd is None or np.isnan(sd).any():
            bad = np.flatnonzero(np.isnan(K).any(axis=1))
            return Reachability(None, None, K, int(bad.max()) if bad.size else 0)
        return Reachability(sd**2, sdd, K, None)
    ds = np.diff(gridpoints)
    x, u, K, failed = seidel.passes(
        *stage_rows(constraints, ds, base), ds, float(sd_start), float(sd_end)
    )
    if failed >= 0:
        return Reachability(None, None, K, int(failed))
    return Reachability(x, u, K, None)


def stage_rows(
    constraints: list[LinearConstraint],
    ds: np.ndarray,
    base: StageLPs | None = None,
) -> StageLPs:
    """Rows ``A u + B x + C <= 0`` and boxes of every stage's LP.

    Args:
        constraints: The constraints, projected in this order.
        ds: (N,) grid steps.
        base: Rows already projected (by this function, on the same grid):
            they come first, then those of ``constraints``; not modified.
    """
    stages = len(ds)
    width = 2 if base is None else base.A.shape[1]
    for c in constraints:
        if isinstance(c, AffineConstraint):
            width += 2 * len(c.coefficients[4])
        elif isinstance(c, StageRows):
            width += c.rows[0].shape[1]
    if base is None:
        A = np.zeros((stages + 1, width))
        B = np.zeros((stages + 1, width))
        C = np.full((stages + 1, width), -1.0)
        lo = np.full((stages + 1, 2), -VAR_BOUND)
        hi = np.full((stages + 1, 2), VAR_BOUND)
        column = 2
    else:
        A, B, C = (np.empty((stages + 1, width)) for _ in range(3))
        column = base.A.shape[1]
        for target, rows, inactive in zip(
            (A, B, C), base[:3], (0.0, 0.0, -1.0), strict=True
        ):
            target[:, :column] = rows
            target[stages, column:] = inactive
        lo, hi = base.lo.copy(), base.hi.copy()
    for constraint in constraints:
        if isinstance(constraint, XBound):
            np.maximum(lo[:, 1], constraint.x_bound[:, 0], out=lo[:, 1])
            np.minimum(hi[:, 1], constraint.x_bound[:, 1], out=hi[:, 1])
        elif isinstance(constraint, AffineConstraint):
            column = seidel.project(*constraint.coefficients, ds, A, B, C, column)
        elif isinstance(constraint, StageRows):
            count = constraint.rows[0].shape[1]
            for target, rows in zip((A, B, C), constraint.rows, strict=True):
                target[:stages, column : column + count] = rows
            column += count
        else:
            raise TypeError(f"unsupported constraint {type(constraint).__name__}")
    return StageLPs(A, B, C, lo, hi)


__all__ = [
    "AffineConstraint",
    "Engine",
    "Reachability",
    "StageLPs",
    "StageRows",
    "XBound",
    "reachability",
    "stage_rows",
]
