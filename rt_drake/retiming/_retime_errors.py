"""Typed errors of the retimer: each names the cause and the path parameter s."""

from __future__ import annotations

import enum

from rt_drake.errors import InputError, RtDrakeError


class RetimeStatus(enum.Enum):
    """Outcome of a retime: OK on a result, one of the others on an error."""

    OK = "ok"
    BAD_INPUT = "bad input"
    GRASP_UNSTABLE_AT_REST = "object slips at rest"
    TORQUE_LIMIT_AT_REST = "torque limit exceeded at rest"
    NOT_CONTROLLABLE = "path not controllable"
    LIMITS_BETWEEN_GRID_POINTS = "limit exceeded between grid points"
    RING_NOT_HELD = "bellows ring exceeds the grasp set"


class RetimeError(RtDrakeError):
    """A path cannot be retimed under the given limits.

    Attributes:
        s: Path parameter in [0, 1] where the problem is (None if nowhere
            in particular).
        status: The :class:`RetimeStatus` of the failure.
    """

    status = RetimeStatus.BAD_INPUT

    def __init__(self, message: str, s: float | None = None) -> None:
        super().__init__(message)
        self.s = s


class RetimeInputError(RetimeError, InputError):
    """The path, limits or grasp are malformed (shape, NaN, sign).

    Also an :class:`~rt_drake.errors.InputError` (and a ``ValueError``).
    """

    status = RetimeStatus.BAD_INPUT


class GraspUnstableAtRestError(RetimeError):
    """Gravity alone already violates the grasp constraint ``F w <= g``.

    The object would slip even with the robot stopped on the path, so no
    time scaling can hold it (the retimer requires that the robot can stop
    anywhere on the path without dropping the object).
    """

    status = RetimeStatus.GRASP_UNSTABLE_AT_REST


class TorqueLimitAtRestError(RetimeError):
    """Holding a path configuration against gravity exceeds a torque limit."""

    status = RetimeStatus.TORQUE_LIMIT_AT_REST


class LimitsBetweenGridPointsError(RetimeError):
    """A limit stays exceeded between grid points after the last refinement.

    The retimer adds cuts and grid points until every joint, torque and
    grasp limit holds between grid points within the contract (a relative
    excess of 1e-3, :data:`rt_drake.retiming._check.DEFAULT_TOLERANCE`); if
    its refinements run out first, it refuses rather than return a
    trajectory that exceeds a limit.
    """

    status = RetimeStatus.LIMITS_BETWEEN_GRID_POINTS


class PathNotControllableError(RetimeError):
    """TOPP-RA found no admissible path velocity from some s to the end."""

    status = RetimeStatus.NOT_CONTROLLABLE


__all__ = [
    "GraspUnstableAtRestError",
    "LimitsBetweenGridPointsError",
    "PathNotControllableError",
    "RetimeError",
    "RetimeInputError",
    "RetimeStatus",
    "TorqueLimitAtRestError",
]
