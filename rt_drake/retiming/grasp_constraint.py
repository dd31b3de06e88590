"""The grasp of a held object: ``F w <= g``, one class per source of the rows.

A grasp constraint is one of a small family behind :class:`GraspConstraint`
(``held``, ``F``, ``g``, :attr:`~GraspConstraint.is_robust`,
:meth:`~GraspConstraint.describe`, :meth:`~GraspConstraint.guarantee`), one
class per source of the rows:

- :class:`GraspConstraint` itself: rows given by hand, of one object;
- :class:`CupGrasp`: one object on one cup, its exact set
  (:meth:`GraspConstraint.for_cup`);
- :class:`ToolGrasp`: one object on a tool of cups
  (:meth:`GraspConstraint.for_tool`, :meth:`GraspConstraint.inner_for_tool`);
- :class:`ObjectSetGrasp`: every object of a set with every cup of a
  friction and suction range: an uncertainty set around a nominal object
  (:meth:`GraspConstraint.robust`, :mod:`rt_drake.uncertainty.inertial_set`,
  :mod:`rt_drake.contact.worst_cup`), or a finite list of objects
  (:meth:`GraspConstraint.for_objects`).

The rows of the sets are built by :mod:`._grasp_sets`, the cup and tool
checked by :mod:`._grasp_checks`.
"""

from __future__ import annotations

import dataclasses

import numpy as np
from pydrake.common.schema import Transform
from pydrake.math import RigidTransform

from rt_drake import arguments
from rt_drake.contact import (
    CupParameters,
    ToolParameters,
    WrenchPolytope,
    cached_wrench_polytope,
)
from rt_drake.contact.load_sharing import SharedLoadSet
from rt_drake.contact.tool import LoadSharing
from rt_drake.contact.tool_polytope import DEFAULT_MAX_FACETS
from rt_drake.contact.wrench_polytope import check_h_representation
from rt_drake.errors import InputError
from rt_drake.model.held import held_object_of
from rt_drake.model.scenario import ObjectConfig
from rt_drake.retiming._grasp_checks import check_grip, check_source, suction_text
from rt_drake.retiming._grasp_sets import (
    inner_tool_rows,
    object_list_rows,
    robust_rows,
    tool_rows,
)
from rt_drake.retiming._retime_errors import RetimeInputError
from rt_drake.types.held_object import HeldObject
from rt_drake.types.object_uncertainty import ObjectUncertainty
from rt_drake.uncertainty.inertial_set import ObjectSet

#: Largest share of g a grasp margin may keep free (``with_margin``).
MAX_GRASP_MARGIN = 0.9


@dataclasses.dataclass(frozen=True, eq=False)
class GraspConstraint:
    """Grasp stability ``F w <= g`` of a held object (paper eq. 20).

    ``w = [torque; force]`` (N m, N) is the wrench the cup exerts on the
    object about the cup origin Co, in the cup frame C (:mod:`rt_drake.contact`
    conventions). ``g > 0`` row-wise: the zero wrench is strictly inside.

    For a tool of several cups (:class:`~rt_drake.contact.ToolParameters`)
    the frame the retimer is given (``cup=``, default ``suction_cup``) is the
    tool frame T: ``held`` is the object's inertia in T, and F, g describe
    the tool's set W_T about T's origin, in T (:meth:`for_tool`).

    Built directly, ``GraspConstraint(held, F, g)`` holds one object under
    rows given by hand. The classmethods build the family member of each
    source (module docstring); the retimer and the checks use only what this
    class has.

    Attributes:
        held: Inertia of the object in C or T (the nominal one of a set).
        F: (R, 6) rows (unit norm from :mod:`rt_drake.contact`).
        g: (R,) offsets.
    """

    held: HeldObject
    F: np.ndarray
    g: np.ndarray

    def __post_init__(self) -> None:
        where = type(self).__name__
        arguments.instance(
            self.held, "held", HeldObject, where=where, error=RetimeInputError
        )
        try:  # shapes, no rows, NaN or inf, an all-zero row (constrains nothing)
            F, g = check_h_representation(self.F, self.g, where)
        except InputError as error:
            raise RetimeInputError(str(error)) from None
        F, g = F.copy(), g.copy()
        if np.any(g <= 0.0):
            row = int(np.argmin(g))
            raise RetimeInputError(
                f"{where}: g must be > 0 (the zero wrench strictly inside), "
                f"got g[{row}] = {g[row]!r}"
            )
        F.setflags(write=False)
        g.setflags(write=False)
        object.__setattr__(self, "F", F)
        object.__setattr__(self, "g", g)

    @staticmethod
    def for_cup(held: HeldObject, cup: CupParameters) -> CupGrasp:
        """The exact polytope of ``cup`` (cached on disk by rt_drake.contact)."""
        check_grip(cup, "GraspConstraint.for_cup")
        polytope = cached_wrench_polytope(cup)
        return CupGrasp(held=held, F=polytope.F, g=polytope.g, cup=cup)

    @staticmethod
    def for_polytope(
        held: HeldObject, polytope: WrenchPolytope | SharedLoadSet
    ) -> CupGrasp | ToolGrasp:
        """The rows of a wrench set already computed for a cup or a tool.

        E.g. ``cached_wrench_polytope(cup)`` or the set the cycle retimes a
        MOVE under (``rt_drake.simulation.move_grasp.move_polytope``).
        """
        if isinstance(polytope.cup, ToolParameters):
            return ToolGrasp(held=held, F=polytope.F, g=polytope.g, tool=polytope.cup)
        return CupGrasp(held=held, F=polytope.F, g=polytope.g, cup=polytope.cup)

    @staticmethod
    def robust(
        held: HeldObject,
        uncertainty: ObjectUncertainty,
        cup: CupParameters,
        R_CO: np.ndarray | None = None,
    ) -> ObjectSetGrasp:
        """Hold every object of ``uncertainty`` around ``held`` with every cup.

        The wrench set is the one every cup of ``cup``'s friction and suction
        range can exert (:func:`~rt_drake.contact.worst_cup_polytope`); the
        objects are the outer set Q of :func:`~rt_drake.uncertainty.inertial_set.
        uncertain_object`, which contains every admissible object. A
        zero-width set of a known cup is exactly :meth:`for_cup`.

        Args:
            held: The nominal object in C.
            uncertainty: Half-widths of mass, CoM (along the object's axes)
                and principal moments.
            cup: The cup, with optional ``friction_min``, ``suction_force_min``.
            R_CO: (3, 3) the object's axes in C (default identity).
        """
        F, g, objects = robust_rows(held, uncertainty, cup, R_CO)
        return ObjectSetGrasp(held=held, F=F, g=g, cup=cup, objects=objects)

    @staticmethod
    def for_objects(objects: list[HeldObject], cup: CupParameters) -> ObjectSetGrasp:
        """Hold each object of a list (the first is the nominal one).

        Retiming under it stacks every object's constraint: with a dense
        sample of an uncertainty set, its duration bounds the robust optimum
        from below.
        """
        F, g, held_set = object_list_rows(objects, cup)
        return ObjectSetGrasp(held=objects[0], F=F, g=g, cup=cup, objects=held_set)

    @staticmethod
    def for_scenario_object(
        obj: ObjectConfig,
        cup: CupParameters,
        X_OC: RigidTransform | None = None,
        robust: bool = True,
    ) -> CupGrasp | ObjectSetGrasp:
        """The grasp of a scenario object held at ``X_OC`` (default its grasp).

        Robust (:meth:`robust`) when ``robust`` and the object has an
        uncertainty set or the cup a friction or suction range; else
        :meth:`for_cup` (the nominal object and cup).
        """
        if X_OC is not None:
            obj = dataclasses.replace(obj, grasp=Transform(X_OC))
        held = held_object_of(obj)
        uncertainty = obj.uncertainty or ObjectUncertainty()
        if robust and (not uncertainty.is_zero() or cup.is_uncertain()):
            X_CO = obj.grasp.GetDeterministicValue().inverse()
            return GraspConstraint.robust(
                held, uncertainty, cup, X_CO.rotation().matrix()
            )
        return GraspConstraint.for_cup(held, cup)

    @property
    def is_robust(self) -> bool:
        """Whether the constraint holds a set of objects, not one object."""
        return False

    def guarantee(self) -> str:
        """What a trajectory retimed under this constraint holds, in words."""
        return f"the nominal object ({self.held.mass:.3g} kg)"

    def describe(self) -> str:
        """E.g. ``object 0.551 kg`` (a cup adds its suction, a tool its cups)."""
        return f"object {self.held.mass:.3g} kg"

    def with_margin(self, fraction: float) -> GraspConstraint:
        """This constraint with a share of each row kept free: ``F w <= (1 - m) g``.

        ``m = fraction`` in [0, :data:`MAX_GRASP_MARGIN`]. The set is the
        original scaled by ``1 - m`` about the zero wrench (inside it), so a
        subset: a motion retimed under it keeps ``m g`` of every row for
        what the retimer does not see, e.g. a controller's interpolation
        between samples (docs: export guide). Same class, same source;
        ``fraction = 0`` returns ``self``.

        Raises:
            RetimeInputError: ``fraction`` not a number in that range.
        """
        where = f"{type(self).__name__}.with_margin"
        fraction = arguments.number(
            fraction, "fraction", where=where, low=0.0, high=MAX_GRASP_MARGIN,
            error=RetimeInputError,
        )  # fmt: skip
        if fraction == 0.0:
            return self
        return dataclasses.replace(self, g=(1.0 - fraction) * self.g)

    @staticmethod
    def for_tool(
        held: HeldObject,
        tool: ToolParameters,
        max_facets: int | None = DEFAULT_MAX_FACETS,
        load_sharing: LoadSharing | str = LoadSharing.ELASTIC,
    ) -> ToolGrasp:
        """The wrench set of a ``tool``, about and in the tool frame T.

        ``held`` is the object's inertia in T, which is the frame given to
        the retimer. With several cups, ``load_sharing`` says how they split
        the load:

        - ``elastic`` (default): a rigid tool and object on equal rim springs
          (:mod:`rt_drake.contact.load_sharing`; cups in T's z = 0 plane,
          axes along z); a few hundred rows, computed in milliseconds.
        - ``stiffness``: compliant (bellows) cups split the whole wrench by
          the ``stiffness`` every cup of ``tool`` states, and each cup's
          share must lie in its own W_c
          (:mod:`rt_drake.contact.stiffness_sharing`); milliseconds.
        - ``any``: any split (the exact Minkowski sum W_T, cached on disk;
          two paper cups take about a minute the first time, 47,728 rows;
          more than ``max_facets`` facets raise ``TooManyFacetsError``, a
          ``TooLargeError``: use :meth:`inner_for_tool`). It over-claims
          for a rigid tool: see :class:`~rt_drake.contact.LoadSharing`.

        One cup: its exact set W_c mapped to T (the paper's).
        """
        F, g = tool_rows(tool, max_facets, load_sharing)
        return ToolGrasp(held=held, F=F, g=g, tool=tool)

    @staticmethod
    def inner_for_tool(
        held: HeldObject,
        tool: ToolParameters,
        guiding_samples: np.ndarray,
        max_vertices: int = 60,
        seed: int = 0,
    ) -> ToolGrasp:
        """A sound inner approximation of a tool's W_T, without its facets.

        The hull of at most ``max_vertices`` support points of W_T chosen to
        cover ``guiding_samples`` ((N, 6) wrenches in T, e.g. the wrenches of
        the motions to come; the zero wrench is added): every wrench it
        accepts is realizable (the paper's guided approximation over
        :class:`~rt_drake.contact.ToolWrenchSet`).
        For tools whose exact set is too large (four cups: > 1.5 million
        facets).
        """
        F, g = inner_tool_rows(tool, guiding_samples, max_vertices, seed)
        return ToolGrasp(held=held, F=F, g=g, tool=tool)


@dataclasses.dataclass(frozen=True, eq=False)
class CupGrasp(GraspConstraint):
    """One object on one cup, under rows of that cup (the nominal cup).

    Attributes:
        cup: The cup the rows belong to.
    """

    cup: CupParameters

    def __post_init__(self) -> None:
        check_source(self, "cup", CupParameters)
        super().__post_init__()

    def describe(self) -> str:
        """E.g. ``object 0.551 kg, suction 20 N (at least 18 N)``."""
        return super().describe() + suction_text(self.cup)


@dataclasses.dataclass(frozen=True, eq=False)
class ToolGrasp(GraspConstraint):
    """One object on a tool of cups, in the tool frame T.

    Attributes:
        tool: The tool the rows belong to.
    """

    tool: ToolParameters

    def __post_init__(self) -> None:
        check_source(self, "tool", ToolParameters)
        super().__post_init__()

    def describe(self) -> str:
        """E.g. ``object 0.551 kg, 2 cups, suction 20 + 20 N``."""
        cups = self.tool.cups
        forces = " + ".join(f"{m.cup.suction_force:.3g}" for m in cups)
        return super().describe() + f", {len(cups)} cups, suction {forces} N"


@dataclasses.dataclass(frozen=True, eq=False)
class ObjectSetGrasp(GraspConstraint):
    """Every object of a set, with every cup of ``cup``'s range (one cup).

    F, g hold for every cup of ``cup``'s friction and suction range
    (:func:`~rt_drake.contact.worst_cup_polytope`); ``held`` is the set's
    nominal object. A set of one object (zero width) is retimed as that
    object alone (:attr:`is_robust` is False).

    Attributes:
        cup: The cup, with its optional friction and suction range.
        objects: The set of objects to hold.
    """

    cup: CupParameters
    objects: ObjectSet

    def __post_init__(self) -> None:
        check_source(self, "cup", CupParameters)
        arguments.instance(
            self.objects,
            "objects",
            ObjectSet,
            where=type(self).__name__,
            error=RetimeInputError,
        )
        super().__post_init__()

    @property
    def is_robust(self) -> bool:
        """Whether the set is more than one object."""
        return not self.objects.is_single()

    @property
    def worst_cup(self) -> bool:
        """Whether F, g are those of the worst cup of a friction or suction range."""
        return self.cup.is_uncertain()

    def guarantee(self) -> str:
        """E.g. ``every object of the set (...), friction down to 0.4 and ...``."""
        what = super().guarantee()
        if self.is_robust:
            what = f"every object of the set ({self.objects.label})"
        if self.worst_cup:
            cup = self.cup.worst_case()
            what += (
                f", friction down to {cup.friction:.3g} and suction down to "
                f"{cup.suction_force:.3g} N"
            )
        return what

    def describe(self) -> str:
        """E.g. ``every object of the set around object 0.551 kg, suction 20 N``."""
        text = super().describe()
        if self.is_robust:
            text = f"every object of the set around {text}"
        return text + suction_text(self.cup)


#: What every grasp constraint has (the retimer's duck-typed check).
GRASP_ATTRIBUTES = ("held", "F", "g", "is_robust")


__all__ = [
    "GRASP_ATTRIBUTES",
    "MAX_GRASP_MARGIN",
    "CupGrasp",
    "GraspConstraint",
    "ObjectSetGrasp",
    "ToolGrasp",
]
