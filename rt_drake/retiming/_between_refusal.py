"""The retimer's refusal of a limit still exceeded between grid points.

After the last refinement, a joint's ``|q' s'| / v_max`` or
``|q' u + q'' x| / qdd_max`` (x = s'^2, u = s''), a torque or a grasp row
``F w / g`` more than :data:`._check.DEFAULT_TOLERANCE` (relative) over 1
between grid points is a :class:`~._retime_errors.LimitsBetweenGridPointsError`
naming the limit kind and s: the retimer never returns a trajectory it
knows exceeds a limit.
"""

from __future__ import annotations

import numpy as np

from rt_drake.retiming._between import refinement_points
from rt_drake.retiming._check_report import DEFAULT_TOLERANCE
from rt_drake.retiming._joint_cuts import joint_excess_max
from rt_drake.retiming._retime_errors import LimitsBetweenGridPointsError
from rt_drake.retiming._samples import PathSamples
from rt_drake.retiming._segments import Segments
from rt_drake.retiming.limits import JointLimits


def refuse_excess(
    segments: Segments,
    samples: PathSamples,
    x: np.ndarray,
    u: np.ndarray,
    limits: JointLimits,
    normals: np.ndarray | None,
    row_max: np.ndarray | None,
    between: np.ndarray | None,
    refinements: int,
    cut_rounds: int,
) -> None:
    """Raise if a limit is still exceeded beyond the contract between grid points.

    Called after the last refinement (``refinements`` of the grid, and
    ``cut_rounds`` of cuts per grid, for the message); the contract is a
    relative excess of :data:`._check.DEFAULT_TOLERANCE`. An excess above
    :data:`._solve.BETWEEN_TOLERANCE` but within the contract is accepted,
    as the trajectory check accepts it.

    Raises:
        LimitsBetweenGridPointsError: naming the limit kind and where (s).
    """
    joint, s_joint = joint_excess_max(segments, x, u, limits)
    if joint > DEFAULT_TOLERANCE:
        raise LimitsBetweenGridPointsError(
            f"a joint velocity or acceleration exceeds its limit by "
            f"{100.0 * joint:.2f} % between grid points near s = {s_joint:.4f} "
            f"after {refinements} refinements and {cut_rounds} rounds "
            f"of cuts",
            s_joint,
        )
    beyond = refinement_points(
        segments, samples, x, u, limits, normals, row_max, DEFAULT_TOLERANCE,
        between,
    )  # fmt: skip
    if beyond.size:
        raise LimitsBetweenGridPointsError(
            f"the grasp or a torque exceeds its limit by more than "
            f"{100.0 * DEFAULT_TOLERANCE:.1f} % between grid points near "
            f"s = {beyond[0]:.4f} after {refinements} refinements",
            float(beyond[0]),
        )
