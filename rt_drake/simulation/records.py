"""What the sequencer measures per object, and the pose arithmetic it uses."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
from pydrake.math import RigidTransform

from rt_drake.simulation.motion import PlanTimes
from rt_drake.types.phase import Phase


@dataclasses.dataclass(frozen=True)
class ObjectRecord:
    """What the sequencer measured for one object.

    Attributes:
        name: The object.
        plan_times: Wall seconds spent producing each moving phase's motion.
        plan_wait_s: Simulated seconds a phase waited for its motion's plan
            (the plan on the critical path; :mod:`.motion` defines the clock).
        exec_s: Simulated seconds each phase lasted (APPROACH and MOVE from
            the start of their motion, after any wait).
        max_slip_translation, max_slip_rotation: m and rad, the object's
            largest displacement during MOVE relative to what touches it:
            the bellows cup's lip L, else the tool's cup frame C (the slip).
        max_on_tool_translation, max_on_tool_rotation: m and rad, the
            object's largest displacement during MOVE relative to the tool's
            cup frame C: the slip plus the bellows' elastic deflection (the
            slip itself under the rim cup, whose lip is the tool).
        placement_translation, placement_rotation: m and rad, the object's
            distance from its goal pose during DETACH.
        move_suction_force: N, the vacuum's force when the MOVE started.
        guarantee: What the MOVE's retiming held (``Motion.guarantee``).
        grasp_price_s: s, what the grasp cost the MOVE's path
            (``Motion.grasp_price_s``; NaN: not computed).
    """

    name: str
    plan_times: dict[Phase, PlanTimes] = dataclasses.field(default_factory=dict)
    plan_wait_s: dict[Phase, float] = dataclasses.field(default_factory=dict)
    exec_s: dict[Phase, float] = dataclasses.field(default_factory=dict)
    max_slip_translation: float = 0.0
    max_slip_rotation: float = 0.0
    max_on_tool_translation: float = 0.0
    max_on_tool_rotation: float = 0.0
    placement_translation: float = float("nan")
    placement_rotation: float = float("nan")
    move_suction_force: float = float("nan")
    guarantee: str = ""
    grasp_price_s: float = float("nan")

    @property
    def plan_on_critical_path_s(self) -> float:
        """Simulated seconds the object's phases waited for planning."""
        return math.fsum(self.plan_wait_s.values())


def pose_difference(X_A: RigidTransform, X_B: RigidTransform) -> tuple[float, float]:
    """Return (m, rad): distance between the origins and the angle of R_A^T R_B."""
    translation = float(np.linalg.norm(X_B.translation() - X_A.translation()))
    R = X_A.rotation().inverse() @ X_B.rotation()
    rotation = float(abs(R.ToAngleAxis().angle()))
    return translation, rotation


def with_slip(
    record: ObjectRecord,
    X_LO_attached: RigidTransform,
    X_LO: RigidTransform,
    X_CO_attached: RigidTransform,
    X_CO: RigidTransform,
) -> ObjectRecord:
    """``record`` with its largest slip and motion on the tool (m, rad) updated.

    The slip is the object's pose X_LO on the lip L (what touches it)
    against X_LO when the MOVE started; the motion on the tool, its pose
    X_CO in the tool's cup frame C against X_CO then. Each is
    :func:`pose_difference`'s pair.
    """
    translation, rotation = pose_difference(X_LO_attached, X_LO)
    on_tool, on_tool_rotation = pose_difference(X_CO_attached, X_CO)
    return dataclasses.replace(
        record,
        max_slip_translation=max(record.max_slip_translation, translation),
        max_slip_rotation=max(record.max_slip_rotation, rotation),
        max_on_tool_translation=max(record.max_on_tool_translation, on_tool),
        max_on_tool_rotation=max(record.max_on_tool_rotation, on_tool_rotation),
    )


def with_placement(
    record: ObjectRecord, X_WO_goal: RigidTransform, X_WO: RigidTransform
) -> ObjectRecord:
    """``record`` with its placement error: X_WO against the goal (m, rad)."""
    translation, rotation = pose_difference(X_WO_goal, X_WO)
    return dataclasses.replace(
        record, placement_translation=translation, placement_rotation=rotation
    )


__all__ = ["ObjectRecord", "pose_difference", "with_placement", "with_slip"]
