"""Joint torques of held objects by Drake's inverse dynamics: an independent reference.

The scenario's arm and tool with one more body B, welded with its frame at
the cup frame C; an object's spatial inertia (mass, centre of mass and
rotational inertia about it, in C) is set in the context, and ``tau =
M(q) vdot + C(q, v) v - tau_g(q)`` comes from ``CalcInverseDynamics`` with
gravity as the applied force. No object wrench and no inertial-parameter
regressor: the retimer's torque rows are checked against it.
"""

from __future__ import annotations

import numpy as np
from pydrake.math import RigidTransform
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import MultibodyForces, RotationalInertia, SpatialInertia

from rt_drake.model.plant import CUP_FRAME, ObjectMode, add_scenario_models
from rt_drake.model.scenario import Scenario
from rt_drake.types.held_object import HeldObject


class TorqueReference:
    """Drake's inverse dynamics with an object welded at the cup frame.

    The arm and tool of the scenario and one body B whose frame is C; an
    object's spatial inertia (about Co, in C) is set in the context, then
    ``tau = M(q) vdot + C(q, v) v - tau_g(q)`` by ``CalcInverseDynamics``
    with gravity as the applied force.
    """

    def __init__(self, scenario: Scenario) -> None:
        plant = MultibodyPlant(0.0)
        add_scenario_models(plant, scenario, ObjectMode.NONE)
        self.body = plant.AddRigidBody(
            "probe",
            plant.AddModelInstance("probe"),
            SpatialInertia.SolidBoxWithMass(0.5, 0.1, 0.1, 0.1),
        )
        plant.WeldFrames(
            plant.GetFrameByName(CUP_FRAME), self.body.body_frame(), RigidTransform()
        )
        plant.Finalize()
        self.plant = plant
        self.context = plant.CreateDefaultContext()
        self.forces = MultibodyForces(plant)

    def torques(
        self, objects: list[HeldObject], q: np.ndarray, v: np.ndarray, a: np.ndarray
    ) -> np.ndarray:
        """(K, N, n) joint torques (N m) with each of K objects at N states."""
        plant, context = self.plant, self.context
        inertias = [
            SpatialInertia.MakeFromCentralInertia(
                o.mass, o.p_CoScm_C, _rotational(o.I_Scm_C)
            )
            for o in objects
        ]
        out = np.empty((len(objects), *q.shape))
        for i in range(len(q)):
            plant.SetPositionsAndVelocities(context, np.concatenate([q[i], v[i]]))
            for k, inertia in enumerate(inertias):
                self.body.SetSpatialInertiaInBodyFrame(context, inertia)
                plant.CalcForceElementsContribution(context, self.forces)
                out[k, i] = plant.CalcInverseDynamics(context, a[i], self.forces)
        return out


def _rotational(inertia: np.ndarray) -> RotationalInertia:
    """Drake's RotationalInertia of a symmetric (3, 3) matrix (kg m^2)."""
    (xx, xy, xz), (_, yy, yz), (_, _, zz) = inertia
    return RotationalInertia(xx, yy, zz, xy, xz, yz)


__all__ = ["TorqueReference"]
