"""A trajectory played faster: ``q_f(t) = q(f t)``.

Used to play a retimed MOVE above its critical speed (slip experiments).
Units: s, rad, rad/s, rad/s^2.
"""

from __future__ import annotations

import numpy as np
from pydrake.trajectories import Trajectory

from rt_drake import arguments
from rt_drake.retiming._retime_errors import RetimeInputError


class TimeScaled(Trajectory):
    """``q_f(t) = q(f t)``: a trajectory played ``f`` times faster.

    Derivatives scale as ``q_f^(k)(t) = f^k q^(k)(f t)``; the time span is
    ``[t0 / f, t1 / f]``.
    """

    def __init__(self, trajectory: Trajectory, factor: float) -> None:
        Trajectory.__init__(self)
        where = "TimeScaled"
        arguments.instance(
            trajectory, "trajectory", Trajectory, where=where, error=RetimeInputError
        )
        arguments.number(
            factor, "factor", where=where, above=0.0, error=RetimeInputError
        )
        self._trajectory = trajectory
        self._factor = float(factor)

    def do_value(self, t: float) -> np.ndarray:  # noqa: D102
        return self._trajectory.value(self._factor * t)

    def do_has_derivative(self) -> bool:  # noqa: D102
        return True

    def DoEvalDerivative(self, t: float, derivative_order: int) -> np.ndarray:  # noqa: D102, N802
        return self._factor**derivative_order * self._trajectory.EvalDerivative(
            self._factor * t, derivative_order
        )

    def do_rows(self) -> int:  # noqa: D102
        return self._trajectory.rows()

    def do_cols(self) -> int:  # noqa: D102
        return self._trajectory.cols()

    def do_start_time(self) -> float:  # noqa: D102
        return self._trajectory.start_time() / self._factor

    def do_end_time(self) -> float:  # noqa: D102
        return self._trajectory.end_time() / self._factor

    def Clone(self) -> TimeScaled:  # noqa: D102, N802
        return TimeScaled(self._trajectory.Clone(), self._factor)

    def __deepcopy__(self, memo: dict) -> TimeScaled:
        return self.Clone()


__all__ = ["TimeScaled"]
