"""The ``vacuum`` key of a scenario: how the suction force builds up and releases.

See :class:`Vacuum`. :func:`check_vacuum` refuses out-of-range values and
:func:`check_renamed` the ``timing`` key it replaced (0.2.0), each with a
one-line :class:`~rt_drake.errors.ScenarioError` naming file, key and value.
(No ``from __future__ import annotations``: ``yaml_load_typed`` reads the
dataclass field types, which must not be strings.)
"""

import dataclasses
import enum
import math
from pathlib import Path

from rt_drake.errors import ScenarioError


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


__all__ = ["Vacuum", "VacuumModel", "check_renamed", "check_vacuum"]
