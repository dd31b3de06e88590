"""What the robot does not know about a held object: :class:`ObjectUncertainty`.

A scenario object may carry ``uncertainty: {mass: 0.2, com: [0.01, 0.01,
0.005], inertia: 0.2}``: the set of objects the retimer must hold is every
object with

- mass ``m`` in ``m0 [1 - mass, 1 + mass]`` (``mass`` relative, in [0, 1));
- centre of mass ``p_OoScm_O = p0_O + delta`` with ``|delta_j| <= com[j]``
  (m), ``delta`` along the object's axes O (the axes of its SDF body frame);
- principal moments of inertia about Scm ``lambda_j`` in ``lambda0_j [1 -
  inertia, 1 + inertia]`` (``inertia`` relative, in [0, 1)), about the
  nominal's principal axes.

The cup's own unknowns are ``cup.friction_min`` and ``cup.suction_force_min``
(:class:`~rt_drake.contact.CupParameters`). This module only holds and checks
the widths (no Drake); :mod:`rt_drake.uncertainty.inertial_set` turns them into the set
the retimer enforces the grasp on.
"""

# No ``from __future__ import annotations``: yaml_load_typed reads the types.
import dataclasses
import math

import numpy as np

from rt_drake.errors import InputError


@dataclasses.dataclass
class ObjectUncertainty:
    """Half-widths of an object's unknown inertial parameters (scenario key).

    Attributes:
        mass: Relative half-width of the mass, in [0, 1).
        com: Half-widths (m) of the centre of mass along the object's axes
            x, y, z, each >= 0.
        inertia: Relative half-width of each principal moment, in [0, 1).
    """

    mass: float = 0.0
    com: list[float] = dataclasses.field(default_factory=lambda: [0.0, 0.0, 0.0])
    inertia: float = 0.0

    def __post_init__(self) -> None:
        self.validate()

    def validate(self, key: str = "uncertainty") -> None:
        """Raise InputError naming ``key`` and the value out of range."""
        for name in ("mass", "inertia"):
            value = getattr(self, name)
            if not _is_number(value) or not math.isfinite(value):
                raise InputError(f"{key}.{name} must be a finite number, got {value!r}")
            if not 0.0 <= value < 1.0:
                raise InputError(
                    f"{key}.{name} must be in [0, 1) (a relative half-width), "
                    f"got {value!r}"
                )
        com = self.com
        if (
            not isinstance(com, (list, tuple, np.ndarray))
            or len(com) != 3
            or not all(_is_number(v) and math.isfinite(v) for v in com)
        ):
            raise InputError(f"{key}.com must be 3 finite numbers (m), got {com!r}")
        if any(v < 0.0 for v in com):
            raise InputError(f"{key}.com half-widths must be >= 0 m, got {list(com)}")

    @property
    def com_half_widths(self) -> np.ndarray:
        """(3,) ``com`` as an array, m."""
        return np.asarray(self.com, dtype=float)

    def describe(self) -> str:
        """E.g. ``mass +-20 %, CoM +-(10, 10, 5) mm, inertia +-20 %``."""
        com = ", ".join(f"{1e3 * v:.3g}" for v in self.com)
        return (
            f"mass +-{100 * self.mass:.3g} %, CoM +-({com}) mm, "
            f"inertia +-{100 * self.inertia:.3g} %"
        )

    def is_zero(self) -> bool:
        """Whether the set is the nominal object alone."""
        return self.mass == 0.0 and self.inertia == 0.0 and not any(self.com)

    def check_inside(
        self, p_OoScm_O: np.ndarray, half_extents: np.ndarray, key: str = "uncertainty"
    ) -> None:
        """Raise InputError if the CoM box leaves the object's box.

        Args:
            p_OoScm_O: (3,) nominal centre of mass in the object frame O, m.
            half_extents: (3,) half-sizes of the object's box, centred at Oo
                along O's axes, m.
            key: Names the scenario key in the message.
        """
        p = np.asarray(p_OoScm_O, dtype=float)
        reach = np.abs(p) + self.com_half_widths
        outside = np.flatnonzero(reach > np.asarray(half_extents) + 1e-12)
        if outside.size:
            j = int(outside[0])
            raise InputError(
                f"{key}.com[{j}] = {self.com[j]!r} m puts the centre of mass "
                f"{reach[j]:.4g} m from the object's centre along its "
                f"{'xyz'[j]} axis, outside the object (half-size "
                f"{half_extents[j]:.4g} m)"
            )


def _is_number(value: object) -> bool:
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(
        value, bool
    )


__all__ = ["ObjectUncertainty"]
