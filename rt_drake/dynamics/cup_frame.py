"""The cup frame C of a plant, named once and looked up once.

C is the frame of the suction cup (or of a multi-cup tool): origin Co at the
centre of the contact face, +z out of the cup into the object. The dynamics
(:mod:`rt_drake.dynamics.wrench`), the retimer and its checks take a
:class:`CupFrame`; build it once per plant and pass it on:

    cup = CupFrame.of(plant)                        # the frame "suction_cup"
    cup = CupFrame.of(plant, "tool_tip", arm_b)     # a name in a model instance
    cup = CupFrame.of(plant, plant.GetFrameByName("tool_tip"))

Besides the frame it holds what the dynamics use at every grid point: the
revolute joints of C's own kinematic chain whose parent body is welded to
the world (their axes ``k_W`` are fixed in W). If one is along gravity,
gravity in C is read from that joint's Jacobian column, ``g_C = (g_W . k_W)
J_w[:, k]``, instead of a rotation query per point
(:func:`vertical_base_joint`). Only joints that move C count: a joint of
another arm or of a turntable in the same plant has a zero column for C.

When the plant's positions are exactly the revolute joints from the world to
C, it also holds that chain (:class:`rt_drake.dynamics.chain.SerialChain`), and the
retimer samples the object wrench with it, batched, instead of from Drake
point by point; any other plant (a second arm, a turntable beside the arm)
has none and takes Drake's route.
"""

from __future__ import annotations

import dataclasses

from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import Frame, ModelInstanceIndex

from rt_drake import arguments
from rt_drake.dynamics.chain import SerialChain
from rt_drake.model.frames import DEFAULT_CUP_FRAME, find_frame


@dataclasses.dataclass(frozen=True, eq=False)
class CupFrame:
    """The cup frame C of a plant (see the module docstring).

    Attributes:
        frame: The Drake frame C.
        base_axes: ``(velocity index, k_W)`` of each revolute joint of C's
            chain whose parent body is welded to the world, ``k_W`` its
            axis in W (unit, fixed).
        chain: The serial chain from the world to C if the plant's
            positions are exactly its revolute joints, else None.
    """

    frame: Frame
    base_axes: tuple[tuple[int, tuple[float, float, float]], ...]
    chain: SerialChain | None = None

    def __post_init__(self) -> None:
        arguments.instance(self.frame, "frame", Frame, where="CupFrame")
        arguments.instance(self.base_axes, "base_axes", tuple, where="CupFrame")

    @classmethod
    def of(
        cls,
        plant: MultibodyPlant,
        frame: Frame | str | None = None,
        model_instance: ModelInstanceIndex | None = None,
    ) -> CupFrame:
        """The cup frame of a finalized ``plant``.

        Args:
            plant: Finalized plant.
            frame: The frame, or its name, possibly scoped
                (``"tool_b::suction_cup"``; default ``"suction_cup"``).
            model_instance: The model instance holding a frame given by name
                (needed when several instances have a frame of that name).

        Raises:
            InputError: no such frame, or a name found in several model
                instances without ``model_instance``.
        """
        cup_frame: Frame = (
            frame
            if isinstance(frame, Frame)
            else find_frame(plant, frame or DEFAULT_CUP_FRAME, model_instance)
        )
        context = plant.CreateDefaultContext()
        welded = {body.index() for body in plant.GetBodiesWeldedTo(plant.world_body())}
        cup_body = cup_frame.body().index()
        axes = []
        for index in plant.GetJointIndices():
            joint = plant.get_joint(index)
            if joint.type_name() != "revolute":
                continue
            if joint.parent_body().index() not in welded:
                continue
            if cup_body not in plant.GetBodiesKinematicallyAffectedBy([index]):
                continue
            R_WF = joint.frame_on_parent().CalcRotationMatrixInWorld(context)
            k_W = R_WF.multiply(joint.revolute_axis())
            axes.append((joint.velocity_start(), (k_W[0], k_W[1], k_W[2])))
        return cls(
            frame=cup_frame,
            base_axes=tuple(axes),
            chain=SerialChain.of(plant, cup_frame),
        )


def vertical_base_joint(
    plant: MultibodyPlant, cup: CupFrame
) -> tuple[int, float] | None:
    """A base joint of C's chain whose axis is along the plant's gravity now.

    Gravity is read at every call (it may change after Finalize); the
    alignment test ``k_W x g_W = 0`` is scalar arithmetic.

    Returns:
        (velocity index of the joint, ``g_W . k_W`` in m/s^2), or None.
    """
    gx, gy, gz = plant.gravity_field().gravity_vector().tolist()
    scale = 1e-12 * (1.0 + abs(gx) + abs(gy) + abs(gz))
    for velocity_index, (kx, ky, kz) in cup.base_axes:
        cross = (ky * gz - kz * gy, kz * gx - kx * gz, kx * gy - ky * gx)
        if max(abs(v) for v in cross) <= scale:
            return velocity_index, kx * gx + ky * gy + kz * gz
    return None


__all__ = ["CupFrame", "vertical_base_joint"]
