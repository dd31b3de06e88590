"""The bellows cup's vacuum: a pull that falls with the gap, a seal that leaks.

For a lip L (:mod:`._bellows`) over a box O, with n_O the outward normal of
the face under the lip (the box axis nearest to -z_L, within 20 deg) and
h its half extent along n_O:

- gaps: each lip point P_j lies ``g_j = p_OPj . n_O - h`` from the face
  (m; negative when pressed in), the lip's centre ``g_c`` likewise;
- seal, per lip a discrete state updated every time step
  (:class:`SealState`): with the valve on, the vacuum draws a face whose
  centre gap is within ``vacuum_range`` (DRAWING); the lip seals once
  every ``g_j <= leak_gap`` (SEALED); a sealed lip with a stretch lifted
  farther than ``leak_gap`` lets air in and loses its vacuum (LOST) until
  the valve closes (OPEN), so the object can drop;
- pull: while DRAWING or SEALED, the vacuum pulls O toward the lip with
  ``f = lambda P A max(0, 1 - max(g_c, 0) / vacuum_range)`` along -z_L,
  applied at the point Q of the face under the lip's centre, and the lip
  with the opposite force at its origin (the pressure acts inside the
  sealed cup, between lip and object, so the bellows carries only the
  object's load). lambda is the vacuum level of
  :mod:`rt_drake.model.vacuum` (the valve, the scenario's build-up), as
  for the rim cup.

Drake's suction-gripper example (PR 19491) lets its pull fall to 0 over
about 4 mm of gap in the same way; Dex-Net 3.0 loses the seal when the
perimeter deforms too far.
"""

from __future__ import annotations

import dataclasses
import enum
from collections.abc import Sequence

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.math import RigidTransform
from pydrake.multibody.plant import ExternallyAppliedSpatialForce
from pydrake.systems.framework import Context, DiscreteValues

from rt_drake.model.cup_physics import BellowsCup
from rt_drake.model.vacuum import Vacuum, next_level
from rt_drake.simulation._bellows import Lip, lip_points
from rt_drake.simulation._suction import (
    CupOnTool,
    Seal,
    SuctionCup,
    SuctionTarget,
    _force_only,
    find_seal,
)


class SealState(enum.IntEnum):
    """A lip's seal (its discrete state)."""

    OPEN = 0  # the valve is closed, or no face is near
    DRAWING = 1  # valve on, a face within the vacuum's range, not yet sealed
    SEALED = 2  # every lip point within the leak gap
    LOST = 3  # was sealed, a stretch lifted past the leak gap: no vacuum


def next_seal(
    state: SealState, valve: bool, gaps: LipGaps | None, cup: BellowsCup
) -> SealState:
    """The seal after one step (see the module docstring)."""
    if not valve:
        return SealState.OPEN
    if state is SealState.LOST:
        return state
    if state is SealState.SEALED:
        if gaps is None or gaps.largest > cup.leak_gap:
            return SealState.LOST
        return state
    if gaps is not None and gaps.largest <= cup.leak_gap:
        return SealState.SEALED
    if gaps is not None and gaps.centre < cup.vacuum_range:
        return SealState.DRAWING
    return SealState.OPEN


@dataclasses.dataclass(frozen=True)
class LipGaps:
    """Where a lip meets a box face.

    Attributes:
        centre: m, the lip centre's gap g_c to the face plane.
        largest: m, the largest gap g_j of a lip point.
        p_OQ_O: m, the point Q of the face under the lip's centre, in O.
    """

    centre: float
    largest: float
    p_OQ_O: np.ndarray


def lip_gaps(
    X_WL: RigidTransform,
    X_WO: RigidTransform,
    half_extents: np.ndarray,
    p_LP: np.ndarray,
) -> LipGaps | None:
    """The gaps of lip L (points ``p_LP``, one per row) over box O; None: no face."""
    seal = find_seal(X_WL, X_WO, half_extents)
    if seal is None:
        return None
    X_OL = X_WO.inverse() @ X_WL
    z_L_O = X_OL.rotation().matrix()[:, 2]
    axis = int(np.argmax(np.abs(z_L_O)))
    sign = -np.sign(z_L_O[axis])
    p_OP = (X_OL.rotation().matrix() @ p_LP.T).T + X_OL.translation()
    gaps = sign * p_OP[:, axis] - half_extents[axis]
    return LipGaps(centre=seal.gap, largest=float(gaps.max()), p_OQ_O=seal.p_OQ_O)


def vacuum_pull(cup: BellowsCup, gap: float) -> float:
    """N, the full-level pull at centre gap ``gap`` (m): ``P A (1 - g/range)``.

    Clamped to [0, P A]: full when pressed in (g <= 0), none past the range.
    """
    return cup.suction_force * float(np.clip(1.0 - gap / cup.vacuum_range, 0.0, 1.0))


class BellowsSuction(SuctionCup):
    """The vacuum of bellows lips on the objects under them (module docstring).

    .. pydrake_system::

        name: BellowsSuction
        input_ports:
        - valve
        - body_poses
        output_ports:
        - spatial_forces
        - sealed
        - suction_force
        - part_present

    The ports of :class:`~._suction.SuctionCup` with the same meanings;
    the cups are the lips; ``sealed`` is 1 for a target a lip holds SEALED;
    ``suction_force`` is ``sum_i lambda_i P A`` (the level's
    force, before the gap law).
    """

    def __init__(
        self,
        lips: Sequence[Lip],
        cup: BellowsCup,
        targets: list[SuctionTarget],
        vacuum: Vacuum | None = None,
        time_step: float = 1e-3,
    ) -> None:
        """Make the system for ``lips`` of the catalogue ``cup`` over ``targets``."""
        super().__init__(
            tool_body_index=lips[0].body_index,
            cups=[CupOnTool(RigidTransform(), cup.suction_force) for _ in lips],
            targets=targets,
            seal_distance=cup.leak_gap,
            vacuum=vacuum,
            time_step=time_step,
        )
        self._lips = tuple(lips)
        self._cup = cup
        self._p_LP = lip_points(cup)
        # m: a lip within the vacuum's range of a face of target i has its
        # centre within this distance of the target's origin.
        self._reach = [
            float(np.linalg.norm(t.half_extents)) + cup.vacuum_range for t in targets
        ]
        self._seal_index = self.DeclareDiscreteState(len(lips))
        self.DeclarePeriodicDiscreteUpdateEvent(time_step, 0.0, self._UpdateSeal)

    def start_sealed(self, context: Context) -> None:
        """Set every lip SEALED (and a first-order vacuum at full level) in ``context``.

        For an object that starts held on the lips (:mod:`._held_start`),
        before the simulation starts; the valve must be on from then on.
        """
        sealed = np.full(len(self._lips), float(SealState.SEALED))
        context.SetDiscreteState(self._seal_index, sealed)
        if self._level_index is not None:
            context.SetDiscreteState(self._level_index, np.ones(len(self._lips)))

    def seal_states(self, context: Context) -> list[SealState]:
        """Each lip's seal."""
        vector = context.get_discrete_state(self._seal_index).CopyToVector()
        return [SealState(int(round(v))) for v in vector]

    def _UpdateSeal(self, context: Context, state: DiscreteValues) -> None:
        valve = self._valve_on(context)
        vector = state.get_mutable_vector(self._seal_index)
        for k, (seal, found) in enumerate(
            zip(self.seal_states(context), self._lip_gaps(context), strict=True)
        ):
            gaps = None if found is None else found[1]
            vector.SetAtIndex(k, float(next_seal(seal, valve, gaps, self._cup)))

    def _lip_gaps(self, context: Context) -> list[tuple[int, LipGaps] | None]:
        """Per lip: index and gaps of the nearest face within the vacuum's range."""
        poses = self._poses_port.Eval(context)
        found = []
        for lip in self._lips:
            X_WL = poses[int(lip.body_index)]
            p_WL = X_WL.translation()
            best: tuple[int, LipGaps] | None = None
            for i, target in enumerate(self._targets):
                X_WO = poses[int(target.body_index)]
                if np.linalg.norm(X_WO.translation() - p_WL) > self._reach[i]:
                    continue
                gaps = lip_gaps(X_WL, X_WO, target.half_extents, self._p_LP)
                if gaps is None or gaps.centre >= self._cup.vacuum_range:
                    continue
                if best is None or gaps.centre < best[1].centre:
                    best = (i, gaps)
            found.append(best)
        return found

    def _seals(self, context: Context) -> list[tuple[int, Seal] | None]:
        """Per lip: the face it draws or holds (None when OPEN or LOST)."""
        seals: list[tuple[int, Seal] | None] = []
        for state, found in zip(
            self.seal_states(context), self._lip_gaps(context), strict=True
        ):
            pulls = state in (SealState.DRAWING, SealState.SEALED)
            if found is None or not pulls:
                seals.append(None)
            else:
                seals.append((found[0], Seal(found[1].centre, found[1].p_OQ_O)))
        return seals

    def _CalcSealed(self, context: Context, output) -> None:
        sealed = np.zeros(len(self._targets))
        for state, found in zip(
            self.seal_states(context), self._lip_gaps(context), strict=True
        ):
            if state is SealState.SEALED and found is not None:
                sealed[found[0]] = 1.0
        output.SetFromVector(sealed)

    def _levels(
        self, context: Context, seals: list[tuple[int, Seal] | None] | None = None
    ) -> np.ndarray:
        """Each lip's vacuum level (fixed: the valve and a face drawn or held).

        ``seals`` is not needed: the levels follow the lips' seal states.
        """
        if self._level_index is not None:
            return context.get_discrete_state(self._level_index).CopyToVector()
        valve = self._valve_on(context)
        states = self.seal_states(context)
        pulls = (SealState.DRAWING, SealState.SEALED)
        return np.array(
            [next_level(self._vacuum, 0.0, valve and s in pulls, 0.0) for s in states]
        )

    def _held(self, context: Context) -> list[tuple[int, int, Seal, float]]:
        held = []
        levels = self._levels(context)
        for k, seal in enumerate(self._seals(context)):
            if seal is None:
                continue
            force = levels[k] * vacuum_pull(self._cup, seal[1].gap)
            if force > 0.0:
                held.append((k, seal[0], seal[1], force))
        return held

    def _CalcSpatialForces(self, context: Context, output: AbstractValue) -> None:
        poses = self._poses_port.Eval(context)
        forces = []
        for k, index, seal, force in self._held(context):
            lip = self._lips[k].body_index
            f_W = -force * poses[int(lip)].rotation().matrix()[:, 2]
            on_object = ExternallyAppliedSpatialForce()
            on_object.body_index = self._targets[index].body_index
            on_object.p_BoBq_B = seal.p_OQ_O
            on_object.F_Bq_W = _force_only(f_W)
            on_lip = ExternallyAppliedSpatialForce()
            on_lip.body_index = lip
            on_lip.p_BoBq_B = np.zeros(3)
            on_lip.F_Bq_W = _force_only(-f_W)
            forces += [on_object, on_lip]
        output.set_value(forces)


__all__ = [
    "BellowsSuction",
    "LipGaps",
    "SealState",
    "lip_gaps",
    "next_seal",
    "vacuum_pull",
]
