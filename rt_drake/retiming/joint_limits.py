"""Joint limits of the retimer: velocity, acceleration, torque and jerk.

``|v_j| <= velocity_j`` (rad/s), ``|vdot_j| <= acceleration_j`` (rad/s^2),
``|tau_j| <= torque_j`` (N m) and ``|vddot_j| <= jerk_j`` (rad/s^3), one
entry per joint j, symmetric; built by hand or from a plant's model and a
scenario's ``robot`` overrides (:meth:`JointLimits.from_plant`).
"""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Sequence

import numpy as np
from pydrake.multibody.plant import MultibodyPlant

from rt_drake import arguments
from rt_drake.model.scenario import RobotConfig
from rt_drake.retiming._retime_errors import RetimeInputError


@dataclasses.dataclass(frozen=True, eq=False)
class JointLimits:
    """Symmetric joint limits, one entry per joint.

    ``|v| <= velocity`` (rad/s), ``|vdot| <= acceleration`` (rad/s^2),
    ``|tau| <= torque`` (N m) and ``|vddot| <= jerk`` (rad/s^3); ``torque``
    None leaves torques unconstrained, ``jerk`` None leaves the jerk free
    (the acceleration may then jump, as TOPP-RA's bang-bang profile does).
    """

    velocity: np.ndarray
    acceleration: np.ndarray
    torque: np.ndarray | None = None
    jerk: np.ndarray | None = None

    def __post_init__(self) -> None:
        for name in ("velocity", "acceleration", "torque", "jerk"):
            value = getattr(self, name)
            if value is None and name in ("torque", "jerk"):
                continue
            value = np.array(
                arguments.array(
                    value,
                    name,
                    ("joints",),
                    where="JointLimits",
                    error=RetimeInputError,
                )
            )
            if not np.all(value > 0):
                raise RetimeInputError(
                    f"JointLimits: {name} limits must be > 0, got {value.tolist()}"
                )
            value.setflags(write=False)
            object.__setattr__(self, name, value)
        sizes = {
            v.size
            for v in (self.velocity, self.acceleration, self.torque, self.jerk)
            if v is not None
        }
        if len(sizes) != 1:
            torque = None if self.torque is None else self.torque.size
            jerk = None if self.jerk is None else self.jerk.size
            raise RetimeInputError(
                f"limits differ in length: {self.velocity.size=}, "
                f"{self.acceleration.size=}, torque {torque}, jerk {jerk}"
            )

    def without_jerk(self) -> JointLimits:
        """The same limits with the jerk left free (``jerk`` None)."""
        return dataclasses.replace(self, jerk=None)

    def with_acceleration_ramp(self, ramp_s: float) -> JointLimits:
        """These limits with each joint's jerk at most ``acceleration / ramp_s``.

        ``jerk_j = min(jerk_j, acceleration_j / ramp_s)`` (rad/s^3; ``jerk``
        None counts as unlimited): going from rest to its acceleration limit
        takes joint j at least ``ramp_s`` seconds. The planner's
        ``planning.grasp_ramp_s`` (a margin for a compliant cup's modes).

        Raises:
            RetimeInputError: ``ramp_s`` not a finite number > 0.
        """
        ramp_s = arguments.number(
            ramp_s,
            "ramp_s",
            where="JointLimits.with_acceleration_ramp",
            above=0.0,
            error=RetimeInputError,
        )
        ramped = self.acceleration / ramp_s
        jerk = ramped if self.jerk is None else np.minimum(self.jerk, ramped)
        return dataclasses.replace(self, jerk=jerk)

    @property
    def num_joints(self) -> int:
        """N."""
        return int(self.velocity.size)

    @classmethod
    def from_plant(
        cls,
        plant: MultibodyPlant,
        robot: RobotConfig | None = None,
        torque: bool = False,
        jerk: bool = False,
    ) -> JointLimits:
        """Limits from the plant's model, overridden by the scenario's.

        The model's upper limits (URDF velocity, ``drake:acceleration``,
        effort of the joints' actuators) are replaced by ``robot.*_limits``
        where those are not empty. A URDF has no jerk limit: the jerk is
        limited only by a non-empty ``robot.jerk_limits`` (rad/s^3), and
        only when asked (``jerk=True``, as the command line does unless
        ``--no-jerk-limits``), so that every acceleration-limited caller
        keeps today's trajectories. A model without some of them (no
        ``drake:acceleration``, no transmissions) needs them by hand:
        ``JointLimits(velocity, acceleration)`` (rad/s, rad/s^2, one per
        joint), or the scenario's ``robot.acceleration_limits`` etc.

        Args:
            plant: Finalized plant holding only the path's joints.
            robot: Scenario robot section with optional overrides.
            torque: Whether to include the torque (effort) limits; they are
                also included when ``robot.limit_torques`` is set.
            jerk: Whether to include the scenario's ``robot.jerk_limits``.

        Raises:
            RetimeInputError: a limit the model lacks and nobody gave,
                naming the joint and how to give it.
        """
        where = "JointLimits.from_plant"
        check = functools.partial(
            arguments.instance, where=where, error=RetimeInputError
        )
        check(plant, "plant", MultibodyPlant)
        if robot is not None:
            check(robot, "robot", RobotConfig)
        n = plant.num_velocities()
        model = {
            "velocity": plant.GetVelocityUpperLimits(),
            "acceleration": plant.GetAccelerationUpperLimits(),
            "torque": _effort_limits(plant),
        }
        given: dict[str, Sequence[float]] = {
            "velocity": [],
            "acceleration": [],
            "torque": [],
        }
        if robot is not None:
            given = {
                "velocity": robot.velocity_limits,
                "acceleration": robot.acceleration_limits,
                "torque": robot.torque_limits,
            }
            torque = torque or robot.limit_torques
        chosen = {}
        for name in ("velocity", "acceleration", "torque"):
            if name == "torque" and not torque:
                continue
            value = np.asarray(given[name] if len(given[name]) else model[name])
            if len(given[name]) and value.size != n:
                raise RetimeInputError(
                    f"key 'robot.{name}_limits': {value.size} values but the plant "
                    f"has {n} joints"
                )
            missing = np.flatnonzero(~np.isfinite(value))
            if missing.size:
                j = int(missing[0])
                by_hand = "velocity, acceleration" + ", torque" * (name == "torque")
                raise RetimeInputError(
                    f"the model has no {name} limit for joint {j + 1} "
                    f"({_joint_name(plant, j)}): give the limits by hand, "
                    f"JointLimits({by_hand}), or the scenario's robot.{name}_limits"
                )
            chosen[name] = value
        jerk_limits = None
        if jerk and robot is not None and len(robot.jerk_limits):
            jerk_limits = np.asarray(robot.jerk_limits, dtype=float)
            if jerk_limits.size != n:
                raise RetimeInputError(
                    f"key 'robot.jerk_limits': {jerk_limits.size} values but the "
                    f"plant has {n} joints"
                )
        return cls(
            chosen["velocity"],
            chosen["acceleration"],
            chosen.get("torque"),
            jerk_limits,
        )


def _effort_limits(plant: MultibodyPlant) -> np.ndarray:
    """Per velocity: the effort limit of the joint's actuator (inf if none)."""
    limits = np.full(plant.num_velocities(), np.inf)
    for index in plant.GetJointActuatorIndices():
        actuator = plant.get_joint_actuator(index)
        joint = actuator.joint()
        for k in range(joint.num_velocities()):
            limits[joint.velocity_start() + k] = actuator.effort_limit()
    return limits


def _joint_name(plant: MultibodyPlant, velocity_index: int) -> str:
    for index in plant.GetJointIndices():
        joint = plant.get_joint(index)
        start = joint.velocity_start()
        if start <= velocity_index < start + joint.num_velocities():
            return joint.name()
    return f"velocity {velocity_index}"


__all__ = ["JointLimits"]
