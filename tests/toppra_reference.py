"""An independent time-optimal reference for the tests: the toppra package.

:func:`toppra_duration` is the rest-to-rest duration (s) of a path
``q(s)``, ``s`` in [0, 1] (anything with ``value(s)``), under the joint
velocity and acceleration limits, by toppra's own TOPP-RA on 2000 grid
points (20 times finer than the cycle's uniform grid).
"""

from __future__ import annotations

import numpy as np
import toppra
import toppra.algorithm
import toppra.constraint

from rt_drake.retiming import JointLimits


def toppra_duration(path, limits: JointLimits) -> float:
    """Time-optimal duration (s) of ``path`` at the joint limits (2000 points)."""
    s = np.linspace(0.0, 1.0, 2000)
    spline = toppra.SplineInterpolator(s, path.value(s))
    constraints = [
        toppra.constraint.JointVelocityConstraint(
            np.column_stack([-limits.velocity, limits.velocity])
        ),
        toppra.constraint.JointAccelerationConstraint(
            np.column_stack([-limits.acceleration, limits.acceleration])
        ),
    ]
    instance = toppra.algorithm.TOPPRA(constraints, spline, gridpoints=s)
    return float(instance.compute_trajectory(0.0, 0.0).duration)
