"""The vacuum: the scenario's ``vacuum`` key and its law, in one place.

The ``vacuum`` key says how the suction force builds up and releases.

See :class:`Vacuum`. :func:`check_vacuum` refuses out-of-range values and
:func:`check_renamed` the ``timing`` key it replaced (0.2.0), each with a
one-line :class:`~rt_drake.errors.ScenarioError` naming file, key and value.
(No ``from __future__ import annotations``: ``yaml_load_typed`` reads the
dataclass field types, which must not be strings.)

The law, as pure functions (the simulation's suction system calls them):

The level lambda in [0, 1] scales the cup's full suction force P A (N):
the force on a sealed object is ``lambda P A``. With the scenario's
:class:`~rt_drake.model.vacuum.Vacuum`:

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

import dataclasses
import enum
import math
from pathlib import Path

from rt_drake.errors import RtDrakeError, ScenarioError
from rt_drake.types.phase import Phase


class VacuumModel(enum.Enum):
    """How the suction force follows the valve."""

    FIXED = "fixed"  # full force at once; fixed attach and detach waits
    FIRST_ORDER = "first_order"  # first-order build-up and release


@dataclasses.dataclass
class Vacuum:
    """The vacuum: how fast the suction force P A builds up and releases.

    ``model: fixed`` (the paper's, the default): the force is P A while the
    valve is on and 0 when it is off; ATTACH waits ``attach_s`` and DETACH
    ``detach_s`` seconds (the paper: 1 s each).

    ``model: first_order``: the vacuum level lambda in [0, 1] (force
    lambda P A) follows a first-order lag, ``d lambda/dt = (1 - lambda) /
    build_up_tau_s`` while the valve is on and the cup sealed on a face, and
    ``-lambda / release_tau_s`` otherwise. A vacuum switch reports "part
    present" once ``lambda >= part_present_fraction``: ATTACH ends then
    (``t = build_up_tau_s ln(1 / (1 - part_present_fraction))`` after the
    valve opens) and the MOVE is retimed for the force guaranteed from then
    on, ``part_present_fraction P A``. DETACH ends when the force is below
    the object's weight and the object is at rest. ``attach_s`` and
    ``detach_s`` are then time-outs: a cycle that waits longer stops with a
    VacuumTimeout (no seal, or the object sticks).

    The default time constants are assumptions, not measurements: an
    ejector evacuating a volume V at a suction flow q through the valve is a
    first-order lag of ``tau = V / q`` (isothermal, flow proportional to the
    remaining pressure difference; evacuating from p0 to p1 takes
    ``(V / q) ln(p0 / p1)``). For the paper's 25 mm cup, V is about 15 cm^3
    (cup and 1 m of 4 mm hose) and q about 9 l/min (0.15 l/s) at the cup,
    so tau is about 0.1 s; venting with a blow-off pulse is assumed twice
    as fast (0.05 s). Vacuum switches are commonly set to 60-80 % of the
    working vacuum: 0.8.

    Attributes:
        model: ``fixed`` or ``first_order``.
        attach_s, detach_s: s, the waits (fixed) or time-outs (first_order).
        build_up_tau_s: s, time constant of the build-up (first_order).
        release_tau_s: s, time constant of the release (first_order).
        part_present_fraction: fraction of P A at which "part present" fires.
    """

    model: str = VacuumModel.FIXED.value
    attach_s: float = 1.0
    detach_s: float = 1.0
    build_up_tau_s: float = 0.1
    release_tau_s: float = 0.05
    part_present_fraction: float = 0.8

    @property
    def kind(self) -> VacuumModel:
        """``model`` as the enum (ScenarioError if unknown)."""
        try:
            return VacuumModel(self.model)
        except ValueError:
            known = ", ".join(m.value for m in VacuumModel)
            raise ScenarioError(
                f"key 'vacuum.model': unknown model {self.model!r} (known: {known})"
            ) from None

    @property
    def move_force_fraction(self) -> float:
        """Fraction of P A a MOVE may rely on (1 fixed, the switch's first_order)."""
        if self.kind is VacuumModel.FIXED:
            return 1.0
        return self.part_present_fraction


def check_renamed(path: Path, raw: dict) -> None:
    """``timing: {attach_s, detach_s}`` (before 0.2.0) is now ``vacuum``."""
    timing = raw.get("timing")
    if timing is None:
        return
    waits = timing if isinstance(timing, dict) else {}
    attach, detach = waits.get("attach_s", 1.0), waits.get("detach_s", 1.0)
    raise ScenarioError(
        f"{path}: key 'timing' was renamed 'vacuum': write vacuum: "
        f"{{model: fixed, attach_s: {attach}, detach_s: {detach}}}"
    )


def check_vacuum(path: Path, vacuum: Vacuum) -> None:
    """Refuse a vacuum key out of range (ScenarioError naming the key).

    An unknown model, negative waits, non-positive time constants, a
    part-present fraction outside (0, 1).
    """
    if vacuum.model not in {m.value for m in VacuumModel}:
        known = ", ".join(m.value for m in VacuumModel)
        raise ScenarioError(
            f"{path}: key 'vacuum.model': unknown model {vacuum.model!r} "
            f"(known: {known})"
        )
    bounds = {
        "attach_s": (0.0, False, "s"),
        "detach_s": (0.0, False, "s"),
        "build_up_tau_s": (0.0, True, "s"),
        "release_tau_s": (0.0, True, "s"),
    }
    for field, (low, strict, unit) in bounds.items():
        value = getattr(vacuum, field)
        if not (math.isfinite(value) and (value > low if strict else value >= low)):
            relation = ">" if strict else ">="
            raise ScenarioError(
                f"{path}: key 'vacuum.{field}': must be {relation} {low:g} {unit}, "
                f"got {value}"
            )
    fraction = vacuum.part_present_fraction
    if not (math.isfinite(fraction) and 0.0 < fraction < 1.0):
        raise ScenarioError(
            f"{path}: key 'vacuum.part_present_fraction': must be in (0, 1), "
            f"got {fraction}"
        )


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
    "Vacuum",
    "VacuumModel",
    "VacuumTimeout",
    "check_renamed",
    "check_vacuum",
    "is_released",
    "next_level",
    "part_present",
    "time_to_part_present",
    "wait_over",
]
