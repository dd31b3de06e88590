"""A compliant cup's stiffness: the bellows between the tool and the lip.

A bellows cup joins its lip to the tool through a rubber bellows that gives
along its axis, sideways, in tilt and in torsion. About the cup frame C's
origin (the centre of the contact face, +z out of the cup into the object),
in C, a small rigid deflection ``d = [theta; x]`` (rad, m) of the lip
against the tool loads the object with the wrench ``[torque; force]`` (N m,
N)

    w_C = K_C d,   K_C = diag(k_tilt, k_tilt, k_torsion,
                              k_lateral, k_lateral, k_axial),

an axisymmetric bellows (the simulation's bushing has the same form:
:mod:`rt_drake.simulation`; the planner states its own values, as it states
its own friction and suction force). Numpy only: imported with
:mod:`rt_drake.contact`.
"""

# No ``from __future__ import annotations``: a scenario loader may read the
# dataclass field types, which must be real types, not strings.
import dataclasses
import math

import numpy as np

from rt_drake.errors import InputError

#: Field name -> unit, for messages.
_UNITS = {
    "axial": "N/m",
    "lateral": "N/m",
    "tilt": "N m/rad",
    "torsion": "N m/rad",
}


@dataclasses.dataclass(frozen=True)
class CupStiffness:
    """The bellows' stiffness about the cup frame's origin, in it.

    Attributes:
        axial: N/m, along the cup's axis z_C.
        lateral: N/m, along x_C and along y_C.
        tilt: N m/rad, about x_C and about y_C.
        torsion: N m/rad, about z_C.
    """

    axial: float
    lateral: float
    tilt: float
    torsion: float

    def __post_init__(self) -> None:
        for name, unit in _UNITS.items():
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(
                value, (int, float, np.integer, np.floating)
            ):
                raise InputError(
                    f"cup stiffness {name} must be a number, got {value!r}"
                )
            if not (math.isfinite(value) and value > 0.0):
                raise InputError(
                    f"cup stiffness {name} must be finite and > 0 {unit}, got {value!r}"
                )

    def matrix(self) -> np.ndarray:
        """``K_C`` (6, 6): ``[theta; x]`` -> ``[torque; force]``, about C, in C."""
        return np.diag(
            [
                self.tilt,
                self.tilt,
                self.torsion,
                self.lateral,
                self.lateral,
                self.axial,
            ]
        ).astype(float)

    def as_dict(self) -> dict[str, float]:
        """Return the four stiffnesses as plain floats."""
        return {name: float(getattr(self, name)) for name in _UNITS}


__all__ = ["CupStiffness"]
