"""Plant-building helpers shared by the tests (``tests`` is on the path)."""

from __future__ import annotations

import numpy as np
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import RevoluteJoint, RigidBody, SpatialInertia, UnitInertia


def add_turntable(plant: MultibodyPlant, axis: list[float]) -> RigidBody:
    """A 5 kg turntable on a revolute joint to the world about ``axis`` (in W)."""
    table = plant.AddRigidBody(
        "turntable", SpatialInertia(5.0, np.zeros(3), UnitInertia.SolidBox(1, 1, 0.1))
    )
    plant.AddJoint(
        RevoluteJoint("turntable_joint", plant.world_frame(), table.body_frame(), axis)
    )
    return table
