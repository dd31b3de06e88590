"""Suction-cup contact model: parameters, contact frames and force generators.

Conventions (every function of ``rt_drake.contact`` uses them):

- Cup frame C: origin at the centre of the contact face, +z out of the cup
  into the object.
- A wrench is ``w = [torque; force]`` (Drake's SpatialForce order), the wrench
  the cup exerts ON THE OBJECT, about C's origin, expressed in C; N*m and N.
- Contact point i (i = 0..m-1) sits at ``p_CPi_C = r (cos(2 pi i/m),
  sin(2 pi i/m), 0)``. Its frame Pi has z = C's z and x radial outward, so
  ``R_CPi`` is the rotation by ``2 pi i/m`` about z.
- The rim force at point i, in Pi, is bounded by the pyramid
  ``0 <= fz <= f_max`` and the k-sided friction polygon whose vertices lie at
  angles ``2 pi j/k`` from Pi's x axis at radius ``mu fz`` (k = 4 gives
  ``|fx| + |fy| <= mu fz``). Rim forces push the object (fz >= 0).
- Suction pulls the object onto the cup: the force ``-P A`` along C's z at
  C's origin, i.e. the constant wrench ``[0, 0, 0, 0, 0, -P A]``.

So a wrench is realizable (paper eqs 8-9, Assumption 1) when
``w = sum_i G_i f_i + [0, 0, 0, 0, 0, -P A]`` with ``f_i`` in pyramid i and
``G_i = [[p_CPi_C]x R_CPi; R_CPi]``.
"""

# No ``from __future__ import annotations`` here: pydrake's yaml_load_typed reads
# the dataclass field types, which must be real types, not strings.
import dataclasses
import math
from typing import Any, Self

import numpy as np

from rt_drake import arguments
from rt_drake.errors import InputError

#: Accepted range of each real parameter, [low, high] in SI units: the range
#: of physically sensible suction cups, so that a typo (1e-300, 1e300) is
#: refused instead of producing a degenerate polytope (all-zero rows, or
#: vertices that violate their own H-representation in floating point).
#: Radius 0.1 mm (micro cups) to 0.5 m (a 1 m cup); friction of an elastomer
#: lip on packaging 0 to 1.5; forces 1 mN to 100 kN (full vacuum on a 0.5 m
#: radius cup is 79 kN).
PARAMETER_RANGES: dict[str, tuple[float, float]] = {
    "radius": (1e-4, 0.5),
    "friction": (0.0, 1.5),
    "suction_force": (1e-3, 1e5),
    "max_normal_force": (1e-3, 1e5),
}
#: Accepted range of the counts (contact points m, friction polygon sides k).
#: The exact polytope's cost grows steeply with both; its own limit is a
#: memory estimate (``rt_drake.contact.wrench_polytope``), usually lower.
COUNT_RANGES: dict[str, tuple[int, int]] = {"points": (3, 1000), "sides": (3, 1000)}


@dataclasses.dataclass
class CupParameters:
    """Point-contact model of a suction cup (defaults: the paper's cup).

    Attributes (accepted ranges: :data:`PARAMETER_RANGES`,
    :data:`COUNT_RANGES`):
        radius: Radius r of the circle of contact points, in m.
        points: Number m of contact points on the rim (>= 3).
        friction: Coulomb friction coefficient mu (>= 0).
        sides: Number k of sides of the linearised friction cone (>= 3).
        suction_force: Suction force P A pulling the object onto the cup, N.
        max_normal_force: Bound f_max on the normal force of each point, N.
        friction_min: The lowest friction the cup may have (dust, wear), in
            [0, friction]; None: friction is known.
        suction_force_min: The lowest suction force (leaks), N, in (0,
            suction_force]; None: suction is known.
        peel_fraction: c in (0, 1]: a compliant lip, whose tilting moment
            is kept to ``|M_t| <= c r (P A + f_z)`` (1/2: the ring of lip
            springs lifts nowhere; :mod:`rt_drake.contact.peel`); None: the
            rigid rim alone (the paper's model).

    The last two describe what is not known about the cup; they are not
    parameters of its wrench set (``as_dict`` leaves them out) but of the
    range of cups a robust grasp must work with (:meth:`worst_case`).
    """

    radius: float = 0.0125
    points: int = 6
    friction: float = 0.3
    sides: int = 4
    suction_force: float = 20.0
    max_normal_force: float = 33.3
    friction_min: float | None = None
    suction_force_min: float | None = None
    peel_fraction: float | None = None

    def __post_init__(self) -> None:
        self.validate()

    def validate(self) -> None:
        """Raise InputError naming the first parameter that is out of range."""
        self._validate_peel()
        for name, (first, last) in COUNT_RANGES.items():
            count = getattr(self, name)
            if isinstance(count, bool) or not isinstance(count, (int, np.integer)):
                raise InputError(f"cup {name} must be an integer, got {count!r}")
            if not first <= count <= last:
                raise InputError(
                    f"cup {name} must be in [{first}, {last}], got {count!r}"
                )
        for name, (low, high) in PARAMETER_RANGES.items():
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(
                value, (int, float, np.integer, np.floating)
            ):
                raise InputError(f"cup {name} must be a number, got {value!r}")
            if not math.isfinite(value):
                raise InputError(f"cup {name} must be finite, got {value!r}")
            if not low <= value <= high:
                raise InputError(
                    f"cup {name} must be in [{low:g}, {high:g}]{_UNITS[name]}, "
                    f"got {value!r}"
                )
        for name, nominal in (
            ("friction_min", "friction"),
            ("suction_force_min", "suction_force"),
        ):
            value = getattr(self, name)
            if value is None:
                continue
            if isinstance(value, bool) or not isinstance(
                value, (int, float, np.integer, np.floating)
            ):
                raise InputError(f"cup {name} must be a number, got {value!r}")
            low = PARAMETER_RANGES[nominal][0]
            if not math.isfinite(value) or value < low:
                raise InputError(
                    f"cup {name} must be finite and >= {low:g}{_UNITS[nominal]}, "
                    f"got {value!r}"
                )
            if value > getattr(self, nominal):
                raise InputError(
                    f"cup {name} = {value!r} exceeds {nominal} = "
                    f"{getattr(self, nominal)!r}"
                )

    def _validate_peel(self) -> None:
        """``peel_fraction`` None or a finite number in (0, 1]."""
        value = self.peel_fraction
        if value is None:
            return
        if isinstance(value, bool) or not isinstance(
            value, (int, float, np.integer, np.floating)
        ):
            raise InputError(f"cup peel_fraction must be a number, got {value!r}")
        if not (math.isfinite(value) and 0.0 < value <= 1.0):
            raise InputError(f"cup peel_fraction must be in (0, 1], got {value!r}")

    @classmethod
    def from_vacuum(cls, pressure_pa: float, area_m2: float, **fields: Any) -> Self:
        """Return a cup whose suction force is ``P A`` (N).

        Args:
            pressure_pa: Vacuum (negative gauge) pressure P, in Pa, > 0.
            area_m2: Suction area A, in m^2, > 0.
            **fields: Any other field of CupParameters.
        """
        for name, value in (("pressure_pa", pressure_pa), ("area_m2", area_m2)):
            if not (isinstance(value, (int, float)) and math.isfinite(value)):
                raise InputError(f"{name} must be a finite number, got {value!r}")
            if value <= 0.0:
                raise InputError(f"{name} must be > 0, got {value!r}")
        return cls(suction_force=float(pressure_pa) * float(area_m2), **fields)

    def as_dict(self) -> dict[str, float | int]:
        """Return the model's fields as plain Python numbers, in declaration order.

        The fields that define the wrench set (and its cache key): not
        ``friction_min`` and ``suction_force_min``, and ``peel_fraction``
        only when set (the rigid rim's key and set are the paper model's).
        """
        return {
            f.name: (int if f.type is int else float)(getattr(self, f.name))
            for f in dataclasses.fields(self)
            if f.name not in _RANGE_FIELDS
            and not (f.name == "peel_fraction" and self.peel_fraction is None)
        }

    def is_uncertain(self) -> bool:
        """Whether friction or suction is known only down to a minimum."""
        return (
            self.friction_min is not None and self.friction_min < self.friction
        ) or (
            self.suction_force_min is not None
            and self.suction_force_min < self.suction_force
        )

    def worst_case(self) -> Self:
        """The cup at ``friction_min`` and ``suction_force_min`` (no ranges).

        W_c grows with the friction (every friction polygon contains the
        polygons of lower friction at the same normal force): its wrench set
        is contained in that of every cup of the range. Suction shifts W_c
        along the cup axis instead (see :mod:`rt_drake.contact.worst_cup`).
        """
        fields = {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}
        fields.update(
            friction=self.friction if self.friction_min is None else self.friction_min,
            suction_force=self.suction_force
            if self.suction_force_min is None
            else self.suction_force_min,
            friction_min=None,
            suction_force_min=None,
        )
        return type(self)(**fields)


#: Fields of CupParameters that describe a range of cups, not one cup.
_RANGE_FIELDS = ("friction_min", "suction_force_min")


_UNITS = {
    "radius": " m",
    "friction": "",
    "suction_force": " N",
    "max_normal_force": " N",
}


def contact_positions(cup: CupParameters) -> np.ndarray:
    """Return ``p_CPi_C`` (m, 3), in m: the rim contact points in C."""
    angles = 2.0 * np.pi * np.arange(cup.points) / cup.points
    zeros = np.zeros_like(angles)
    return cup.radius * np.stack([np.cos(angles), np.sin(angles), zeros], axis=1)


def contact_rotations(cup: CupParameters) -> np.ndarray:
    """Return ``R_CPi`` (m, 3, 3): rotation by ``2 pi i/m`` about C's z."""
    angles = 2.0 * np.pi * np.arange(cup.points) / cup.points
    c, s = np.cos(angles), np.sin(angles)
    rotations = np.zeros((cup.points, 3, 3))
    rotations[:, 0, 0], rotations[:, 0, 1] = c, -s
    rotations[:, 1, 0], rotations[:, 1, 1] = s, c
    rotations[:, 2, 2] = 1.0
    return rotations


def grasp_matrices(cup: CupParameters) -> np.ndarray:
    """Return ``G_i`` (m, 6, 3): force in Pi -> wrench about C's origin in C.

    ``G_i = [[p_CPi_C]x R_CPi; R_CPi]`` (paper eq. 8).
    """
    arguments.instance(cup, "cup", CupParameters, where="grasp_matrices")
    p = contact_positions(cup)
    rotations = contact_rotations(cup)
    skew = np.zeros((cup.points, 3, 3))
    skew[:, 0, 1], skew[:, 0, 2] = -p[:, 2], p[:, 1]
    skew[:, 1, 0], skew[:, 1, 2] = p[:, 2], -p[:, 0]
    skew[:, 2, 0], skew[:, 2, 1] = -p[:, 1], p[:, 0]
    return np.concatenate([skew @ rotations, rotations], axis=1)


def friction_pyramid(cup: CupParameters) -> np.ndarray:
    """Return the (k + 1, 3) vertices of the bounded friction cone, in Pi, N.

    Row 0 is the apex 0; row 1 + j is ``f_max (mu cos a_j, mu sin a_j, 1)``
    with ``a_j = 2 pi j/k``.
    """
    angles = 2.0 * np.pi * np.arange(cup.sides) / cup.sides
    mu = cup.friction
    base = np.stack(
        [mu * np.cos(angles), mu * np.sin(angles), np.ones_like(angles)], axis=1
    )
    return np.vstack([np.zeros(3), cup.max_normal_force * base])


def friction_halfspaces(cup: CupParameters) -> tuple[np.ndarray, np.ndarray]:
    """Return ``(A, b)`` with the pyramid as ``A f <= b`` for f in Pi (N).

    Polygon edge j has outward normal at angle ``2 pi (j + 1/2)/k`` and reads
    ``cos(b_j) fx + sin(b_j) fy <= mu cos(pi/k) fz``; then ``-fz <= 0`` and
    ``fz <= f_max``. This is the H-form, independent of the vertex list.
    """
    k, mu = cup.sides, cup.friction
    normals = 2.0 * np.pi * (np.arange(k) + 0.5) / k
    polygon = np.stack(
        [np.cos(normals), np.sin(normals), np.full(k, -mu * np.cos(np.pi / k))],
        axis=1,
    )
    A = np.vstack([polygon, [0.0, 0.0, -1.0], [0.0, 0.0, 1.0]])
    b = np.concatenate([np.zeros(k + 1), [cup.max_normal_force]])
    return A, b


def suction_wrench(cup: CupParameters) -> np.ndarray:
    """Return the suction wrench on the object, ``[0, 0, 0, 0, 0, -P A]``."""
    arguments.instance(cup, "cup", CupParameters, where="suction_wrench")
    return np.array([0.0, 0.0, 0.0, 0.0, 0.0, -cup.suction_force])
