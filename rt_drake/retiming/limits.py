"""What the retimer constrains: joint limits and the grasp of a held object."""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import numpy as np
from pydrake.multibody.plant import MultibodyPlant

from rt_drake.contact import CupParameters, cached_wrench_polytope
from rt_drake.contact.wrench_polytope import check_h_representation
from rt_drake.dynamics import HeldObject
from rt_drake.errors import InputError
from rt_drake.retiming.errors import RetimeInputError
from rt_drake.scenario import RobotConfig


@dataclasses.dataclass(frozen=True, eq=False)
class JointLimits:
    """Symmetric joint limits, one entry per joint.

    ``|v| <= velocity`` (rad/s), ``|vdot| <= acceleration`` (rad/s^2) and
    ``|tau| <= torque`` (N m); ``torque`` None leaves torques unconstrained.
    """

    velocity: np.ndarray
    acceleration: np.ndarray
    torque: np.ndarray | None = None

    def __post_init__(self) -> None:
        for name in ("velocity", "acceleration", "torque"):
            value = getattr(self, name)
            if value is None:
                continue
            value = np.array(value, dtype=float).reshape(-1)
            if not (np.all(np.isfinite(value)) and np.all(value > 0)):
                raise RetimeInputError(f"{name} limits must be finite and > 0: {value}")
            value.setflags(write=False)
            object.__setattr__(self, name, value)
        sizes = {
            v.size
            for v in (self.velocity, self.acceleration, self.torque)
            if v is not None
        }
        if len(sizes) != 1:
            torque = None if self.torque is None else self.torque.size
            raise RetimeInputError(
                f"limits differ in length: {self.velocity.size=}, "
                f"{self.acceleration.size=}, torque {torque}"
            )

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
    ) -> JointLimits:
        """Limits from the plant's model, overridden by the scenario's.

        The model's upper limits (URDF velocity, ``drake:acceleration``,
        effort of the joints' actuators) are replaced by ``robot.*_limits``
        where those are not empty. A model without some of them (no
        ``drake:acceleration``, no transmissions) needs them by hand:
        ``JointLimits(velocity, acceleration)`` (rad/s, rad/s^2, one per
        joint), or the scenario's ``robot.acceleration_limits`` etc.

        Args:
            plant: Finalized plant holding only the path's joints.
            robot: Scenario robot section with optional overrides.
            torque: Whether to include the torque (effort) limits; they are
                also included when ``robot.limit_torques`` is set.

        Raises:
            RetimeInputError: a limit the model lacks and nobody gave,
                naming the joint and how to give it.
        """
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
        return cls(chosen["velocity"], chosen["acceleration"], chosen.get("torque"))


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


@dataclasses.dataclass(frozen=True, eq=False)
class GraspConstraint:
    """Grasp stability ``F w <= g`` of a held object (paper eq. 20).

    ``w = [torque; force]`` (N m, N) is the wrench the cup exerts on the
    object about the cup origin Co, in the cup frame C (:mod:`rt_drake.contact`
    conventions). ``g > 0`` row-wise: the zero wrench is strictly inside.

    Attributes:
        held: Inertia of the object in C.
        F: (R, 6) rows (unit norm from :mod:`rt_drake.contact`).
        g: (R,) offsets.
        cup: The cup the polytope belongs to (for messages), if known.
    """

    held: HeldObject
    F: np.ndarray
    g: np.ndarray
    cup: CupParameters | None = None

    def __post_init__(self) -> None:
        F = np.array(self.F, dtype=float)
        g = np.array(self.g, dtype=float).reshape(-1)
        try:  # shapes, NaN or inf, an all-zero row (it would constrain nothing)
            check_h_representation(F, g)
        except InputError as error:
            raise RetimeInputError(f"grasp constraint: {error}") from None
        if np.any(g <= 0.0):
            raise RetimeInputError(
                f"grasp constraint needs g > 0 (zero wrench inside), min g = {g.min()}"
            )
        F.setflags(write=False)
        g.setflags(write=False)
        object.__setattr__(self, "F", F)
        object.__setattr__(self, "g", g)

    @classmethod
    def for_cup(cls, held: HeldObject, cup: CupParameters) -> GraspConstraint:
        """The exact polytope of ``cup`` (cached on disk by rt_drake.contact)."""
        polytope = cached_wrench_polytope(cup)
        return cls(held=held, F=polytope.F, g=polytope.g, cup=cup)

    def describe(self) -> str:
        """E.g. ``object 0.551 kg, suction 20 N``."""
        text = f"object {self.held.mass:.3g} kg"
        if self.cup is not None:
            text += f", suction {self.cup.suction_force:.3g} N"
        return text


__all__ = ["GraspConstraint", "JointLimits"]
