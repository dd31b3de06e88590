"""The pick-and-place sequencer: APPROACH, REACH, ATTACH, MOVE, DETACH per object.

The sequencer commands the arm and the suction valve. Per object it plays
two motions from its :class:`~.motion.MotionSource`: the pick (APPROACH then
REACH, one motion without a stop at the approach pose) and the MOVE.

Planning ahead (``pipelined``, the default): the next object's pick is
requested when the MOVE starts, so it is planned during the MOVE and the
DETACH wait, and that object's MOVE right after it (its grasp
configuration is the pick's end), as soon as the planner is free: during
the same MOVE and DETACH, then the pick and the ATTACH wait. The first
object's MOVE is requested when its pick starts moving.
The first object's pick has nothing before it to hide behind: it is
requested at t = 0 and the arm waits for its planning and retiming (only
the planner's construction, which loads the cell and the objects at their
start poses into its collision scene, comes before the clock); when that
pick is staged (:attr:`~.motion.Motion.staged`: a straight APPROACH, then
the REACH), the arm starts on the APPROACH and the REACH is planned behind
it (:attr:`~.motion.PendingMotion.start_at`). Sequential
(``pipelined=False``): each motion is requested when its phase starts, and
the arm waits for all of it, staged or not. Either way a phase waits only
for the part of its planning that did not fit in the time before it
(:class:`~.motion.PendingMotion` defines how wall time is charged against
simulated time), and the calls to the motion source, with their arguments,
are the same.

ATTACH and DETACH follow the scenario's vacuum (:mod:`rt_drake.model.vacuum`): fixed
waits, or "part present" and "released" (force below the object's weight,
object at rest) with the waits as time-outs. With the ``first_order``
vacuum the valve opens during the last stretch of the descent, the time the
vacuum needs to reach "part present" (``time_to_part_present``) before
REACH ends: the level builds only once the cup seals (its face within the
seal distance), so the seal forms at contact and the build-up overlaps the
motion's end; the MOVE still starts at "part present", retimed for the
force certain then. Likewise the valve closes ``release_s`` before the MOVE
arrives (:attr:`~.motion.Motion.release_s`: the lead over which the grasp
holds with the force certain as the vacuum decays), so the release overlaps
the set-down; DETACH still ends at "released".

It measures, from the plant's body poses, how far the held object slips on
what touches it (each of the bellows cups' lips, the largest slip of them,
else the tool's cup frame), how far
it moves on the tool's cup frame (the slip plus the bellows' deflection) and
where it lands. All that changes lives in the Context's abstract
state.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.math import RigidTransform
from pydrake.multibody.math import SpatialVelocity
from pydrake.multibody.tree import BodyIndex
from pydrake.systems.framework import BasicVector, Context, LeafSystem, State
from pydrake.trajectories import Trajectory

from rt_drake.model.scenario import ObjectConfig
from rt_drake.model.vacuum import (
    Vacuum,
    VacuumModel,
    is_released,
    time_to_part_present,
    wait_over,
)
from rt_drake.retiming import PathTrajectory
from rt_drake.simulation._command import sampled_command
from rt_drake.simulation.motion import Motion, MotionSource, PendingMotion
from rt_drake.simulation.records import (
    ObjectRecord,
    pose_difference,
    with_placement,
    with_slip,
)
from rt_drake.types.phase import Phase

#: s, period of the sequencer's update (the paper's robot runs at 125 Hz).
UPDATE_PERIOD = 1.0 / 125.0


@dataclasses.dataclass
class SequencerState:
    """The sequencer's abstract state (replaced, never mutated, by updates).

    ``motion`` is played with its t = 0 at simulated ``t_motion_start``;
    ``pending`` is the next motion, planned ahead, and ``pending_move`` the
    MOVE after it when ``pending`` is a pick planned ahead; ``pick`` the
    current object's pick (its MOVE lifts along it).
    """

    phase: Phase
    object_index: int
    t_phase_start: float
    q_hold: np.ndarray
    motion: Motion | None = None
    t_motion_start: float = 0.0
    pending: PendingMotion | None = None
    pending_move: PendingMotion | None = None
    pick: Motion | None = None
    X_CO_attached: RigidTransform | None = None
    X_LO_attached: tuple[RigidTransform, ...] | None = None
    records: tuple[ObjectRecord, ...] = ()

    def __deepcopy__(self, memo: dict) -> SequencerState:
        """The state itself: updates replace it, never mutate it.

        Drake copies the abstract state at every update (125 Hz); a deep copy
        of the motions' trajectories took about a tenth of a rollout's CPU.
        """
        return self


class Sequencer(LeafSystem):
    """Runs the pick-and-place cycle of every object in turn.

    .. pydrake_system::

        name: Sequencer
        input_ports:
        - body_poses
        - body_spatial_velocities
        - suction_force
        - part_present
        output_ports:
        - desired_state
        - desired_acceleration
        - valve

    The inputs are the station's outputs of those names; ``desired_state``
    ([q; v], rad and rad/s), ``desired_acceleration`` (rad/s^2) and ``valve``
    (1: on) go to the station and depend on the state and time only. Phase
    switches happen in a periodic unrestricted update every
    :data:`UPDATE_PERIOD`.
    """

    def __init__(
        self,
        motions: MotionSource,
        objects: list[ObjectConfig],
        object_bodies: list[BodyIndex],
        object_weights: list[float],
        tool_body: BodyIndex,
        X_TC: RigidTransform,
        q_home: np.ndarray,
        vacuum: Vacuum,
        pipelined: bool = True,
        command_period: float | None = None,
        lip_bodies: Sequence[BodyIndex] = (),
        held_at_start: bool = False,
    ) -> None:
        """Make the sequencer.

        Args:
            motions: plans and retimes the pick and the MOVE of each object.
            objects: the objects, in picking order.
            object_bodies: each object's body in the plant.
            object_weights: N, each object's weight.
            tool_body: body T carrying the cup.
            X_TC: pose of the cup frame C in T.
            q_home: rad, the arm's configuration at t = 0.
            vacuum: the waits (fixed) or the signals and time-outs.
            pipelined: plan each motion ahead (else when its phase starts).
            command_period: s, send the motion sampled at this period and
                interpolated between samples (:mod:`._command`); None:
                continuous.
            lip_bodies: the bellows cups' lips L_i, one per cup, each frame
                its cup's frame at rest: the slip is the largest on any of
                them; none: on C (the rim cup).
            held_at_start: the first object starts sealed on the cup (a
                rollout's object already picked): the valve is on from t = 0,
                through its APPROACH and REACH too.
        """
        super().__init__()
        self._motions = motions
        self._objects = list(objects)
        self._bodies = list(object_bodies)
        self._weights = list(object_weights)
        self._tool = tool_body
        self._X_TC = X_TC
        self._lips = tuple(lip_bodies)
        self._vacuum = vacuum
        self._pipelined = pipelined
        self._command_period = command_period
        self._held_at_start = bool(held_at_start)
        self._n = len(q_home)
        self._last_reference: (
            tuple[Trajectory, float, tuple[np.ndarray, ...]] | None
        ) = None
        initial = SequencerState(Phase.APPROACH, 0, 0.0, np.array(q_home))
        self._state_index = self.DeclareAbstractState(AbstractValue.Make(initial))
        self._poses_port = self.DeclareAbstractInputPort(
            "body_poses", AbstractValue.Make([RigidTransform()])
        )
        self._velocities_port = self.DeclareAbstractInputPort(
            "body_spatial_velocities", AbstractValue.Make([SpatialVelocity()])
        )
        self._force_port = self.DeclareVectorInputPort("suction_force", 1)
        self._present_port = self.DeclareVectorInputPort("part_present", 1)
        state_only = {self.time_ticket(), self.abstract_state_ticket(self._state_index)}
        self.DeclareVectorOutputPort(
            "desired_state", 2 * self._n, self._CalcDesiredState, state_only
        )
        self.DeclareVectorOutputPort(
            "desired_acceleration", self._n, self._CalcDesiredAcceleration, state_only
        )
        self.DeclareVectorOutputPort("valve", 1, self._CalcValve, state_only)
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
        """The commanded q (order 0), v (1) or a (2) now; rad, rad/s, rad/s^2."""
        state = self.sequencer_state(context)
        if state.motion is None:
            return state.q_hold if order == 0 else np.zeros(self._n)
        traj = state.motion.trajectory
        t = context.get_time() - state.t_motion_start
        last = self._last_reference
        if last is None or last[0] is not traj or last[1] != t:
            last = (traj, t, self._references(traj, t))
            self._last_reference = last
        return last[2][order]

    def _references(
        self, traj: Trajectory, t: float
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(q, v, a) of ``traj`` at motion time ``t`` (s), held at its ends.

        The three outputs ask at the same instant: one evaluation serves
        them (a pure function of the trajectory and t, so kept on the
        system, whatever the context).
        """
        if self._command_period is not None:
            return sampled_command(traj, t, self._command_period)
        end = traj.end_time()
        inside = 0.0 <= t <= end
        t = min(max(t, 0.0), end)
        if isinstance(traj, PathTrajectory):  # q, q', q'' in one pass
            q, v, a = (x.ravel() for x in traj.sample(t, order=2))
        else:
            q = traj.value(t).ravel()
            v, a = (traj.EvalDerivative(t, k).ravel() for k in (1, 2))
        if not inside:
            v, a = np.zeros(self._n), np.zeros(self._n)
        return q, v, a

    def _CalcDesiredState(self, context: Context, output: BasicVector) -> None:
        output.SetFromVector(
            np.concatenate([self._reference(context, 0), self._reference(context, 1)])
        )

    def _CalcDesiredAcceleration(self, context: Context, output: BasicVector) -> None:
        output.SetFromVector(self._reference(context, 2))

    def _CalcValve(self, context: Context, output: BasicVector) -> None:
        state = self.sequencer_state(context)
        held = self._held_at_start and state.object_index == 0
        on = (
            state.phase is Phase.ATTACH
            or (held and state.phase in (Phase.APPROACH, Phase.REACH))
            or (state.phase is Phase.MOVE and not self._closes_early(context, state))
            or self._opens_early(context, state)
        )
        output.SetFromVector([1.0 if on else 0.0])

    def _closes_early(self, context: Context, state: SequencerState) -> bool:
        """MOVE: off for its last ``release_s`` s (0 unless first_order)."""
        motion = state.motion
        if motion is None or motion.release_s <= 0.0:
            return False
        t = context.get_time() - state.t_motion_start
        return t >= motion.duration - motion.release_s

    def _opens_early(self, context: Context, state: SequencerState) -> bool:
        """first_order: on for the last ``time_to_part_present`` s of REACH."""
        if (
            self._vacuum.kind is not VacuumModel.FIRST_ORDER
            or state.phase is not Phase.REACH
            or state.motion is None
        ):
            return False
        t = context.get_time() - state.t_motion_start
        lead = time_to_part_present(self._vacuum)
        return t >= state.motion.phase_end(Phase.REACH) - lead

    # -- updates ------------------------------------------------------------
    def _Initialize(self, context: Context, state: State) -> None:
        now = context.get_time()
        current = dataclasses.replace(
            self.sequencer_state(context),
            records=tuple(ObjectRecord(name=o.name) for o in self._objects),
            t_phase_start=now,
        )
        if not self._objects:
            current = dataclasses.replace(current, phase=Phase.DONE)
        else:
            current = self._enter(current, Phase.APPROACH, context)
        state.get_mutable_abstract_state(self._state_index).set_value(current)

    def _Update(self, context: Context, state: State) -> None:
        current = self.sequencer_state(context)
        if current.phase is Phase.DONE:
            return
        current = self._measure(context, current)
        if self._phase_over(context, current):
            now = context.get_time()
            start = current.t_phase_start
            if current.phase in (Phase.APPROACH, Phase.MOVE):
                start = current.t_motion_start  # its plan wait is apart
            current = self._record(current, exec_s={current.phase: now - start})
            order = list(Phase)
            phase = order[order.index(current.phase) + 1]
            if phase is Phase.DONE:  # after DETACH: the next object, if any
                nxt = current.object_index + 1
                current = dataclasses.replace(current, object_index=nxt, pick=None)
                phase = Phase.APPROACH if nxt < len(self._objects) else Phase.DONE
            current = self._enter(current, phase, context)
        state.get_mutable_abstract_state(self._state_index).set_value(current)

    def _phase_over(self, context: Context, state: SequencerState) -> bool:
        now = context.get_time()
        waited = now - state.t_phase_start
        if state.phase in (Phase.ATTACH, Phase.DETACH):
            signal = self._vacuum.kind is VacuumModel.FIRST_ORDER and (
                self._part_present(context)
                if state.phase is Phase.ATTACH
                else self._released(context, state.object_index)
            )
            name = self._objects[state.object_index].name
            return wait_over(self._vacuum, state.phase, waited, signal, name)
        assert state.motion is not None
        end = state.motion.phase_end(state.phase)
        return now - state.t_motion_start >= end - 1e-9

    def _part_present(self, context: Context) -> bool:
        return bool(self._present_port.Eval(context)[0] > 0.5)

    def _released(self, context: Context, index: int) -> bool:
        velocity = self._velocities_port.Eval(context)[int(self._bodies[index])]
        return is_released(
            float(self._force_port.Eval(context)[0]),
            self._weights[index],
            float(np.linalg.norm(velocity.translational())),
            float(np.linalg.norm(velocity.rotational())),
        )

    def _enter(
        self, state: SequencerState, phase: Phase, context: Context
    ) -> SequencerState:
        """Enter ``phase`` now, starting its motion once it is planned."""
        now = context.get_time()
        q_hold = state.q_hold
        if state.motion is not None:
            q_hold = state.motion.q_end
        state = dataclasses.replace(state, phase=phase, t_phase_start=now)
        if phase is Phase.REACH:  # the pick goes on
            return state
        if phase not in (Phase.APPROACH, Phase.MOVE):
            return dataclasses.replace(state, q_hold=q_hold, motion=None)
        index = state.object_index
        pending = state.pending
        if pending is None:  # sequential, or the first object: plan it now
            pending = self._request(state, phase, q_hold, now)
        motion = pending.motion
        wait = pending.wait_s(now)
        if not self._pipelined:  # the paper's order: all of it, then the motion
            wait = max(0.0, pending.ready_at - now)
        parts = (Phase.APPROACH, Phase.REACH) if phase is Phase.APPROACH else (phase,)
        state = self._record(
            state,
            plan_times={p: motion.plan_times(p) for p in parts},
            plan_wait_s={phase: wait},
        )
        state = dataclasses.replace(
            state,
            q_hold=q_hold,
            motion=motion,
            t_motion_start=now + wait,
            pending=None,
            pick=motion if phase is Phase.APPROACH else state.pick,
        )
        if phase is Phase.MOVE:
            record = state.records[index]
            force = float(self._force_port.Eval(context)[0])
            state = _with_record(
                dataclasses.replace(
                    state,
                    X_CO_attached=self._X_CO(context, index),
                    X_LO_attached=self._X_LO(context, index),
                ),
                dataclasses.replace(
                    record,
                    move_suction_force=force,
                    guarantee=motion.guarantee,
                    grasp_price_s=motion.grasp_price_s,
                ),
            )
        if self._pipelined:  # plan the next motion while this one runs
            # once the planner is free: a staged motion's later parts are
            # still being planned when it starts
            free = max(now + wait, pending.ready_at)
            if phase is Phase.APPROACH:  # its MOVE, unless planned with it
                request = state.pending_move or self._request(
                    state, Phase.MOVE, motion.q_end, free
                )
                state = dataclasses.replace(state, pending=request, pending_move=None)
            elif index + 1 < len(self._objects):  # the next pick, then its MOVE
                request = self._request(state, Phase.APPROACH, motion.q_end, free)
                after = self._motions.move(
                    request.motion.q_end, self._objects[index + 1], request.motion
                )
                state = dataclasses.replace(
                    state,
                    pending=request,
                    pending_move=PendingMotion(after, request.ready_at),
                )
        return state

    def _request(
        self, state: SequencerState, phase: Phase, q_start: np.ndarray, now: float
    ) -> PendingMotion:
        """Plan ``phase`` (APPROACH: the pick of the object it is for) from q_start.

        A pick requested during a MOVE is for the next object.
        """
        index = state.object_index
        if phase is Phase.MOVE:
            obj = self._objects[index]
            return PendingMotion(self._motions.move(q_start, obj, state.pick), now)
        if state.phase is Phase.MOVE:  # planning ahead, during this MOVE
            index += 1
        motion = self._motions.pick(q_start, self._objects[index], retreat=index > 0)
        return PendingMotion(motion, now)

    def _record(self, state: SequencerState, **fields: dict) -> SequencerState:
        """Merge ``fields`` (dicts keyed by phase) into the current record."""
        record = state.records[state.object_index]
        merged: dict = {k: {**getattr(record, k), **v} for k, v in fields.items()}
        return _with_record(state, dataclasses.replace(record, **merged))

    # -- measurements -------------------------------------------------------
    def _X_CO(self, context: Context, index: int) -> RigidTransform:
        """Pose of object ``index`` in the tool's cup frame C."""
        poses = self._poses_port.Eval(context)
        X_WC = poses[int(self._tool)] @ self._X_TC
        return X_WC.inverse() @ poses[int(self._bodies[index])]

    def _X_LO(self, context: Context, index: int) -> tuple[RigidTransform, ...]:
        """Poses X_LiO of object ``index`` on each lip L_i (C without lips)."""
        if not self._lips:
            return (self._X_CO(context, index),)
        poses = self._poses_port.Eval(context)
        X_WO = poses[int(self._bodies[index])]
        return tuple(poses[int(lip)].inverse() @ X_WO for lip in self._lips)

    def _measure(self, context: Context, state: SequencerState) -> SequencerState:
        """Track slip during MOVE and the placement error during DETACH."""
        index = state.object_index
        record = state.records[index]
        X_LO_attached, X_CO_attached = state.X_LO_attached, state.X_CO_attached
        if (
            state.phase is Phase.MOVE
            and X_LO_attached is not None
            and X_CO_attached is not None
        ):
            X_CO = self._X_CO(context, index)
            # The slip is the largest on any lip: the object held still by
            # every lip has not slipped, however far the bellows deflect.
            for X_LO_then, X_LO in zip(
                X_LO_attached, self._X_LO(context, index), strict=True
            ):
                record = with_slip(record, X_LO_then, X_LO, X_CO_attached, X_CO)
        elif state.phase is Phase.DETACH:
            X_WO = self._poses_port.Eval(context)[int(self._bodies[index])]
            goal = self._objects[index].goal.GetDeterministicValue()
            record = with_placement(record, goal, X_WO)
        return _with_record(state, record)


def _with_record(state: SequencerState, record: ObjectRecord) -> SequencerState:
    """Return ``state`` with the current object's record replaced."""
    records = list(state.records)
    records[state.object_index] = record
    return dataclasses.replace(state, records=tuple(records))


__all__ = [
    "ObjectRecord",
    "Sequencer",
    "SequencerState",
    "UPDATE_PERIOD",
    "pose_difference",
]
