"""The rows ``F w <= g`` of the grasp constraints built from sets.

One function per source that needs more than a cached polytope: a set of
objects with every cup of a friction and suction range (:func:`robust_rows`,
:func:`object_list_rows`), and a tool of cups, exact or guided from inside
(:func:`tool_rows`, :func:`inner_tool_rows`). ``w = [torque; force]`` (N m,
N) about and in the cup frame C, or the tool frame T for a tool. Each
checks its inputs (:class:`RetimeInputError` naming the
:class:`~rt_drake.retiming.GraspConstraint` factory) and returns the rows;
the factory wraps them in its family member.
"""

from __future__ import annotations

import numpy as np

from rt_drake import arguments
from rt_drake.contact import CupParameters, ToolParameters, cached_wrench_polytope
from rt_drake.contact.load_sharing import SharedLoadSet
from rt_drake.contact.stiffness_sharing import stiffness_shared_set
from rt_drake.contact.tool import LoadSharing
from rt_drake.contact.worst_cup import worst_cup_polytope
from rt_drake.retiming._grasp_checks import check_grip, check_single_cup
from rt_drake.retiming._retime_errors import RetimeInputError
from rt_drake.types.held_object import HeldObject
from rt_drake.types.object_uncertainty import ObjectUncertainty
from rt_drake.uncertainty.inertial_set import (
    ObjectSet,
    object_list,
    uncertain_object,
)


def robust_rows(
    held: HeldObject,
    uncertainty: ObjectUncertainty,
    cup: CupParameters,
    R_CO: np.ndarray | None,
) -> tuple[np.ndarray, np.ndarray, ObjectSet]:
    """Worst-cup rows F, g and the outer object set Q around ``held``.

    F, g: the set every cup of ``cup``'s range exerts
    (:func:`~rt_drake.contact.worst_cup_polytope`); Q:
    :func:`~rt_drake.uncertainty.inertial_set.uncertain_object` with the
    object's axes R_CO in C (None: identity).
    """
    check_single_cup(cup, "robust")
    check_grip(cup, "GraspConstraint.robust")
    arguments.instance(
        uncertainty,
        "uncertainty",
        ObjectUncertainty,
        where="GraspConstraint.robust",
        error=RetimeInputError,
    )
    if R_CO is not None:
        R_CO = arguments.array(
            R_CO,
            "R_CO",
            (3, 3),
            where="GraspConstraint.robust",
            error=RetimeInputError,
        )
    F, g = worst_cup_polytope(cup)
    objects = uncertain_object(held, uncertainty, R_CO)
    return F, g, objects


def object_list_rows(
    objects: list[HeldObject], cup: CupParameters
) -> tuple[np.ndarray, np.ndarray, ObjectSet]:
    """Worst-cup rows F, g and the finite set of ``objects`` (non-empty)."""
    check_single_cup(cup, "for_objects")
    check_grip(cup, "GraspConstraint.for_objects")
    if (
        not isinstance(objects, (list, tuple))
        or not objects
        or not all(isinstance(o, HeldObject) for o in objects)
    ):
        raise arguments.fail(
            "GraspConstraint.for_objects",
            "objects",
            "a non-empty list of HeldObject",
            objects,
            RetimeInputError,
        )
    F, g = worst_cup_polytope(cup)
    return F, g, object_list(objects)


def tool_rows(
    tool: ToolParameters,
    max_facets: int | None,
    load_sharing: LoadSharing | str,
) -> tuple[np.ndarray, np.ndarray]:
    """Rows of the tool's set W_T about and in T, under ``load_sharing``.

    Several cups sharing elastically: the rim-spring set
    (:class:`~rt_drake.contact.load_sharing.SharedLoadSet`); by stiffness:
    each cup's share in its own set
    (:func:`~rt_drake.contact.stiffness_sharing.stiffness_shared_set`); else
    the exact Minkowski sum (cached, at most ``max_facets`` facets).
    """
    if not isinstance(tool, ToolParameters):
        raise RetimeInputError(
            f"for_tool needs a ToolParameters, got {type(tool).__name__}"
        )
    check_grip(tool, "GraspConstraint.for_tool")
    try:
        sharing = LoadSharing(load_sharing)
    except ValueError:
        choices = ", ".join(repr(m.value) for m in LoadSharing)
        raise RetimeInputError(
            f"load_sharing must be one of {choices}, got {load_sharing!r}"
        ) from None
    if len(tool.cups) > 1 and sharing is LoadSharing.ELASTIC:
        shared = SharedLoadSet.of(tool)
        return shared.F, shared.g
    if len(tool.cups) > 1 and sharing is LoadSharing.STIFFNESS:
        shared = stiffness_shared_set(tool)
        return shared.F, shared.g
    polytope = cached_wrench_polytope(tool, max_facets=max_facets)
    return polytope.F, polytope.g


def inner_tool_rows(
    tool: ToolParameters,
    guiding_samples: np.ndarray,
    max_vertices: int,
    seed: int,
) -> tuple[np.ndarray, np.ndarray]:
    """Rows of the hull of <= ``max_vertices`` support points of W_T.

    Chosen to cover ``guiding_samples`` ((N, 6) wrenches in T) and the zero
    wrench (:func:`~rt_drake.contact.guided_approximation`).
    """
    from rt_drake.contact import ToolWrenchSet, guided_approximation

    if not isinstance(tool, ToolParameters):
        raise RetimeInputError(
            f"inner_for_tool needs a ToolParameters, got {type(tool).__name__}"
        )
    guiding_samples = arguments.array(
        guiding_samples,
        "guiding_samples",
        ("count", 6),
        where="GraspConstraint.inner_for_tool",
        error=RetimeInputError,
    )
    samples = np.vstack([np.zeros(6), guiding_samples])
    inner = guided_approximation(ToolWrenchSet(tool), samples, max_vertices, seed=seed)
    return inner.F, inner.g
