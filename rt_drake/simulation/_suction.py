"""Suction physics: the vacuum force between each cup and a box-shaped object.

A tool carries one or more cups (:class:`CupOnTool`). Each cup i seals on its
own: while an object's face lies within the seal distance of cup i, the
vacuum pulls that object onto the cup with the force ``lambda_i P_i A_i``
along ``-z_Ci`` (lambda_i: cup i's vacuum level of :mod:`rt_drake.model.vacuum`, 1 while
the valve is on and the cup sealed in the ``fixed`` model) (C_i: the cup's
frame, +z out of the cup into the object), applied at the point of the face
under the cup's centre; the opposite force acts on the tool at the cup's
centre. Everything else (friction, the rims pushing the object) comes from
the plant's contact between each cup's rim spheres and the object, with the
friction coefficient of the contact model. One valve drives every cup.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.math import RigidTransform
from pydrake.multibody.math import SpatialForce
from pydrake.multibody.plant import ExternallyAppliedSpatialForce
from pydrake.multibody.tree import BodyIndex
from pydrake.systems.framework import BasicVector, Context, DiscreteValues, LeafSystem

from rt_drake.errors import InputError
from rt_drake.model.vacuum import (
    Vacuum,
    VacuumModel,
    next_level,
    part_present,
)

#: Cosine of the largest angle between the cup axis and a face's inward
#: normal at which the cup can still seal on that face (20 deg).
_SEAL_COS = np.cos(np.radians(20.0))


@dataclasses.dataclass(frozen=True)
class SuctionTarget:
    """A box-shaped object the cup can hold.

    Attributes:
        body_index: the object's body in the plant.
        half_extents: m, half sizes of the box along its body axes.
    """

    body_index: BodyIndex
    half_extents: np.ndarray


@dataclasses.dataclass(frozen=True)
class CupOnTool:
    """One cup of the tool, for the suction physics.

    Attributes:
        X_TC: pose of the cup frame C in the tool body T.
        suction_force: N, the cup's full vacuum force P A.
    """

    X_TC: RigidTransform
    suction_force: float


@dataclasses.dataclass(frozen=True)
class Seal:
    """Where the cup meets an object's face.

    Attributes:
        gap: m, distance from the cup's centre to the face plane, along the
            face's outward normal (negative when the cup presses into it).
        p_OQ_O: m, the point Q of the face under the cup's centre, in O.
    """

    gap: float
    p_OQ_O: np.ndarray


def find_seal(
    X_WC: RigidTransform, X_WO: RigidTransform, half_extents: np.ndarray
) -> Seal | None:
    """Return the seal of cup C on box O, or None if no face is under the cup.

    The face under the cup is the one whose outward normal n_O is within 20
    deg of ``-z_C`` and whose rectangle contains the projection of the cup's
    centre; ``gap = (p_OC - p_OF) . n_O`` with F the face centre.
    """
    X_OC = X_WO.inverse() @ X_WC
    p_OC = X_OC.translation()
    z_C_O = X_OC.rotation().matrix()[:, 2]
    # n_O = sign e_axis; -z_C . n_O >= cos 20 deg > cos 45 deg holds for one
    # face at most: the one along z_C's largest component, facing the cup.
    axis = int(np.argmax(np.abs(z_C_O)))
    sign = -1.0 if z_C_O[axis] > 0.0 else 1.0
    if -sign * z_C_O[axis] < _SEAL_COS:
        return None
    a, b = (axis + 1) % 3, (axis + 2) % 3
    if abs(p_OC[a]) > half_extents[a] or abs(p_OC[b]) > half_extents[b]:
        return None
    p_OQ = p_OC.copy()
    p_OQ[axis] = sign * half_extents[axis]
    return Seal(gap=float(sign * p_OC[axis] - half_extents[axis]), p_OQ_O=p_OQ)


class SuctionCup(LeafSystem):
    """The vacuum force of the tool's suction cups on the objects under them.

    .. pydrake_system::

        name: SuctionCup
        input_ports:
        - valve
        - body_poses
        output_ports:
        - spatial_forces
        - sealed
        - suction_force
        - part_present

    ``valve`` (1-vector, on when > 0.5; it drives every cup); ``body_poses``
    is the plant's ``body_poses`` output. Each cup seals on the target whose
    face is nearest to it (gap at most ``seal_distance``); each cup's vacuum
    level lambda_i follows the scenario's :class:`~rt_drake.model.vacuum.Vacuum`
    (:mod:`rt_drake.model.vacuum`; state: one discrete value per cup, updated every
    ``time_step``, ``fixed`` needs none). ``spatial_forces`` is a list of
    ExternallyAppliedSpatialForce for the plant: per cup that pulls,
    ``lambda_i P_i A_i`` on its sealed target and the reaction on the tool;
    ``sealed`` holds, per target, 1 if the vacuum of any cup pulls it, else 0;
    ``suction_force`` is ``sum_i lambda_i P_i A_i`` (N, 1-vector);
    ``part_present`` is the vacuum switch (1-vector, 1 when every cup's level
    reads part present, else 0).
    """

    def __init__(
        self,
        tool_body_index: BodyIndex,
        cups: Sequence[CupOnTool],
        targets: list[SuctionTarget],
        seal_distance: float = 0.005,
        vacuum: Vacuum | None = None,
        time_step: float = 1e-3,
    ) -> None:
        """Make the system.

        Args:
            tool_body_index: body T that carries the cups.
            cups: the cups, each posed in T, with its full vacuum force.
            targets: the objects the cups may hold.
            seal_distance: m, the largest gap at which the vacuum seals.
            vacuum: how the force follows the valve (default: fixed).
            time_step: s, period of the first_order level update.
        """
        super().__init__()
        if not cups:
            raise InputError("the suction tool needs at least one cup, got none")
        self._tool = tool_body_index
        self._cups = tuple(cups)
        self._targets = list(targets)
        self._seal_distance = float(seal_distance)
        self._vacuum = vacuum or Vacuum()
        self._valve_port = self.DeclareVectorInputPort("valve", 1)
        self._poses_port = self.DeclareAbstractInputPort(
            "body_poses", AbstractValue.Make([RigidTransform()])
        )
        self._level_index = None
        if self._vacuum.kind is VacuumModel.FIRST_ORDER:
            self._level_index = self.DeclareDiscreteState(len(self._cups))
            # The update at t_k + h stores lambda(t_k + h): hold, never lead.
            self.DeclarePeriodicDiscreteUpdateEvent(
                time_step, time_step, self._UpdateLevel
            )
            self._time_step = float(time_step)
        self.DeclareAbstractOutputPort(
            "spatial_forces",
            lambda: AbstractValue.Make([ExternallyAppliedSpatialForce()]),
            self._CalcSpatialForces,
        )
        self.DeclareVectorOutputPort("sealed", len(self._targets), self._CalcSealed)
        self.DeclareVectorOutputPort("suction_force", 1, self._CalcSuctionForce)
        self.DeclareVectorOutputPort("part_present", 1, self._CalcPartPresent)

    def valve_input_port(self):
        """The 1-vector valve command (on when > 0.5)."""
        return self._valve_port

    def body_poses_input_port(self):
        """The plant's body poses."""
        return self._poses_port

    def _valve_on(self, context: Context) -> bool:
        return bool(self._valve_port.Eval(context)[0] > 0.5)

    def _seals(self, context: Context) -> list[tuple[int, Seal] | None]:
        """Per cup: index and seal of the target it is sealed on, if any."""
        poses = self._poses_port.Eval(context)
        X_WT = poses[int(self._tool)]
        seals = []
        for cup in self._cups:
            X_WC = X_WT @ cup.X_TC
            best: tuple[int, Seal] | None = None
            for i, target in enumerate(self._targets):
                seal = find_seal(
                    X_WC, poses[int(target.body_index)], target.half_extents
                )
                if seal is None or seal.gap > self._seal_distance:
                    continue
                if best is None or seal.gap < best[1].gap:
                    best = (i, seal)
            seals.append(best)
        return seals

    def _levels(
        self, context: Context, seals: list[tuple[int, Seal] | None] | None = None
    ) -> np.ndarray:
        """Each cup's vacuum level lambda_i in [0, 1] (fixed: valve and seal).

        ``seals``: this context's :meth:`_seals`, if already found.
        """
        if self._level_index is None:
            valve = self._valve_on(context)
            return np.array(
                [
                    next_level(self._vacuum, 0.0, valve and seal is not None, 0.0)
                    for seal in (self._seals(context) if seals is None else seals)
                ]
            )
        return context.get_discrete_state(self._level_index).CopyToVector()

    def _held(self, context: Context) -> list[tuple[int, int, Seal, float]]:
        """Cup, target index, seal and force (N) of every cup that pulls."""
        held = []
        seals = self._seals(context)
        levels = self._levels(context, seals)
        for k, (cup, seal) in enumerate(zip(self._cups, seals, strict=True)):
            force = levels[k] * cup.suction_force
            if force > 0.0 and seal is not None:
                held.append((k, seal[0], seal[1], force))
        return held

    def _UpdateLevel(self, context: Context, state: DiscreteValues) -> None:
        valve = self._valve_on(context)
        levels = self._levels(context)
        vector = state.get_mutable_vector(self._level_index)
        for k, seal in enumerate(self._seals(context)):
            on = valve and seal is not None
            vector.SetAtIndex(
                k, next_level(self._vacuum, levels[k], on, self._time_step)
            )

    def _CalcSealed(self, context: Context, output: BasicVector) -> None:
        sealed = np.zeros(len(self._targets))
        for _, index, _, _ in self._held(context):
            sealed[index] = 1.0
        output.SetFromVector(sealed)

    def _CalcSuctionForce(self, context: Context, output: BasicVector) -> None:
        forces = [cup.suction_force for cup in self._cups]
        output.SetFromVector([float(self._levels(context) @ forces)])

    def _CalcPartPresent(self, context: Context, output: BasicVector) -> None:
        present = all(
            part_present(self._vacuum, level) for level in self._levels(context)
        )
        output.SetFromVector([1.0 if present else 0.0])

    def _CalcSpatialForces(self, context: Context, output: AbstractValue) -> None:
        poses = self._poses_port.Eval(context)
        forces = []
        for k, index, seal, force in self._held(context):
            X_TC = self._cups[k].X_TC
            X_WC = poses[int(self._tool)] @ X_TC
            # Pull on the object toward the cup: -z_C, in W.
            f_W = -force * X_WC.rotation().matrix()[:, 2]
            on_object = ExternallyAppliedSpatialForce()
            on_object.body_index = self._targets[index].body_index
            on_object.p_BoBq_B = seal.p_OQ_O
            on_object.F_Bq_W = _force_only(f_W)
            on_tool = ExternallyAppliedSpatialForce()
            on_tool.body_index = self._tool
            on_tool.p_BoBq_B = X_TC.translation()
            on_tool.F_Bq_W = _force_only(-f_W)
            forces += [on_object, on_tool]
        output.set_value(forces)


def _force_only(f_W: np.ndarray) -> SpatialForce:
    """A spatial force with no torque and force ``f_W`` (N)."""
    return SpatialForce(np.zeros(3), f_W)
