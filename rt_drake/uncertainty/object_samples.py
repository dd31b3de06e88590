"""Objects drawn from an uncertainty set: corners, random draws, hardest corners.

An object of the set of :class:`~rt_drake.types.object_uncertainty.ObjectUncertainty`
around a nominal one has mass ``m0 (1 + e_m mass)``, centre of mass
``p0_O + e_c * com`` (along the object's axes O) and principal moments
``lambda0_j (1 + e_j inertia)`` about the nominal's principal axes, with every
``e`` in [-1, 1]. These are objects in the object frame O
(:class:`ObjectInertia`), for the physics (a body's spatial inertia) and, held
at a grasp ``X_OC``, for the retimer (:class:`~rt_drake.types.held_object.HeldObject`
in the cup frame C). Used to check a robust plan (soundness: every object it
must hold), to bound the robust optimum from below (a dense sample), and to
play a plan with a true object the planner did not know.
"""

from __future__ import annotations

import dataclasses
import itertools

import numpy as np
from pydrake.math import RigidTransform
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import RotationalInertia, SpatialInertia

from rt_drake import arguments
from rt_drake.model.object_model import OBJECT_BODY
from rt_drake.model.parser import make_parser
from rt_drake.model.scenario import ObjectConfig
from rt_drake.types.held_object import INERTIA_RTOL, HeldObject
from rt_drake.types.object_uncertainty import ObjectUncertainty


@dataclasses.dataclass(frozen=True, eq=False)
class ObjectInertia:
    """An object's inertia in its body frame O.

    Attributes:
        mass: kg.
        p_OoScm_O: (3,) centre of mass, m.
        I_Scm_O: (3, 3) rotational inertia about the centre of mass, kg m^2.
    """

    mass: float
    p_OoScm_O: np.ndarray
    I_Scm_O: np.ndarray

    def __post_init__(self) -> None:
        where = "ObjectInertia"
        arguments.number(self.mass, "mass", where=where, above=0.0)
        p = arguments.array(self.p_OoScm_O, "p_OoScm_O", (3,), where=where)
        I_Scm_O = arguments.array(self.I_Scm_O, "I_Scm_O", (3, 3), where=where)
        object.__setattr__(self, "p_OoScm_O", p)
        object.__setattr__(self, "I_Scm_O", I_Scm_O)

    @classmethod
    def of_model(cls, obj: ObjectConfig) -> ObjectInertia:
        """The inertia of a scenario object's model (its SDF's body ``body``)."""
        plant = MultibodyPlant(0.0)
        url = obj.model if "://" in obj.model else f"file://{obj.model}"
        (instance,) = make_parser(plant).AddModels(url=url)
        M = plant.GetBodyByName(OBJECT_BODY, instance).default_spatial_inertia()
        p = M.get_com()
        I_Scm_O = M.CalcRotationalInertia().ShiftToCenterOfMass(M.get_mass(), p)
        return cls(M.get_mass(), np.asarray(p), I_Scm_O.CopyToFullMatrix3())

    def spatial_inertia(self) -> SpatialInertia:
        """``M_OOo_O``: about the body origin, in O (for the plant)."""
        xx, yy, zz = np.diag(self.I_Scm_O)
        xy, xz, yz = self.I_Scm_O[0, 1], self.I_Scm_O[0, 2], self.I_Scm_O[1, 2]
        return SpatialInertia.MakeFromCentralInertia(
            self.mass, self.p_OoScm_O, RotationalInertia(xx, yy, zz, xy, xz, yz)
        )

    def held(self, X_OC: RigidTransform) -> HeldObject:
        """The object held with the cup frame at ``X_OC`` (in C)."""
        X_CO = X_OC.inverse()
        R_CO = X_CO.rotation().matrix()
        return HeldObject(
            mass=self.mass,
            p_CoScm_C=X_CO.multiply(self.p_OoScm_O),
            I_Scm_C=R_CO @ self.I_Scm_O @ R_CO.T,
        )

    def as_dict(self) -> dict[str, object]:
        """``mass`` (kg), ``com`` (m, in O), ``inertia`` (kg m^2, about Scm, in O)."""
        return {
            "mass": float(self.mass),
            "com": [float(v) for v in self.p_OoScm_O],
            "inertia": [[float(v) for v in row] for row in self.I_Scm_O],
        }


def perturbed(
    nominal: ObjectInertia,
    uncertainty: ObjectUncertainty,
    mass: float,
    com: np.ndarray,
    inertia: np.ndarray,
) -> ObjectInertia:
    """The object at relative positions in the set (module docstring).

    ``mass`` (scalar), ``com`` (3,) and ``inertia`` (3,), each in [-1, 1].
    Its moments may break the triangle inequality (no body has them; see
    :func:`is_body`).
    """
    moments, axes = np.linalg.eigh(nominal.I_Scm_O)
    scale = 1.0 + np.asarray(inertia, dtype=float) * uncertainty.inertia
    return ObjectInertia(
        mass=nominal.mass * (1.0 + mass * uncertainty.mass),
        p_OoScm_O=nominal.p_OoScm_O + np.asarray(com) * uncertainty.com_half_widths,
        I_Scm_O=axes @ np.diag(moments * scale) @ axes.T,
    )


def is_body(obj: ObjectInertia) -> bool:
    """Whether some mass distribution has these moments (triangle inequality).

    The box of principal moments of an uncertainty set reaches beyond it for
    flat objects (the notebook's largest moment is 98 % of the sum of the
    others): such objects do not exist. The robust grasp holds them too (its
    parameter set contains the whole box); samples of the set, which must be
    objects (:class:`~rt_drake.types.held_object.HeldObject` refuses the others), keep
    only bodies.
    """
    moments = np.linalg.eigvalsh(obj.I_Scm_O)
    return bool(moments[2] <= (moments[0] + moments[1]) * (1.0 + INERTIA_RTOL))


def corners(
    nominal: ObjectInertia, uncertainty: ObjectUncertainty
) -> list[ObjectInertia]:
    """The corners of the set (mass, CoM and moments at their ends) that are bodies.

    128 corners; those that break the triangle inequality of the moments are
    left out (:func:`is_body`; 48 of the notebook's at +-20 %).
    """
    signs = (-1.0, 1.0)
    every = (
        perturbed(nominal, uncertainty, m, np.array(c), np.array(i))
        for m in signs
        for c in itertools.product(signs, repeat=3)
        for i in itertools.product(signs, repeat=3)
    )
    return [obj for obj in every if is_body(obj)]


def random_objects(
    nominal: ObjectInertia,
    uncertainty: ObjectUncertainty,
    count: int,
    rng: np.random.Generator,
) -> list[ObjectInertia]:
    """``count`` objects drawn uniformly from the bodies of the set.

    Uniform draws from the box, those that are no body (:func:`is_body`)
    drawn again.
    """
    drawn: list[ObjectInertia] = []
    while len(drawn) < count:
        obj = perturbed(
            nominal,
            uncertainty,
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0, 3),
            rng.uniform(-1.0, 1.0, 3),
        )
        if is_body(obj):
            drawn.append(obj)
    return drawn


def hardest_corner(
    nominal: ObjectInertia, uncertainty: ObjectUncertainty, rng: np.random.Generator
) -> ObjectInertia:
    """A hard object of the set: heaviest, largest moments, CoM at a corner.

    The CoM corner (one sign per axis) is drawn from ``rng``; mass and
    moments at their upper ends (every moment scaled alike: a real body).
    """
    signs = rng.choice([-1.0, 1.0], size=3)
    return perturbed(nominal, uncertainty, 1.0, signs, np.ones(3))


__all__ = [
    "ObjectInertia",
    "corners",
    "hardest_corner",
    "is_body",
    "perturbed",
    "random_objects",
]
