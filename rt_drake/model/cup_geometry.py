"""The simulated cup's contact geometry: rim spheres, a tool's holders and bar.

The rim of a cup of radius r with m contact points is m spheres of radius
:data:`RIM_SPHERE_RADIUS` touching the plane z_C = 0 at ``p_CPi_C = r
(cos(2 pi i/m), sin(2 pi i/m), 0)`` in the cup frame C (+z out of the cup
toward the object), exactly where the grasp constraint's contact model puts
the contact points; their friction is :func:`rim_friction`. A multi-cup
tool (tool frame T) also gets a holder per cup and a bar that carries them
(m). Geometry is registered on the tool body B of an unfinalized plant.
"""

from __future__ import annotations

import numpy as np
from pydrake.geometry import Box, Cylinder, Sphere
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.multibody.plant import CoulombFriction, MultibodyPlant
from pydrake.multibody.tree import Frame

from rt_drake.contact import CupMount, CupParameters, ToolParameters
from rt_drake.contact.tool import is_identity_pose
from rt_drake.errors import ScenarioError

#: Friction coefficient of the objects' SDF collision geometry.
OBJECT_FRICTION = 1.0
#: m, radius of the spheres that model the cup's rim.
RIM_SPHERE_RADIUS = 0.002
#: m, a multi-cup tool's holders: radial clearance beyond the cup's radius,
#: gap above the contact face and length (the shipped tool's cup cylinder),
#: and the thickness of the bar that carries them.
HOLDER_CLEARANCE = 0.0025
HOLDER_GAP = 0.006
HOLDER_LENGTH = 0.014
BAR_THICKNESS = 0.01
TOOL_COLOUR = np.array([0.08, 0.08, 0.08, 1.0])


def rim_friction(
    cup_friction: float, object_friction: float = OBJECT_FRICTION
) -> float:
    """Friction of the rim spheres so that rim-object contact has ``cup_friction``.

    Drake combines two coefficients as ``2 a b / (a + b)``; solving
    ``2 r o / (r + o) = mu`` for the rim's r gives ``r = mu o / (2 o - mu)``.
    """
    if not 0.0 <= cup_friction < 2.0 * object_friction:
        raise ScenarioError(
            f"key 'cup.friction': {cup_friction} must lie in [0, {2 * object_friction})"
            f" for objects of friction {object_friction}"
        )
    return cup_friction * object_friction / (2.0 * object_friction - cup_friction)


def add_cup_rim(
    plant: MultibodyPlant,
    cup_frame: Frame,
    cup: CupParameters,
    X_BC: RigidTransform | None = None,
    prefix: str = "",
) -> None:
    """Register the cup's rim as ``cup.points`` small spheres on the tool body.

    Sphere i touches the plane z_C = 0 at the contact point
    ``p_CPi_C = r (cos(2 pi i/m), sin(2 pi i/m), 0)`` of the contact model, so
    the simulated cup touches an object exactly where the grasp constraint
    assumes (friction: :func:`rim_friction`). The cup frame C is
    ``cup_frame``, or at ``X_BC`` in its body B if given; the spheres are
    named ``{prefix}rim_{i}``.
    """
    mu = rim_friction(cup.friction)
    if X_BC is None:
        X_BC = cup_frame.GetFixedPoseInBodyFrame()
    for i in range(cup.points):
        angle = 2.0 * np.pi * i / cup.points
        p_CS = [
            cup.radius * np.cos(angle),
            cup.radius * np.sin(angle),
            -RIM_SPHERE_RADIUS,
        ]
        plant.RegisterCollisionGeometry(
            cup_frame.body(),
            X_BC @ RigidTransform(p_CS),
            Sphere(RIM_SPHERE_RADIUS),
            f"{prefix}rim_{i}",
            CoulombFriction(mu, mu),
        )


def cup_poses_in_body(frame: Frame, tool: ToolParameters) -> list[RigidTransform]:
    """Pose X_BCi of each cup frame C_i in the tool body B (T: ``frame``).

    ``X_BCi = X_BT X_TCi``; a cup at the tool frame is exactly X_BT.
    """
    X_BT = frame.GetFixedPoseInBodyFrame()
    return [
        X_BT if is_identity_pose(mount) else X_BT @ _mount_pose(mount)
        for mount in tool.cups
    ]


def add_tool_cups(plant: MultibodyPlant, frame: Frame, tool: ToolParameters) -> None:
    """Register a multi-cup tool's rims and the geometry that carries its cups.

    ``frame`` is the tool frame T. Per cup i: its rim (:func:`add_cup_rim`,
    spheres named ``cup{i}_rim_{j}``) and a holder, a cylinder of radius
    ``r_i + 2.5 mm`` from 6 mm to 20 mm above the contact face (as the
    shipped tool's own cup); then a bar, the box over T's x-y extent of every
    holder, from 20 mm to 30 mm above T's origin (it carries the cups from
    the tool's body). Collision and illustration alike.
    """
    X_BT = frame.GetFixedPoseInBodyFrame()
    body = frame.body()
    low, high = np.full(2, np.inf), np.full(2, -np.inf)
    for i, (mount, X_BC) in enumerate(
        zip(tool.cups, cup_poses_in_body(frame, tool), strict=True)
    ):
        add_cup_rim(plant, frame, mount.cup, X_BC, prefix=f"cup{i}_")
        holder = Cylinder(mount.cup.radius + HOLDER_CLEARANCE, HOLDER_LENGTH)
        X_BH = X_BC @ RigidTransform([0.0, 0.0, -HOLDER_GAP - HOLDER_LENGTH / 2])
        _register(plant, body, X_BH, holder, f"cup{i}_holder")
        reach = mount.cup.radius + HOLDER_CLEARANCE
        low = np.minimum(low, mount.p_TC[:2] - reach)
        high = np.maximum(high, mount.p_TC[:2] + reach)
    bar = Box(*(high - low), BAR_THICKNESS)
    centre = [*((low + high) / 2), -HOLDER_GAP - HOLDER_LENGTH - BAR_THICKNESS / 2]
    _register(plant, body, X_BT @ RigidTransform(centre), bar, "cup_bar")


def _register(
    plant: MultibodyPlant, body, X_BG: RigidTransform, shape, name: str
) -> None:
    """Register ``shape`` on ``body`` for collision and illustration."""
    plant.RegisterCollisionGeometry(body, X_BG, shape, name, CoulombFriction())
    plant.RegisterVisualGeometry(body, X_BG, shape, name, TOOL_COLOUR)


def _mount_pose(mount: CupMount) -> RigidTransform:
    """X_TC of a cup mount."""
    return RigidTransform(RotationMatrix(mount.R_TC), mount.p_TC)


__all__ = [
    "OBJECT_FRICTION",
    "RIM_SPHERE_RADIUS",
    "add_cup_rim",
    "add_tool_cups",
    "cup_poses_in_body",
    "rim_friction",
]
