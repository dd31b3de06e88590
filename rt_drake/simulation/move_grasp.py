"""The grasp a MOVE is retimed under: the held object, the wrench set, the cup.

What :class:`~rt_drake.simulation.OnlineMotions` (and the campaigns and the
``plan`` command) take from the scenario to state the grasp constraint
``F w <= g`` of a MOVE: the held object's inertia in the cup frame
(:func:`held_object`), the set W of the cup or tool (:func:`move_polytope`),
the cup with the suction range a MOVE may rely on (:func:`move_cup`), and
the joint limits of a grasp-constrained MOVE (:func:`grasp_limits`), the
grasp constraint itself, nominal or robust (:func:`grasp_for`), and the
bellows cups whose ring sets the margin with ``planning.grasp_margin:
ring`` (:func:`ring_tool`). Units:
SI; wrenches about the cup (or tool) frame, in it.
"""

from __future__ import annotations

import dataclasses

import numpy as np
from pydrake.common.schema import Transform
from pydrake.math import RigidTransform, RotationMatrix

from rt_drake.contact import (
    CupParameters,
    LoadSharing,
    SharedLoadSet,
    ToolParameters,
    WrenchPolytope,
    cached_wrench_polytope,
    stiffness_shared_set,
    with_suction_force,
    worst_cup_polytope,
)
from rt_drake.dynamics.bellows_modes import BellowsTool
from rt_drake.errors import ScenarioError
from rt_drake.model.cup_physics import load_bellows_cup
from rt_drake.model.held import held_object_of
from rt_drake.model.scenario import RING, ObjectConfig, Scenario
from rt_drake.retiming import GraspConstraint, JointLimits, ObjectSetGrasp
from rt_drake.types.held_object import HeldObject
from rt_drake.types.object_uncertainty import ObjectUncertainty
from rt_drake.uncertainty.inertial_set import uncertain_object


def held_object(obj: ObjectConfig, X_OC: RigidTransform) -> HeldObject:
    """Inertia of ``obj`` in the cup frame, held at grasp ``X_OC``."""
    return held_object_of(dataclasses.replace(obj, grasp=Transform(X_OC)))


def move_polytope(scenario: Scenario) -> WrenchPolytope | SharedLoadSet:
    """The wrench set the MOVE is retimed under (F, g and the cup or tool).

    The scenario's cup W_c (cached on disk), or its tool's set about the
    tool frame, in it: for several cups with ``tool.load_sharing:
    elastic`` (the default) the rims' spring split (:class:`SharedLoadSet`,
    milliseconds), with ``stiffness`` each cup's share of the bellows'
    stiffness split in its own set, with ``any`` the exact W_T of any split
    (two paper cups: 47,728 rows, about a minute the first time, then
    cached). With a ``first_order`` vacuum, for the suction force guaranteed at "part
    present": every cup's ``P A`` times ``part_present_fraction`` (one cup:
    W_c translated; a tool: the set of the tool with those forces).
    """
    fraction = scenario.vacuum.move_force_fraction
    if scenario.tool is None:
        full = cached_wrench_polytope(scenario.cup)
        if fraction == 1.0:
            return full
        return with_suction_force(full, fraction * scenario.cup.suction_force)
    tool = scenario.tool_parameters()
    if fraction != 1.0:
        tool = ToolParameters(
            cups=tuple(
                dataclasses.replace(
                    mount,
                    cup=dataclasses.replace(
                        mount.cup,
                        suction_force=fraction * mount.cup.suction_force,
                    ),
                )
                for mount in tool.cups
            )
        )
    if len(tool.cups) > 1 and scenario.tool.load_sharing == LoadSharing.ELASTIC.value:
        return SharedLoadSet.of(tool)
    if len(tool.cups) > 1 and scenario.tool.load_sharing == LoadSharing.STIFFNESS.value:
        return stiffness_shared_set(tool)
    return cached_wrench_polytope(tool)


def grasp_limits(limits: JointLimits, scenario: Scenario) -> JointLimits:
    """The joint limits of a MOVE retimed under the grasp constraint.

    ``limits`` with each joint's jerk at most ``a_j / planning.grasp_ramp_s``
    (rad/s^3, ``a_j`` the acceleration limit) when the scenario gives that
    margin (:meth:`~rt_drake.retiming.JointLimits.with_acceleration_ramp`);
    else ``limits`` unchanged. Motions without the grasp constraint keep
    ``limits``: the ramp is a margin of the grasp, not a robot limit.
    """
    ramp_s = scenario.planning.grasp_ramp_s
    return limits if ramp_s is None else limits.with_acceleration_ramp(ramp_s)


def move_cup(scenario: Scenario) -> CupParameters:
    """The scenario's (single) cup with the suction range a MOVE may rely on.

    With a ``first_order`` vacuum the MOVE starts when "part present" fires,
    at ``part_present_fraction`` of the suction, and the force then builds
    up: the range reaches down to that fraction of its lowest P A.
    """
    cup = scenario.single_cup("a robust grasp (an uncertainty set)")
    fraction = scenario.vacuum.move_force_fraction
    if fraction == 1.0:
        return cup
    lowest = (
        cup.suction_force if cup.suction_force_min is None else cup.suction_force_min
    )
    return dataclasses.replace(cup, suction_force_min=fraction * lowest)


def grasp_for(
    scenario: Scenario,
    obj: ObjectConfig,
    X_OC: RigidTransform,
    robust: bool,
    polytope: WrenchPolytope | SharedLoadSet | None = None,
    worst_cup: tuple[np.ndarray, np.ndarray] | None = None,
) -> GraspConstraint:
    """The grasp constraint of ``obj`` held at ``X_OC``.

    Robust (every object of its uncertainty set, every cup of the cup's
    range: :class:`~rt_drake.retiming.ObjectSetGrasp`) when ``robust`` and
    the scenario gives a set or a range; else the nominal object and cup
    (:func:`move_polytope`, or ``polytope`` if computed already). Shrunk by
    the scenario's ``planning.grasp_margin`` (not with ``ring``: the MOVE's
    retime shrinks it, :func:`ring_tool`). ``worst_cup``: the cup's
    worst-case rows ``(F, g)`` (:func:`~rt_drake.contact.worst_cup_polytope`
    of :func:`move_cup`) if computed already.
    """
    margin = scenario.planning.fixed_margin
    held = held_object(obj, X_OC)
    uncertainty = obj.uncertainty or ObjectUncertainty()
    uncertain_cup = scenario.tool is None and scenario.cup.is_uncertain()
    if not robust or (uncertainty.is_zero() and not uncertain_cup):
        polytope = polytope or move_polytope(scenario)
        return GraspConstraint.for_polytope(held, polytope).with_margin(margin)
    cup = move_cup(scenario)
    F, g = worst_cup or worst_cup_polytope(cup)
    R_CO = X_OC.inverse().rotation().matrix()
    objects = uncertain_object(held, uncertainty, R_CO)
    grasp = ObjectSetGrasp(held=held, F=F, g=g, cup=cup, objects=objects)
    return grasp.with_margin(margin)


def ring_tool(scenario: Scenario, robust: bool = False) -> BellowsTool | None:
    """The bellows cups whose ring sets each MOVE's margin, or None.

    With ``planning.grasp_margin: ring``: the catalogue cup
    ``cup_physics.cup`` at each of the tool's cup poses ``X_TC`` (one cup:
    at the tool frame), whatever ``cup_physics.kind`` the simulation plays:
    the margin is the planner's statement about that cup's modes
    (:func:`rt_drake.retiming.retime_for_ring`). Else None.

    Raises:
        ScenarioError: ``ring`` with ``robust`` and an object with an
            uncertainty set (the bound rings one object, not a set).
    """
    if not scenario.planning.ring_margin:
        return None
    uncertain = [
        obj.name
        for obj in scenario.objects
        if obj.uncertainty is not None and not obj.uncertainty.is_zero()
    ]
    if robust and uncertain:
        raise ScenarioError(
            f"{scenario.key('planning.grasp_margin')}: '{RING}' bounds the ring "
            f"of one object, not of the uncertainty set of {', '.join(uncertain)}; "
            "give a number (python tools/bellows_margin.py SCENARIO --robust)"
        )
    cup = load_bellows_cup(scenario.cup_physics.cup)
    X_TCs = tuple(
        RigidTransform(RotationMatrix(mount.R_TC), mount.p_TC)
        for mount in scenario.tool_parameters().cups
    )
    return BellowsTool(cup, X_TCs)


__all__ = [
    "grasp_for",
    "grasp_limits",
    "held_object",
    "move_cup",
    "move_polytope",
    "ring_tool",
]
