"""The checks of :func:`~._solve.retime`'s arguments that are not its path.

Types of the plant, limits, grasp (duck-typed: ``held``, ``F``, ``g``,
``is_robust``), context and cup frame; path velocities ``s'`` (1/s) finite
and >= 0 and a finite start time (s). Each failure is a one-line
:class:`~._retime_errors.RetimeInputError` naming the argument.
"""

from __future__ import annotations

import functools

import numpy as np
from pydrake.multibody.plant import MultibodyPlant
from pydrake.systems.framework import Context

from rt_drake import arguments
from rt_drake.dynamics.cup_frame import CupFrame
from rt_drake.retiming._retime_errors import RetimeInputError
from rt_drake.retiming.limits import GRASP_ATTRIBUTES, JointLimits


def check_arguments(sd_start: float, sd_end: float, start_time: float) -> None:
    """Refuse NaN, inf or negative path velocities and a NaN start time."""
    for name, value in (("sd_start", sd_start), ("sd_end", sd_end)):
        if not (isinstance(value, (int, float, np.number)) and np.isfinite(value)):
            raise RetimeInputError(f"{name} must be a finite number, got {value!r}")
        if value < 0.0:
            raise RetimeInputError(f"{name} must be >= 0 (1/s), got {value!r}")
    if not (
        isinstance(start_time, (int, float, np.number)) and np.isfinite(start_time)
    ):
        raise RetimeInputError(f"start_time must be finite, got {start_time!r}")


def check_jerk_start(start: object, jerk: object) -> None:
    """Refuse a ``jerk_start`` that is not a retime's result, or without jerk limits."""
    s = np.asarray(getattr(start, "gridpoints", None), dtype=float)
    sd = np.asarray(getattr(start, "sd", None), dtype=float)
    if s.ndim != 1 or len(s) < 2 or s.shape != sd.shape:
        raise RetimeInputError(
            "jerk_start must be a RetimeResult (gridpoints and sd of one "
            f"length), got {type(start).__name__}"
        )
    if jerk is None:
        raise RetimeInputError("jerk_start given but limits.jerk is None")
    ends = s[0] == 0.0 and s[-1] == 1.0
    if not (ends and np.isfinite(sd).all() and (sd >= 0.0).all()):
        raise RetimeInputError(
            "jerk_start: its sd must be finite and >= 0 on a grid from 0 to 1"
        )


def check_objects(
    plant: object, limits: object, grasp: object, context: object, cup: object
) -> None:
    """Refuse arguments of the wrong type, naming them."""
    check = functools.partial(
        arguments.instance, where="retime", error=RetimeInputError
    )
    check(plant, "plant", MultibodyPlant)
    check(limits, "limits", JointLimits)
    if grasp is not None:
        arguments.having(
            grasp,
            "grasp",
            "GraspConstraint",
            GRASP_ATTRIBUTES,
            where="retime",
            error=RetimeInputError,
        )
    if context is not None:
        check(context, "context", Context)
    if cup is not None:
        check(cup, "cup", CupFrame)
