"""The path and its constraint coefficients at the grid points.

At each grid point s_i: ``q(s_i)``, ``q'(s_i)``, ``q''(s_i)`` from the path's
spline, the velocity bound ``x_cap = min_j v_j^2 / q'_j^2`` on ``x = s'^2``,
and, from Drake (:mod:`rt_drake.dynamics.wrench`), the coefficients of the joint
torques ``tau = a u + b x + c`` (if torques are limited) and of the object
wrench ``w = a u + b x + c`` (if an object is held). Drake is the expensive
part (about 20 us per point), so a refined grid evaluates only its new
points (:func:`with_points`), and when the plant is the cup's serial chain
alone (``cup.chain``, :mod:`rt_drake.dynamics.chain`) the object wrench comes from
that chain's batched kinematics instead (the same quantities to rounding,
about 1.4 us per point). Torques, and a plant with other joints (a second
arm, a turntable), take Drake's route.

For a set of objects (a robust grasp, :mod:`rt_drake.uncertainty.inertial_set`) the
wrench is linear in the inertial parameters (:mod:`rt_drake.dynamics.regressor`):
the samples then hold the coefficients of the set's P parameter columns
(``wrench_set``, each (G, P, 6); ``torque_set``, each (G, P, n), the held
object's share of the joint torques) and ``torque`` is the arm's own.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from pydrake.multibody.plant import MultibodyPlant
from pydrake.systems.framework import Context

from rt_drake.dynamics.cup_frame import CupFrame
from rt_drake.dynamics.regressor import (
    path_wrench_regressor,
    torque_regressor,
)
from rt_drake.dynamics.wrench import (
    PathCoefficients,
    path_torque_coefficients,
    path_wrench_coefficients,
)
from rt_drake.retiming._joint_path import JointPath
from rt_drake.types.held_object import HeldObject


class PathSamples(NamedTuple):
    """The path at the grid points (see the module docstring).

    Attributes:
        s: (G,) the grid.
        q, dq, ddq: (G, n) the path and its first two derivatives in s.
        x_cap: (G,) the joint-velocity bound on ``s'^2`` (inf where q' = 0).
        torque: torque coefficients (each (G, n)), or None; with a set of
            objects, the arm's alone.
        wrench: object-wrench coefficients (each (G, 6)), or None.
        wrench_set: with a set of objects, the wrench coefficients of its
            parameter columns (each (G, P, 6)), else None.
        torque_set: with a set of objects and torque limits, the torques
            of its parameter columns (each (G, P, n)), else None.
    """

    s: np.ndarray
    q: np.ndarray
    dq: np.ndarray
    ddq: np.ndarray
    x_cap: np.ndarray
    torque: PathCoefficients | None
    wrench: PathCoefficients | None
    wrench_set: PathCoefficients | None = None
    torque_set: PathCoefficients | None = None


def sample_path(
    plant: MultibodyPlant,
    spline: JointPath,
    s: np.ndarray,
    velocity_limit: np.ndarray,
    torque: bool,
    held: HeldObject | None,
    context: Context,
    cup: CupFrame,
    columns: np.ndarray | None = None,
) -> PathSamples:
    """Evaluate the path and the coefficients at the grid ``s``.

    Args:
        plant: The retimer's plant.
        spline: The path q(s).
        s: (G,) grid points.
        velocity_limit: (n,) rad/s.
        torque: Whether to compute torque coefficients (with ``held``'s load).
        held: The held object, for the wrench (and the torques' load).
        context: Scratch context of ``plant``.
        cup: The cup frame C.
        columns: (P, 10) parameter columns of a set of objects (then
            ``held`` is ignored), or None.
    """
    q, dq, ddq = spline(s), spline(s, 1), spline(s, 2)
    with np.errstate(divide="ignore", over="ignore"):  # q' = 0: no cap
        x_cap = np.min(velocity_limit**2 / dq**2, axis=1)
    if columns is not None:
        Y, kin = path_wrench_regressor(plant, q, dq, ddq, context, cup, torque)
        wrench_set = PathCoefficients(*Y.coefficients(columns))
        arm = torque_set = None
        if torque:
            arm_abc, TY = torque_regressor(kin, dq, ddq, Y)
            arm = PathCoefficients(*arm_abc)
            torque_set = PathCoefficients(*TY.coefficients(columns))
        return PathSamples(s, q, dq, ddq, x_cap, arm, None, wrench_set, torque_set)
    tau = (
        path_torque_coefficients(plant, q, dq, ddq, held, context, cup)
        if torque
        else None
    )
    wrench = None if held is None else _wrench(plant, held, q, dq, ddq, context, cup)
    return PathSamples(s, q, dq, ddq, x_cap, tau, wrench)


def _wrench(
    plant: MultibodyPlant,
    held: HeldObject,
    q: np.ndarray,
    dq: np.ndarray,
    ddq: np.ndarray,
    context: Context,
    cup: CupFrame,
) -> PathCoefficients:
    """The object wrench's coefficients: batched on the cup's chain, else Drake."""
    chain = cup.chain
    if chain is None or chain.num_joints != plant.num_positions():
        return path_wrench_coefficients(plant, held, q, dq, ddq, context, cup)
    gravity_W = plant.gravity_field().gravity_vector()  # read now: it may change
    return PathCoefficients(*chain.wrench_coefficients(held, q, dq, ddq, gravity_W))


def with_points(samples: PathSamples, new: PathSamples) -> PathSamples:
    """``samples`` and ``new`` (other grid points) merged, sorted by s."""
    order = np.argsort(np.concatenate([samples.s, new.s]), kind="stable")

    def merged(old: np.ndarray, added: np.ndarray) -> np.ndarray:
        return np.concatenate([old, added])[order]

    def merged_coefficients(
        old: PathCoefficients | None, added: PathCoefficients | None
    ) -> PathCoefficients | None:
        if old is None or added is None:
            return None
        return PathCoefficients(
            *(merged(o, a) for o, a in zip(old, added, strict=True))
        )

    return PathSamples(
        merged(samples.s, new.s),
        merged(samples.q, new.q),
        merged(samples.dq, new.dq),
        merged(samples.ddq, new.ddq),
        merged(samples.x_cap, new.x_cap),
        merged_coefficients(samples.torque, new.torque),
        merged_coefficients(samples.wrench, new.wrench),
        merged_coefficients(samples.wrench_set, new.wrench_set),
        merged_coefficients(samples.torque_set, new.torque_set),
    )


__all__ = ["PathSamples", "sample_path", "with_points"]
