"""An object that starts held on the bellows cups: at rest, at its static equilibrium.

A trial that starts with the object sealed on the tool (``random_transport.
start_on_cup``) stands for an object already picked and at rest: the arm
lifted it, the bellows stretched under its weight as the arm rose, and
their ring died out. Started instead on relaxed bellows, the object falls
into them, a step load that overshoots the static stretch by up to twice
(damping ratios 0.05-0.1): the 2.2 kg carton on two 14.7 N cups then pulls
its lips off the carton at the bottom of that first swing, 0.09 s into the
trial, before any MOVE (BENCHMARKS.md, "The 14.7 N carton", session 6). A
real pick loads the cups gradually; this module places the object and the
lips where that pick leaves them.

The object O and the lips L_i, pressed together by the vacuum, move as one
rigid assembly on the n bushings (each between its mount C_i on the tool and
L_i, :mod:`._bellows`). A small twist ``d = [theta; x]`` of the assembly
(rotation vector theta, rad, and translation x, m, of the point P, all in
the world frame W) deflects bushing i, in C_i at C_i's origin, by

    delta_i = J_i d,   J_i = [[R_CW, 0], [-R_CW [r_i]x, R_CW]],  r_i = p_WCi - P,

and the bushing puts ``-K_i delta_i`` on L_i (``K_i = diag(k_tilt, k_tilt,
k_torsion, k_lat, k_lat, k_axial)``, the catalogue cup's, small angles). The
assembly is at rest when the bushings carry its weight:

    K d = w_g,   K = sum_i J_i^T K_i J_i,   w_g = sum_B [(p_WBcm - P) x m_B g; m_B g],

(B over O and the lips, g the plant's gravity vector). The lip ring's own
compression under the vacuum is left as placed (0.08 mm for the catalogue
cup at full pull).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from pydrake.common.eigen_geometry import AngleAxis
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import RigidBody
from pydrake.systems.framework import Context

from rt_drake.model.cup_physics import BellowsCup
from rt_drake.simulation._bellows import Lip


def _cross(r: np.ndarray) -> np.ndarray:
    """``[r]x``, the (3, 3) matrix of ``v -> r x v``."""
    return np.array([[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]])


def bushing_stiffness(cup: BellowsCup) -> np.ndarray:
    """``K_C`` (6, 6): the bellows' stiffness on ``[rotation; translation]`` in C.

    N m/rad on the rotation (tilt about x_C and y_C, torsion about z_C), N/m on
    the translation (lateral along x_C and y_C, axial along z_C).
    """
    return np.diag(
        [
            cup.tilt_stiffness,
            cup.tilt_stiffness,
            cup.torsion_stiffness,
            cup.lateral_stiffness,
            cup.lateral_stiffness,
            cup.axial_stiffness,
        ]
    )


def hanging_twist(
    X_WC: Sequence[RigidTransform],
    K_C: np.ndarray,
    masses: Sequence[float],
    p_Wcm: Sequence[np.ndarray],
    gravity_W: np.ndarray,
    p_WP: np.ndarray,
) -> np.ndarray:
    """``d = [theta; x]`` (rad, m, in W, about P): the sag (module docstring).

    Args:
        X_WC: each bushing's mount C_i in W (its lip's rest pose).
        K_C: (6, 6) each bushing's stiffness (:func:`bushing_stiffness`).
        masses: kg, each body of the assembly.
        p_Wcm: m, each body's centre of mass in W.
        gravity_W: m/s^2, the gravity vector in W.
        p_WP: m, the point P the twist is about, in W.
    """
    K = np.zeros((6, 6))
    for X in X_WC:
        R_CW = X.rotation().inverse().matrix()
        J = np.zeros((6, 6))
        J[:3, :3] = J[3:, 3:] = R_CW
        J[3:, :3] = -R_CW @ _cross(X.translation() - p_WP)
        K += J.T @ K_C @ J
    w = np.zeros(6)
    for m, p in zip(masses, p_Wcm, strict=True):
        f = m * np.asarray(gravity_W, dtype=float)
        w += np.concatenate([np.cross(np.asarray(p) - p_WP, f), f])
    return np.linalg.solve(K, w)


def hang_on_lips(
    plant: MultibodyPlant,
    context: Context,
    lips: Sequence[Lip],
    cup: BellowsCup,
    body: RigidBody,
) -> None:
    """Move ``body`` and the ``lips`` in ``context`` by their sag (module docstring).

    ``context`` is the plant's, with the arm, the lips (at rest) and the
    object posed; the twist is about the object's body origin.
    """
    lip_bodies = [plant.get_body(lip.body_index) for lip in lips]
    bodies = [body, *lip_bodies]
    X_WB = [plant.EvalBodyPoseInWorld(context, b) for b in bodies]
    p_WP = X_WB[0].translation()
    masses = [b.get_mass(context) for b in bodies]
    p_Wcm = [
        X @ b.CalcCenterOfMassInBodyFrame(context)
        for X, b in zip(X_WB, bodies, strict=True)
    ]
    X_WC = [plant.get_frame(lip.mount).CalcPoseInWorld(context) for lip in lips]
    d = hanging_twist(
        X_WC,
        bushing_stiffness(cup),
        masses,
        p_Wcm,
        plant.gravity_field().gravity_vector(),
        p_WP,
    )
    angle = float(np.linalg.norm(d[:3]))
    axis = d[:3] / angle if angle > 0.0 else np.array([0.0, 0.0, 1.0])
    R = RotationMatrix(AngleAxis(angle, axis))
    for b, X in zip(bodies, X_WB, strict=True):
        p = p_WP + R.multiply(X.translation() - p_WP) + d[3:]
        plant.SetFreeBodyPose(context, b, RigidTransform(R @ X.rotation(), p))


__all__ = ["bushing_stiffness", "hang_on_lips", "hanging_twist"]
