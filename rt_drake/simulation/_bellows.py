"""The bellows cup in the plant: a lip body on a bushing, a ring of compliant points.

Per cup of the tool (cup frame C_i on the tool body T), :func:`add_bellows_lips`
adds to an unfinalized plant:

- a lip body L_i (mass ``lip_mass``, inertia ``lip_inertia`` about each
  axis) whose frame coincides with
  C_i at rest: origin at the centre of the lip's contact face, +z out of
  the cup toward the object;
- a :class:`LinearBushingRollPitchYaw` between C_i and L_i: the bellows.
  With the bushing's displacement ``p = p_CiLi`` and roll-pitch-yaw angles
  ``q`` of ``R_CiLi``, the force on L_i is ``-(K_f p + D_f p')`` with
  ``K_f = diag(k_lat, k_lat, k_ax)`` (N/m) and the torque
  ``-(K_t q + D_t q')`` with ``K_t = diag(k_tilt, k_tilt, k_tor)``
  (N m/rad); under a static shear f along x_C alone the lip deflects
  ``x = f / k_lat``;
- the lip: ``lip_points`` spheres of radius :data:`LIP_SPHERE_RADIUS`
  touching the plane z_L = 0 at ``p_LPj = r (cos 2 pi j/n, sin 2 pi j/n,
  0)``, in point contact (Drake's compliant point contact, SAP) with
  stiffness ``lip_stiffness / n`` each (in series with the object's own),
  SAP dissipation time ``lip_relaxation_time``, and the friction that
  makes the lip-object coefficient the catalogue's ``friction``
  (:func:`~rt_drake.model.plant.rim_friction`). The lip does not touch the
  tool it hangs from.

The vacuum between lip and object is :mod:`._bellows_suction`.
"""

from __future__ import annotations

import dataclasses

import numpy as np
from pydrake.geometry import (
    AddContactMaterial,
    CollisionFilterDeclaration,
    Cylinder,
    GeometrySet,
    ProximityProperties,
    SceneGraph,
    Sphere,
)
from pydrake.math import RigidTransform
from pydrake.multibody.plant import CoulombFriction, MultibodyPlant
from pydrake.multibody.tree import (
    BodyIndex,
    FixedOffsetFrame,
    FrameIndex,
    LinearBushingRollPitchYaw,
    ModelInstanceIndex,
    RigidBody,
    RotationalInertia,
    SpatialInertia,
)

from rt_drake.model.cup_physics import BellowsCup
from rt_drake.model.plant import rim_friction

#: m, radius of the spheres of the lip ring.
LIP_SPHERE_RADIUS = 0.001
LIP_COLOUR = np.array([0.1, 0.1, 0.1, 1.0])


@dataclasses.dataclass(frozen=True)
class Lip:
    """One cup's lip in the plant.

    Attributes:
        body_index: the lip body L.
        mount: the frame C on the tool the bushing holds L to.
        X_TC: pose of C (L's rest pose) in the tool body T.
    """

    body_index: BodyIndex
    mount: FrameIndex
    X_TC: RigidTransform


def lip_points(cup: BellowsCup) -> np.ndarray:
    """The ring's points p_LPj (m, in L), one row each, on the plane z_L = 0."""
    angles = 2.0 * np.pi * np.arange(cup.lip_points) / cup.lip_points
    return np.column_stack(
        [cup.radius * np.cos(angles), cup.radius * np.sin(angles), 0 * angles]
    )


def add_bellows_lips(
    plant: MultibodyPlant,
    scene_graph: SceneGraph,
    tool_body: RigidBody,
    cup_poses: list[RigidTransform],
    cup: BellowsCup,
) -> list[Lip]:
    """Add one bellows lip per cup pose X_TC (see the module docstring)."""
    instance = plant.AddModelInstance("bellows")
    mu = rim_friction(cup.friction)
    lips = []
    for i, X_TC in enumerate(cup_poses):
        mass, inertia, r = cup.lip_mass, cup.lip_inertia, cup.radius
        body = plant.AddRigidBody(
            f"lip_{i}",
            instance,
            SpatialInertia.MakeFromCentralInertia(
                mass,
                np.zeros(3),
                RotationalInertia(inertia, inertia, inertia),
            ),
        )
        frame_C = plant.AddFrame(
            FixedOffsetFrame(f"bellows_mount_{i}", tool_body.body_frame(), X_TC)
        )
        plant.AddForceElement(
            LinearBushingRollPitchYaw(
                frame_C,
                body.body_frame(),
                [cup.tilt_stiffness, cup.tilt_stiffness, cup.torsion_stiffness],
                [cup.tilt_damping, cup.tilt_damping, cup.torsion_damping],
                [cup.lateral_stiffness, cup.lateral_stiffness, cup.axial_stiffness],
                [cup.lateral_damping, cup.lateral_damping, cup.axial_damping],
            )
        )
        properties = ProximityProperties()
        AddContactMaterial(
            dissipation=None,
            point_stiffness=cup.lip_stiffness / cup.lip_points,
            friction=CoulombFriction(mu, mu),
            properties=properties,
        )
        properties.AddProperty("material", "relaxation_time", cup.lip_relaxation_time)
        ids = []
        for j, p_LP in enumerate(lip_points(cup)):
            X_LS = RigidTransform(p_LP - [0.0, 0.0, LIP_SPHERE_RADIUS])
            ids.append(
                plant.RegisterCollisionGeometry(
                    body, X_LS, Sphere(LIP_SPHERE_RADIUS), f"lip_{i}_{j}", properties
                )
            )
        ring = RigidTransform([0.0, 0.0, -0.003])
        plant.RegisterVisualGeometry(
            body, ring, Cylinder(r + 0.001, 0.006), f"lip_{i}", LIP_COLOUR
        )
        tool_ids = plant.GetCollisionGeometriesForBody(tool_body)
        scene_graph.collision_filter_manager().Apply(
            CollisionFilterDeclaration().ExcludeBetween(
                GeometrySet(ids), GeometrySet(tool_ids)
            )
        )
        lips.append(Lip(body.index(), frame_C.index(), X_TC))
    return lips


def place_lips(
    plant: MultibodyPlant,
    lips: list[Lip],
    robot: ModelInstanceIndex,
    q_robot: np.ndarray,
) -> None:
    """Set each lip's default pose to its rest pose with the arm at ``q_robot``.

    ``X_WL = X_WC`` (the bushing relaxed); call after Finalize.
    """
    context = plant.CreateDefaultContext()
    plant.SetPositions(context, robot, q_robot)
    for lip in lips:
        X_WL = plant.get_frame(lip.mount).CalcPoseInWorld(context)
        plant.SetDefaultFloatingBaseBodyPose(plant.get_body(lip.body_index), X_WL)


__all__ = ["LIP_SPHERE_RADIUS", "Lip", "add_bellows_lips", "lip_points", "place_lips"]
