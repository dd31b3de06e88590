"""Trajectories played one after the other, as one Drake Trajectory.

``q(t) = q_k(t - T_k)`` for ``T_k <= t < T_{k+1}``, with ``T_0 = 0`` and
``T_{k+1} = T_k + d_k`` (``d_k`` the k-th piece's duration; each piece is
read from its own start time). Derivatives likewise, piece by piece: where a
piece ends at rest and the next starts at rest, q, q' and q'' are continuous
(the cycle's first pick: the straight APPROACH, then the REACH).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from pydrake.trajectories import Trajectory


class Joined(Trajectory):
    """Pieces played in turn; t in [0, sum of their durations] (s)."""

    def __init__(self, pieces: Sequence[Trajectory]) -> None:
        Trajectory.__init__(self)
        self._pieces = tuple(pieces)
        durations = [p.end_time() - p.start_time() for p in self._pieces]
        self._starts = np.concatenate([[0.0], np.cumsum(durations)])

    @property
    def starts(self) -> np.ndarray:
        """Start time (s) of each piece, then the end time (len(pieces) + 1)."""
        return self._starts

    def _piece(self, t: float) -> tuple[Trajectory, float]:
        """The piece playing at ``t`` and its own time then."""
        k = int(np.searchsorted(self._starts, t, side="right") - 1)
        k = min(max(k, 0), len(self._pieces) - 1)
        piece = self._pieces[k]
        return piece, piece.start_time() + t - self._starts[k]

    def sample(self, times: np.ndarray, order: int = 2) -> list[np.ndarray]:
        """``[q, q', ..., q^(order)]`` at ``times`` (s), each (M, n).

        Piece by piece: a piece's own vectorised ``sample`` where it has one.
        """
        times = np.asarray(times, dtype=float)
        k = np.searchsorted(self._starts, times, side="right") - 1
        k = np.clip(k, 0, len(self._pieces) - 1)
        out = [np.empty((len(times), self.rows())) for _ in range(order + 1)]
        for index, piece in enumerate(self._pieces):
            mask = k == index
            if not mask.any():
                continue
            local = piece.start_time() + times[mask] - self._starts[index]
            if hasattr(piece, "sample"):
                values = piece.sample(local, order=order)
            else:
                values = [
                    np.array([piece.EvalDerivative(t, d).ravel() for t in local])
                    for d in range(order + 1)
                ]
            for d in range(order + 1):
                out[d][mask] = values[d]
        return out

    def do_value(self, t: float) -> np.ndarray:  # noqa: D102
        piece, local = self._piece(t)
        return piece.value(local)

    def do_has_derivative(self) -> bool:  # noqa: D102
        return True

    def DoEvalDerivative(self, t: float, derivative_order: int) -> np.ndarray:  # noqa: D102, N802
        piece, local = self._piece(t)
        return piece.EvalDerivative(local, derivative_order)

    def do_rows(self) -> int:  # noqa: D102
        return self._pieces[0].rows()

    def do_cols(self) -> int:  # noqa: D102
        return self._pieces[0].cols()

    def do_start_time(self) -> float:  # noqa: D102
        return 0.0

    def do_end_time(self) -> float:  # noqa: D102
        return float(self._starts[-1])

    def Clone(self) -> Joined:  # noqa: D102, N802
        return Joined([p.Clone() for p in self._pieces])

    def __deepcopy__(self, memo: dict) -> Joined:
        return self.Clone()


__all__ = ["Joined"]
