"""What the dense check of a trajectory reports: margins per constraint.

A margin is ``1 - ratio`` of a constraint's value to its limit (``|v_j| /
v_max_j``, ``|vdot_j| / a_max_j``, ``|tau_j| / tau_max_j``, ``max_k F_k w /
g_k``, ...), the retimer's sign convention (:attr:`RetimeResult.margins
<rt_drake.retiming._retime_result.RetimeResult>`): positive is room left,
negative is over the limit by that fraction. :class:`Margin` names the
constraints, :class:`WorstMargin` is one constraint's smallest margin and
where, :class:`TrajectoryCheck` all of them (:func:`._check.check_trajectory`).
"""

from __future__ import annotations

import dataclasses
import enum
import warnings

import numpy as np

#: Allowed relative excess over a limit (and over g for the grasp), see above:
#: a margin down to ``-DEFAULT_TOLERANCE`` passes.
DEFAULT_TOLERANCE = 1e-3


class Margin(enum.Enum):
    """A constraint the retimer holds, keying its margins and the check's."""

    #: Joint velocity, ``|v_j| <= v_max_j``.
    VELOCITY = "velocity"
    #: Joint acceleration, ``|vdot_j| <= a_max_j``.
    ACCELERATION = "acceleration"
    #: Joint torque, ``|tau_j| <= tau_max_j`` (when limited).
    TORQUE = "torque"
    #: The grasp, ``F w <= g`` (with a held object).
    GRASP = "grasp"
    #: Joint position, inside the plant's limits (checked by the checker only).
    POSITION = "position"
    #: Joint jerk, ``|vddot_j| <= jerk_j`` (when limited).
    JERK = "jerk"


@dataclasses.dataclass(frozen=True)
class WorstMargin:
    """Smallest margin of one constraint over the samples.

    Attributes:
        value: ``1 - max(ratio)``: positive is room left, negative is over
            the limit by that fraction (the sign of ``RetimeResult.margins``).
        time: When it occurs, s.
        index: The joint (0-based) or grasp row it occurs at.
        detail: For a joint quantity, what it is there and its limit, e.g.
            ``joint 1 (vs060_joint1): 4.9671 rad, limit 2.9671 rad``; else
            empty.
    """

    value: float
    time: float
    index: int
    detail: str = ""

    def words(self, tolerance: float = DEFAULT_TOLERANCE) -> str:
        """``room 0.006 %`` or ``over by 0.010 %`` (no sign to misread).

        An excess the contract allows (at most ``tolerance``) says so:
        ``over by 0.010 % (within the 0.100 % tolerance)``.
        """
        if self.value >= 0.0:
            return f"room {100 * self.value:.3f} %"
        text = f"over by {-100 * self.value:.3f} %"
        if -self.value <= tolerance:
            text += f" (within the {100 * tolerance:.3f} % tolerance)"
        return text


@dataclasses.dataclass(frozen=True)
class Excess:
    """Deprecated: the old sign, ``max(ratio) - 1`` (see :class:`WorstMargin`).

    Attributes:
        value: ``max(ratio) - 1`` (<= 0: within the limit).
        time: When it occurs, s.
        index: The joint (0-based) or grasp row it occurs at.
    """

    value: float
    time: float
    index: int


@dataclasses.dataclass(frozen=True, eq=False)
class TrajectoryCheck:
    """Result of :func:`check_trajectory`.

    ``margins`` maps each constraint checked (:attr:`Margin.VELOCITY`,
    :attr:`Margin.ACCELERATION`, and :attr:`Margin.TORQUE`,
    :attr:`Margin.GRASP` when checked) to its :class:`WorstMargin`.
    """

    times: np.ndarray
    margins: dict[Margin, WorstMargin]

    def min_margin(self) -> float:
        """Smallest margin over all constraints (negative: over a limit)."""
        return min(m.value for m in self.margins.values())

    def passed(self, tolerance: float = DEFAULT_TOLERANCE) -> bool:
        """Whether no constraint is over its limit by more than ``tolerance``."""
        return self.min_margin() >= -tolerance

    def summary(self, tolerance: float = DEFAULT_TOLERANCE) -> str:
        """One line per constraint: name, margin in words, time, index.

        E.g. ``grasp: room 0.006 % at t = 0.4120 s (#17)`` or ``torque: over
        by 0.200 % at t = 1.2000 s (#2)`` (:meth:`WorstMargin.words`).
        """
        return "\n".join(
            f"{kind.value}: {m.words(tolerance)} at t = {m.time:.4f} s "
            + (f"({m.detail})" if m.detail else f"(#{m.index})")
            for kind, m in self.margins.items()
        )

    @property
    def excess(self) -> dict[str, Excess]:
        """Deprecated: the old sign (positive = over); use :attr:`margins`."""
        warnings.warn(
            "TrajectoryCheck.excess is deprecated (positive meant over the limit): "
            "use .margins (positive means room, negative over the limit)",
            DeprecationWarning,
            stacklevel=2,
        )
        return {
            kind.value: Excess(-m.value, m.time, m.index)
            for kind, m in self.margins.items()
        }

    def worst(self) -> float:
        """Deprecated: the largest excess, ``-min_margin()``; use :meth:`min_margin`."""
        warnings.warn(
            "TrajectoryCheck.worst() is deprecated (positive meant over the limit): "
            "use .min_margin() (positive means room, negative over the limit)",
            DeprecationWarning,
            stacklevel=2,
        )
        return -self.min_margin()


__all__ = [
    "DEFAULT_TOLERANCE",
    "Excess",
    "Margin",
    "TrajectoryCheck",
    "WorstMargin",
]
