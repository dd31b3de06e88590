"""The bellows tool's stiffness, inertia and periods against Drake and closed forms.

- Drake: a free object with the lips welded to it, each lip on a
  ``LinearBushingRollPitchYaw`` to the world at its cup pose, as the
  simulation builds them (:mod:`rt_drake.simulation._bellows`); the
  stiffness is the central difference of Drake's force-element forces in
  the object's pose, the inertia Drake's mass matrix. Their generalized
  eigenvalues are the periods.
- Closed form: two cups at ``x = +-d`` under an object whose centre of mass
  is on the tool's axis decouple; torsion about z has ``2 k_tor + 2 k_lat
  d^2``, tilt about y ``2 k_tilt + 2 k_ax d^2``, tilt about x ``2 k_tilt``.
"""

from __future__ import annotations

import numpy as np
import pytest
from pydrake.math import RigidTransform, RollPitchYaw, RotationMatrix
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import (
    FixedOffsetFrame,
    LinearBushingRollPitchYaw,
    MultibodyForces,
    RotationalInertia,
    SpatialInertia,
)
from scipy.linalg import eigh

from rt_drake.dynamics.bellows_modes import held_inertia, mode_periods, tool_stiffness
from rt_drake.model.cup_physics import BellowsCup, load_bellows_cup
from rt_drake.model.held import held_object_of
from rt_drake.model.resources import resolve_scenario_path
from rt_drake.model.scenario import load_scenario
from rt_drake.types.held_object import HeldObject

#: rad and m, the central difference's step.
STEP = 1e-6


@pytest.fixture(scope="module")
def cup() -> BellowsCup:
    return load_bellows_cup("vs060_bellows")


def _drake_stiffness_and_inertia(
    cup: BellowsCup, held: HeldObject, X_TCs: list[RigidTransform]
) -> tuple[np.ndarray, np.ndarray]:
    """K (by central differences of Drake's bushing forces) and M (Drake's)."""
    plant = MultibodyPlant(0.0)
    plant.mutable_gravity_field().set_gravity_vector(np.zeros(3))
    obj = plant.AddRigidBody(
        "object",
        SpatialInertia.MakeFromCentralInertia(
            held.mass, held.p_CoScm_C, RotationalInertia(*_moments(held.I_Scm_C))
        ),
    )
    for i, X_TC in enumerate(X_TCs):
        lip = plant.AddRigidBody(
            f"lip_{i}",
            SpatialInertia.MakeFromCentralInertia(
                cup.lip_mass,
                np.zeros(3),
                RotationalInertia(cup.lip_inertia, cup.lip_inertia, cup.lip_inertia),
            ),
        )
        plant.WeldFrames(obj.body_frame(), lip.body_frame(), X_TC)
        mount = plant.AddFrame(
            FixedOffsetFrame(f"mount_{i}", plant.world_frame(), X_TC)
        )
        plant.AddForceElement(
            LinearBushingRollPitchYaw(
                mount,
                lip.body_frame(),
                [cup.tilt_stiffness, cup.tilt_stiffness, cup.torsion_stiffness],
                [0.0, 0.0, 0.0],
                [cup.lateral_stiffness, cup.lateral_stiffness, cup.axial_stiffness],
                [0.0, 0.0, 0.0],
            )
        )
    plant.Finalize()
    context = plant.CreateDefaultContext()

    def forces(delta: np.ndarray) -> np.ndarray:
        angle = np.linalg.norm(delta[:3])
        axis = delta[:3] / angle if angle > 0 else np.array([0.0, 0.0, 1.0])
        R = RotationMatrix(_axis_angle(axis, angle))
        plant.SetFreeBodyPose(context, obj, RigidTransform(R, delta[3:]))
        out = MultibodyForces(plant)
        plant.CalcForceElementsContribution(context, out)
        # [torque about Bo; force], in W
        return plant.CalcGeneralizedForces(context, out)

    K = np.zeros((6, 6))
    for j in range(6):
        e = np.zeros(6)
        e[j] = STEP
        K[:, j] = -(forces(e) - forces(-e)) / (2 * STEP)
    plant.SetFreeBodyPose(context, obj, RigidTransform())
    return K, plant.CalcMassMatrix(context)


def _moments(inertia: np.ndarray) -> tuple[float, ...]:
    """(Ixx, Iyy, Izz, Ixy, Ixz, Iyz) of a symmetric 3 x 3 matrix."""
    (xx, xy, xz), (_, yy, yz), (_, _, zz) = inertia
    return xx, yy, zz, xy, xz, yz


def _axis_angle(axis: np.ndarray, angle: float) -> np.ndarray:
    """Rodrigues' rotation matrix."""
    S = np.array(
        [[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]]
    )
    return np.eye(3) + np.sin(angle) * S + (1 - np.cos(angle)) * S @ S


def _box(mass: float, size: tuple[float, float, float], p: np.ndarray) -> HeldObject:
    a, b, c = size
    moments = mass / 12 * np.array([b * b + c * c, a * a + c * c, a * a + b * b])
    return HeldObject(mass=mass, p_CoScm_C=p, I_Scm_C=np.diag(moments))


def test_two_cups_decouple_into_the_closed_forms(cup):
    d = 0.06
    X_TCs = [RigidTransform([d, 0.0, 0.0]), RigidTransform([-d, 0.0, 0.0])]
    held = _box(2.2, (0.32, 0.22, 0.045), np.zeros(3))
    K = tool_stiffness(cup, X_TCs)
    expected = np.diag(
        [
            2 * cup.tilt_stiffness,
            2 * cup.tilt_stiffness + 2 * cup.axial_stiffness * d**2,
            2 * cup.torsion_stiffness + 2 * cup.lateral_stiffness * d**2,
            2 * cup.lateral_stiffness,
            2 * cup.lateral_stiffness,
            2 * cup.axial_stiffness,
        ]
    )
    np.testing.assert_allclose(K, expected, rtol=1e-12, atol=1e-12)
    # The periods: 2 pi sqrt(inertia / stiffness) per axis, the lips as
    # point masses at +-d plus their own moments.
    m_lip, i_lip = cup.lip_mass, cup.lip_inertia
    moments = np.diag(held.I_Scm_C) + 2 * i_lip + 2 * m_lip * d**2 * np.array([0, 1, 1])
    inertia = np.concatenate([moments, np.full(3, held.mass + 2 * m_lip)])
    closed = np.sort(2 * np.pi * np.sqrt(inertia / np.diag(expected)))[::-1]
    periods, _ = mode_periods(K, held_inertia(held, cup, X_TCs))
    np.testing.assert_allclose(periods, closed, rtol=1e-12)
    # torsion is the axis the pair stiffens most: 2 k_lat d^2 = 7.2 N m/rad
    # against the one cup's 1 N m/rad
    assert expected[2, 2] > 4 * cup.torsion_stiffness


@pytest.mark.parametrize(
    "X_TCs",
    [
        [RigidTransform([0.0, 0.0, 0.0])],
        [RigidTransform([0.06, 0.0, 0.0]), RigidTransform([-0.06, 0.0, 0.0])],
        [  # three cups, one tilted 20 deg and raised: every coupling term
            RigidTransform([0.05, 0.02, 0.0]),
            RigidTransform([-0.04, 0.03, 0.0]),
            RigidTransform(RollPitchYaw(0.35, 0.0, 0.5), [0.0, -0.05, 0.01]),
        ],
    ],
    ids=["one cup", "two cups", "three cups, one tilted"],
)
def test_stiffness_inertia_and_periods_match_drakes_bushings(cup, X_TCs):
    # the centre of mass off the axis and below the face: the modes couple
    held = _box(0.9, (0.25, 0.16, 0.04), np.array([0.01, -0.008, 0.025]))
    K = tool_stiffness(cup, X_TCs)
    M = held_inertia(held, cup, X_TCs)
    K_drake, M_drake = _drake_stiffness_and_inertia(cup, held, X_TCs)
    np.testing.assert_allclose(K, K_drake, rtol=1e-6, atol=1e-6 * np.abs(K).max())
    np.testing.assert_allclose(M, M_drake, rtol=1e-12, atol=1e-12)
    omega2 = eigh(K_drake, M_drake, eigvals_only=True)
    reference = np.sort(2 * np.pi / np.sqrt(omega2))[::-1]
    periods, modes = mode_periods(K, M)
    np.testing.assert_allclose(periods, reference, rtol=1e-6)
    # each mode shape solves K v = (2 pi / T)^2 M v
    for T, v in zip(periods, modes.T, strict=True):
        np.testing.assert_allclose(K @ v, (2 * np.pi / T) ** 2 * M @ v, atol=1e-8)


@pytest.mark.parametrize(
    "name", ["carton_two_cups_bellows", "carton_two_cups_bellows_20n"]
)
def test_the_two_cup_scenarios_ramp_over_the_tools_longest_mode(cup, name):
    scenario = load_scenario(resolve_scenario_path(name))
    X_TCs = [
        RigidTransform(RotationMatrix(m.R_TC), m.p_TC)
        for m in scenario.tool_parameters().cups
    ]
    assert len(X_TCs) == 2
    held = held_object_of(scenario.objects[0])
    periods, _ = mode_periods(
        tool_stiffness(cup, X_TCs), held_inertia(held, cup, X_TCs)
    )
    assert scenario.planning.grasp_ramp_s == pytest.approx(periods[0], abs=1e-3)
    # one cup alone would give 0.97 s (torsion): the pair is far stiffer
    assert periods[0] < 0.4
