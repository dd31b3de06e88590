"""The pick-and-place sequencer: APPROACH, REACH, ATTACH, MOVE, DETACH per object.

The sequencer commands the arm and the suction valve. When a phase ends it
asks its :class:`MotionSource` for the next motion (planned and retimed
online; the wall time that took is recorded), and it measures, from the
plant's body poses, how far the held object slips on the cup and where it
lands. All that changes lives in the Context's abstract state.
"""

from __future__ import annotations

import dataclasses

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.math import RigidTransform
from pydrake.multibody.tree import BodyIndex
from pydrake.systems.framework import BasicVector, Context, LeafSystem, State
from pydrake.trajectories import Trajectory

from rt_drake.phase import Phase
from rt_drake.scenario import ObjectConfig
from rt_drake.simulation.motion import Motion, MotionSource, PlanTimes

#: s, period of the sequencer's update (the paper's robot runs at 125 Hz).
UPDATE_PERIOD = 1.0 / 125.0


@dataclasses.dataclass(frozen=True)
class ObjectRecord:
    """What the sequencer measured for one object.

    Attributes:
        name: The object.
        plan_times: Wall seconds spent producing each moving phase's motion.
        exec_s: Simulated seconds each phase lasted.
        max_slip_translation, max_slip_rotation: m and rad, the object's
            largest displacement relative to the cup during MOVE.
        placement_translation, placement_rotation: m and rad, the object's
            distance from its goal pose during DETACH.
        guarantee: What the MOVE's retiming held (``Motion.guarantee``).
    """

    name: str
    plan_times: dict[Phase, PlanTimes] = dataclasses.field(default_factory=dict)
    exec_s: dict[Phase, float] = dataclasses.field(default_factory=dict)
    max_slip_translation: float = 0.0
    max_slip_rotation: float = 0.0
    placement_translation: float = float("nan")
    placement_rotation: float = float("nan")
    guarantee: str = ""


@dataclasses.dataclass
class SequencerState:
    """The sequencer's abstract state (replaced, never mutated, by updates)."""

    phase: Phase
    object_index: int
    t_phase_start: float
    q_hold: np.ndarray
    trajectory: Trajectory | None = None
    reach: Motion | None = None  # the current object's REACH, for its MOVE
    X_CO_attached: RigidTransform | None = None
    records: tuple[ObjectRecord, ...] = ()


class Sequencer(LeafSystem):
    """Runs the pick-and-place cycle of every object in turn.

    .. pydrake_system::

        name: Sequencer
        input_ports:
        - body_poses
        output_ports:
        - desired_state
        - desired_acceleration
        - valve

    ``body_poses`` is the plant's output; ``desired_state`` ([q; v], rad and
    rad/s), ``desired_acceleration`` (rad/s^2) and ``valve`` (1: on) go to
    the station. Phase switches happen in a periodic unrestricted update
    every :data:`UPDATE_PERIOD`.
    """

    def __init__(
        self,
        motions: MotionSource,
        objects: list[ObjectConfig],
        object_bodies: list[BodyIndex],
        tool_body: BodyIndex,
        X_TC: RigidTransform,
        q_home: np.ndarray,
        attach_s: float,
        detach_s: float,
    ) -> None:
        """Make the sequencer.

        Args:
            motions: plans and retimes APPROACH, REACH and MOVE.
            objects: the objects, in picking order.
            object_bodies: each object's body in the plant.
            tool_body: body T carrying the cup.
            X_TC: pose of the cup frame C in T.
            q_home: rad, the arm's configuration at t = 0.
            attach_s: s, wait with the valve on before MOVE.
            detach_s: s, wait with the valve off after MOVE.
        """
        super().__init__()
        self._motions = motions
        self._objects = list(objects)
        self._bodies = list(object_bodies)
        self._tool = tool_body
        self._X_TC = X_TC
        self._waits = {Phase.ATTACH: attach_s, Phase.DETACH: detach_s}
        self._n = len(q_home)
        initial = SequencerState(
            phase=Phase.APPROACH,
            object_index=0,
            t_phase_start=0.0,
            q_hold=np.array(q_home),
        )
        self._state_index = self.DeclareAbstractState(AbstractValue.Make(initial))
        self._poses_port = self.DeclareAbstractInputPort(
            "body_poses", AbstractValue.Make([RigidTransform()])
        )
        self.DeclareVectorOutputPort(
            "desired_state", 2 * self._n, self._CalcDesiredState
        )
        self.DeclareVectorOutputPort(
            "desired_acceleration", self._n, self._CalcDesiredAcceleration
        )
        self.DeclareVectorOutputPort("valve", 1, self._CalcValve)
        self.DeclareInitializationUnrestrictedUpdateEvent(self._Initialize)
        self.DeclarePeriodicUnrestrictedUpdateEvent(UPDATE_PERIOD, 0.0, self._Update)

    # -- reading the state ------------------------------------------------
    def sequencer_state(self, context: Context) -> SequencerState:
        """The current state (phase, records, ...)."""
        return context.get_abstract_state(self._state_index).get_value()

    def is_done(self, context: Context) -> bool:
        """True once every object has been placed."""
        return self.sequencer_state(context).phase is Phase.DONE

    def _reference(self, context: Context, order: int) -> np.ndarray:
        state = self.sequencer_state(context)
        if state.trajectory is None:
            return state.q_hold if order == 0 else np.zeros(self._n)
        traj = state.trajectory
        t = min(max(context.get_time() - state.t_phase_start, 0.0), traj.end_time())
        if order > 0 and context.get_time() - state.t_phase_start > traj.end_time():
            return np.zeros(self._n)
        return (traj.value(t) if order == 0 else traj.EvalDerivative(t, order)).ravel()

    def _CalcDesiredState(self, context: Context, output: BasicVector) -> None:
        output.SetFromVector(
            np.concatenate([self._reference(context, 0), self._reference(context, 1)])
        )

    def _CalcDesiredAcceleration(self, context: Context, output: BasicVector) -> None:
        output.SetFromVector(self._reference(context, 2))

    def _CalcValve(self, context: Context, output: BasicVector) -> None:
        phase = self.sequencer_state(context).phase
        output.SetFromVector([1.0 if phase in (Phase.ATTACH, Phase.MOVE) else 0.0])

    # -- updates ------------------------------------------------------------
    def _Initialize(self, context: Context, state: State) -> None:
        current = self.sequencer_state(context)
        records = tuple(ObjectRecord(name=o.name) for o in self._objects)
        start = dataclasses.replace(
            current, records=records, t_phase_start=context.get_time()
        )
        if not self._objects:
            start = dataclasses.replace(start, phase=Phase.DONE)
        else:
            start = self._begin(start, Phase.APPROACH, context.get_time())
        state.get_mutable_abstract_state(self._state_index).set_value(start)

    def _Update(self, context: Context, state: State) -> None:
        current = self.sequencer_state(context)
        if current.phase is Phase.DONE:
            return
        now = context.get_time()
        current = self._measure(context, current)
        if now - current.t_phase_start < self._phase_duration(current) - 1e-9:
            state.get_mutable_abstract_state(self._state_index).set_value(current)
            return
        record = current.records[current.object_index]
        exec_s = {**record.exec_s, current.phase: now - current.t_phase_start}
        current = _with_record(current, dataclasses.replace(record, exec_s=exec_s))
        if current.phase is Phase.DETACH:
            nxt = current.object_index + 1
            current = dataclasses.replace(
                current, object_index=nxt, X_CO_attached=None, reach=None
            )
            phase = Phase.APPROACH if nxt < len(self._objects) else Phase.DONE
        else:
            order = list(Phase)
            phase = order[order.index(current.phase) + 1]
        if phase is Phase.MOVE:
            current = dataclasses.replace(
                current, X_CO_attached=self._X_CO(context, current.object_index)
            )
        state.get_mutable_abstract_state(self._state_index).set_value(
            self._begin(current, phase, now)
        )

    def _phase_duration(self, state: SequencerState) -> float:
        if state.phase in self._waits:
            return self._waits[state.phase]
        return state.trajectory.end_time() if state.trajectory is not None else 0.0

    def _begin(self, state: SequencerState, phase: Phase, now: float) -> SequencerState:
        """Enter ``phase`` at time ``now``, planning its motion if it moves."""
        q_hold = state.q_hold
        if state.trajectory is not None:
            q_hold = state.trajectory.value(state.trajectory.end_time()).ravel()
        if phase is Phase.DONE or phase in self._waits:
            return dataclasses.replace(
                state, phase=phase, t_phase_start=now, q_hold=q_hold, trajectory=None
            )
        obj = self._objects[state.object_index]
        if phase is Phase.APPROACH:
            motion = self._motions.approach(q_hold, obj)
        elif phase is Phase.REACH:
            motion = self._motions.reach(q_hold, obj)
        else:
            motion = self._motions.move(q_hold, obj, state.reach)
        record = state.records[state.object_index]
        plan_times = {**record.plan_times, phase: motion.times}
        guarantee = motion.guarantee if phase is Phase.MOVE else record.guarantee
        state = _with_record(
            state,
            dataclasses.replace(record, plan_times=plan_times, guarantee=guarantee),
        )
        return dataclasses.replace(
            state,
            phase=phase,
            t_phase_start=now,
            q_hold=q_hold,
            trajectory=motion.trajectory,
            reach=motion if phase is Phase.REACH else state.reach,
        )

    # -- measurements -------------------------------------------------------
    def _X_CO(self, context: Context, index: int) -> RigidTransform:
        poses = self._poses_port.Eval(context)
        X_WC = poses[int(self._tool)] @ self._X_TC
        return X_WC.inverse() @ poses[int(self._bodies[index])]

    def _measure(self, context: Context, state: SequencerState) -> SequencerState:
        """Track slip during MOVE and the placement error during DETACH."""
        if state.phase is Phase.MOVE and state.X_CO_attached is not None:
            record = state.records[state.object_index]
            X_CO = self._X_CO(context, state.object_index)
            translation, rotation = pose_difference(state.X_CO_attached, X_CO)
            if (
                translation > record.max_slip_translation
                or rotation > record.max_slip_rotation
            ):
                record = dataclasses.replace(
                    record,
                    max_slip_translation=max(record.max_slip_translation, translation),
                    max_slip_rotation=max(record.max_slip_rotation, rotation),
                )
                state = _with_record(state, record)
        if state.phase is Phase.DETACH:
            poses = self._poses_port.Eval(context)
            X_WO = poses[int(self._bodies[state.object_index])]
            goal = self._objects[state.object_index].goal.GetDeterministicValue()
            translation, rotation = pose_difference(goal, X_WO)
            record = dataclasses.replace(
                state.records[state.object_index],
                placement_translation=translation,
                placement_rotation=rotation,
            )
            state = _with_record(state, record)
        return state


def _with_record(state: SequencerState, record: ObjectRecord) -> SequencerState:
    """Return ``state`` with the current object's record replaced."""
    records = list(state.records)
    records[state.object_index] = record
    return dataclasses.replace(state, records=tuple(records))


def pose_difference(X_A: RigidTransform, X_B: RigidTransform) -> tuple[float, float]:
    """Return (m, rad): distance between the origins and the angle of R_A^T R_B."""
    translation = float(np.linalg.norm(X_B.translation() - X_A.translation()))
    R = X_A.rotation().inverse() @ X_B.rotation()
    rotation = float(abs(R.ToAngleAxis().angle()))
    return translation, rotation


__all__ = [
    "ObjectRecord",
    "Sequencer",
    "SequencerState",
    "UPDATE_PERIOD",
    "pose_difference",
]
