"""The vacuum's law: suction level, "part present" and release, as pure functions.

The level lambda in [0, 1] scales the cup's full suction force P A (N):
the force on a sealed object is ``lambda P A``. With the scenario's
:class:`~rt_drake.scenario.Vacuum`:

- ``fixed``: lambda = 1 while the valve is on, 0 when it is off (no state);
- ``first_order``: a first-order lag toward 1 while the valve is on and the
  cup sealed on a face (time constant ``build_up_tau_s``), toward 0
  otherwise (``release_tau_s``). Over a step h with the target held
  constant, the exact solution is ``lambda' = target + (lambda - target)
  exp(-h / tau)``.

"Part present" (the vacuum switch) is ``lambda >= part_present_fraction``
(fixed: the valve on and the cup sealed). An object is released when the
force is below its weight and it is at rest (:func:`is_released`).
:func:`wait_over` says when ATTACH and DETACH end.
"""

from __future__ import annotations

import math

from rt_drake.errors import RtDrakeError
from rt_drake.phase import Phase
from rt_drake.scenario import Vacuum, VacuumModel

#: m/s and rad/s: an object moving slower than this is at rest.
REST_SPEED = 5e-3
REST_ANGULAR_SPEED = 0.05


class VacuumTimeout(RtDrakeError):
    """The vacuum did not seal, or did not release, within its time-out."""


def next_level(vacuum: Vacuum, level: float, on_and_sealed: bool, h: float) -> float:
    """The level lambda after ``h`` seconds (exact for a constant input)."""
    if vacuum.kind is VacuumModel.FIXED:
        return 1.0 if on_and_sealed else 0.0
    target = 1.0 if on_and_sealed else 0.0
    tau = vacuum.build_up_tau_s if on_and_sealed else vacuum.release_tau_s
    return target + (level - target) * math.exp(-h / tau)


def part_present(vacuum: Vacuum, level: float) -> bool:
    """The vacuum switch: lambda at or above ``part_present_fraction``."""
    if vacuum.kind is VacuumModel.FIXED:
        return level >= 1.0
    return level >= vacuum.part_present_fraction


def time_to_part_present(vacuum: Vacuum) -> float:
    """Seconds from valve on (sealed, lambda = 0) to "part present".

    ``build_up_tau_s ln(1 / (1 - part_present_fraction))`` (first_order);
    fixed: 0.
    """
    if vacuum.kind is VacuumModel.FIXED:
        return 0.0
    return vacuum.build_up_tau_s * math.log(1.0 / (1.0 - vacuum.part_present_fraction))


def is_released(
    force: float, weight: float, speed: float, angular_speed: float
) -> bool:
    """Force (N) below the weight (N) and the object at rest (m/s, rad/s)."""
    return force < weight and speed < REST_SPEED and angular_speed < REST_ANGULAR_SPEED


def wait_over(
    vacuum: Vacuum, phase: Phase, waited: float, signal: bool, name: str
) -> bool:
    """Whether ATTACH or DETACH of object ``name`` is over after ``waited`` s.

    fixed: once ``waited`` reaches ``attach_s`` (``detach_s``). first_order:
    once ``signal`` ("part present" for ATTACH, "released" for DETACH).

    Raises:
        VacuumTimeout: first_order, no signal and ``waited`` past the time-out.
    """
    limit = vacuum.attach_s if phase is Phase.ATTACH else vacuum.detach_s
    if vacuum.kind is VacuumModel.FIXED:
        return waited >= limit - 1e-9
    if not signal and waited > limit:
        what = "part present" if phase is Phase.ATTACH else "release"
        raise VacuumTimeout(f"{phase.label} {name}: no {what} within {limit:g} s")
    return signal


__all__ = [
    "REST_ANGULAR_SPEED",
    "REST_SPEED",
    "VacuumTimeout",
    "is_released",
    "next_level",
    "part_present",
    "time_to_part_present",
    "wait_over",
]
