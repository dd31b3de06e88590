"""The path inside the joint position limits: :func:`check_position_limits`.

``lower_j - 1e-9 <= q_j(s) <= upper_j + 1e-9`` (rad) for every s of the
path; a path that leaves them is refused before it is retimed.
"""

from __future__ import annotations

import numpy as np
from pydrake.multibody.plant import MultibodyPlant

from rt_drake.retiming._between_kernels import position_excess
from rt_drake.retiming._joint_path import JointPath
from rt_drake.retiming._retime_errors import RetimeInputError
from rt_drake.retiming._samples import PathSamples
from rt_drake.retiming.seidel import kernel_array

#: Where a non-cubic path is checked against the position limits, in
#: fractions of each segment.
_DENSE = np.arange(1, 16) / 16


def check_position_limits(
    plant: MultibodyPlant, samples: PathSamples, path: JointPath
) -> None:
    """Raise if the path leaves the plant's joint position limits anywhere.

    For a cubic path, exact: at the grid points, and at the extremes of each
    joint inside each segment, the roots in (0, 1) of the quadratic
    ``d q_j(s_i + theta ds_i) / d theta`` (every segment lies inside one
    cubic piece, :mod:`.grid`; :func:`._between_kernels.position_excess`).
    For another path, at the grid points and 15 points inside every segment.
    A tolerance of 1e-9 rad absorbs rounding.

    Raises:
        RetimeInputError: naming the joint, the value, the limit and s.
    """
    lower = plant.GetPositionLowerLimits()
    upper = plant.GetPositionUpperLimits()
    s = samples.s
    if path.cubic:
        found, j, value, at = position_excess(
            *(kernel_array(v) for v in (s, samples.q, samples.dq, samples.ddq)),
            kernel_array(lower),
            kernel_array(upper),
            1e-9,
        )
    else:
        where = np.union1d(s, (s[:-1, None] + np.diff(s)[:, None] * _DENSE).ravel())
        q = path(where)
        outside = (q < lower - 1e-9) | (q > upper + 1e-9)
        found = bool(outside.any())
        if found:
            i, j = (int(k[0]) for k in np.nonzero(outside))
            value, at = float(q[i, j]), float(where[i])
    if not found:
        return
    limit = lower[j] if value < lower[j] else upper[j]
    raise RetimeInputError(
        f"path leaves the position limits of joint {j + 1} "
        f"({_joint_name(plant, j)}) at s = {at:.3f}: {value:.4f} rad, "
        f"limit {limit:.4f} rad",
        s=float(at),
    )


def _joint_name(plant: MultibodyPlant, position_index: int) -> str:
    """The name of the joint owning position ``position_index``."""
    for index in plant.GetJointIndices():
        joint = plant.get_joint(index)
        start = joint.position_start()
        if start <= position_index < start + joint.num_positions():
            return joint.name()
    return f"position {position_index}"
