"""rt_drake.dynamics.wrench: the object wrench along a path, against finite differences.

The reference is independent of Drake's Jacobians and bias terms: the cup
pose X_WC(t) from forward kinematics along a timed path, finite-differenced
to the CoM acceleration and the angular velocity and acceleration, then
Newton-Euler by hand.
"""

import dataclasses

import numpy as np
import pytest
from pydrake.common.schema import Transform
from pydrake.math import RigidTransform, RollPitchYaw, RotationMatrix
from pydrake.multibody.plant import MultibodyPlant
from scipy.interpolate import CubicSpline

from rt_drake.dynamics.wrench import (
    joint_torques,
    object_wrench,
    path_torque_coefficients,
    path_wrench_coefficients,
)
from rt_drake.model.held import held_object_of
from rt_drake.model.plant import (
    CUP_FRAME,
    ObjectMode,
    add_scenario_models,
)
from rt_drake.types.held_object import HeldObject

HOME = np.array([0.0, 0.35, 1.75, 0.0, 1.04, 0.0])
WAYPOINTS = np.array(
    [
        HOME,
        HOME + [0.7, 0.2, -0.3, 0.4, 0.3, 0.6],
        HOME + [1.4, -0.1, 0.1, -0.2, 0.5, 1.2],
    ]
)


@pytest.fixture(scope="module")
def held(scenario):
    # An off-centre object: CoM not on the cup axis, full inertia.
    return HeldObject(
        mass=0.8,
        p_CoScm_C=np.array([0.02, -0.015, 0.03]),
        I_Scm_C=np.array(
            [[2e-3, 2e-4, -1e-4], [2e-4, 3e-3, 3e-4], [-1e-4, 3e-4, 4e-3]]
        ),
    )


def _path():
    chords = np.linalg.norm(np.diff(WAYPOINTS, axis=0), axis=1)
    knots = np.concatenate([[0.0], np.cumsum(chords)]) / chords.sum()
    return CubicSpline(knots, WAYPOINTS, bc_type="clamped")


def _timing(t, T=1.3):
    """Quintic rest-to-rest s(t) on [0, T]: s, s', s''."""
    r = t / T
    s = 10 * r**3 - 15 * r**4 + 6 * r**5
    sd = (30 * r**2 - 60 * r**3 + 30 * r**4) / T
    sdd = (60 * r - 180 * r**2 + 120 * r**3) / T**2
    return s, sd, sdd


def _pose(plant, context, q):
    plant.SetPositions(context, q)
    return plant.GetFrameByName(CUP_FRAME).CalcPoseInWorld(context)


def _vee_log(R: np.ndarray) -> np.ndarray:
    """Rotation vector of a rotation matrix (small angles fine)."""
    aa = RotationMatrix(R).ToAngleAxis()
    return aa.angle() * aa.axis()


def _finite_difference_wrench(plant, held, t, h=1e-3):
    """Wrench on the object at time t from FK poses only (no Jacobians)."""
    spline = _path()
    context = plant.CreateDefaultContext()
    times = t + h * np.arange(-2, 3)
    poses = [_pose(plant, context, spline(_timing(ti)[0])) for ti in times]
    R = [X.rotation().matrix() for X in poses]
    p = [X.multiply(held.p_CoScm_C) for X in poses]
    a_W = (p[3] - 2 * p[2] + p[1]) / h**2
    omega = [_vee_log(R[k + 1] @ R[k - 1].T) / (2 * h) for k in (1, 2, 3)]
    alpha_W = (omega[2] - omega[0]) / (2 * h)
    R_WC = R[2]
    g_W = plant.gravity_field().gravity_vector()
    f_C = held.mass * R_WC.T @ (a_W - g_W)
    w_C, alpha_C = R_WC.T @ omega[1], R_WC.T @ alpha_W
    inertia = held.I_Scm_C
    torque = (
        inertia @ alpha_C + np.cross(w_C, inertia @ w_C) + np.cross(held.p_CoScm_C, f_C)
    )
    return np.concatenate([torque, f_C])


@pytest.mark.parametrize("t", [0.2, 0.45, 0.65, 0.9, 1.1])
def test_wrench_coefficients_match_finite_differences(plant, held, t):
    spline = _path()
    s, sd, sdd = _timing(np.array([t]))
    coefficients = path_wrench_coefficients(
        plant, held, spline(s), spline(s, 1), spline(s, 2)
    )
    w = (
        coefficients.a * sdd[:, None]
        + coefficients.b * sd[:, None] ** 2
        + coefficients.c
    )
    reference = _finite_difference_wrench(plant, held, t)
    scale = np.abs(reference).max()
    np.testing.assert_allclose(w[0], reference, atol=2e-5 * scale)


def test_gravity_term_at_rest_is_minus_weight(plant, held):
    """c(s): at rest the cup carries the weight, torque = p x f."""
    context = plant.CreateDefaultContext()
    c = path_wrench_coefficients(plant, held, HOME, 0 * HOME, 0 * HOME).c[0]
    R_WC = _pose(plant, context, HOME).rotation().matrix()
    f_C = -held.mass * R_WC.T @ plant.gravity_field().gravity_vector()
    np.testing.assert_allclose(c, np.concatenate([np.cross(held.p_CoScm_C, f_C), f_C]))
    # Cup pointing down at home: the cup pulls the object up, i.e. along -z_C.
    assert f_C[2] < -0.99 * held.mass * 9.81


def test_state_wrench_agrees_with_coefficients(plant, held):
    rng = np.random.default_rng(7)
    spline = _path()
    s = np.linspace(0, 1, 17)
    q, dq, ddq = spline(s), spline(s, 1), spline(s, 2)
    u, x = rng.normal(size=17), rng.uniform(0, 4, size=17)
    coefficients = path_wrench_coefficients(plant, held, q, dq, ddq)
    v = dq * np.sqrt(x)[:, None]
    vdot = dq * u[:, None] + ddq * x[:, None]
    expected = (
        coefficients.a * u[:, None] + coefficients.b * x[:, None] + coefficients.c
    )
    np.testing.assert_allclose(
        object_wrench(plant, held, q, v, vdot), expected, atol=1e-10
    )


@pytest.mark.parametrize("with_object", [False, True])
def test_torque_coefficients_match_inverse_dynamics(plant, held, with_object):
    rng = np.random.default_rng(3)
    spline = _path()
    s = np.linspace(0, 1, 11)
    q, dq, ddq = spline(s), spline(s, 1), spline(s, 2)
    u, x = rng.normal(size=11), rng.uniform(0, 4, size=11)
    obj = held if with_object else None
    tau = path_torque_coefficients(plant, q, dq, ddq, obj)
    v = dq * np.sqrt(x)[:, None]
    vdot = dq * u[:, None] + ddq * x[:, None]
    expected = joint_torques(plant, q, v, vdot, obj)
    actual = tau.a * u[:, None] + tau.b * x[:, None] + tau.c
    np.testing.assert_allclose(actual, expected, atol=1e-9)


def test_object_load_adds_its_weight_to_the_shoulder(plant, held):
    """At rest the object's weight must show in joint 2's torque: m g lever."""
    plain = path_torque_coefficients(plant, HOME, 0 * HOME, 0 * HOME).c[0]
    loaded = path_torque_coefficients(plant, HOME, 0 * HOME, 0 * HOME, held).c[0]
    assert abs(loaded[1]) > abs(plain[1])
    assert abs(loaded[1] - plain[1]) < held.mass * 9.81 * 1.5  # lever < 1.5 m


def test_held_object_from_scenario(scenario):
    obj = scenario.object("notebook")
    held = held_object_of(obj)
    assert held.mass == pytest.approx(0.551)
    # Grasp: cup 12.5 mm above the box centre, flipped: CoM 12.5 mm along +z_C.
    np.testing.assert_allclose(held.p_CoScm_C, [0, 0, 0.0125], atol=1e-12)
    # Flip about x keeps the principal moments on the diagonal.
    np.testing.assert_allclose(np.diag(held.I_Scm_C), [0.000928, 0.00211, 0.00298])


def test_held_object_from_plant_matches_model_file(scenario):
    plant = MultibodyPlant(0.0)
    add_scenario_models(plant, scenario, ObjectMode.FREE)
    plant.Finalize()
    for obj in scenario.objects:
        a = held_object_of(obj, plant)
        b = held_object_of(obj)
        assert a.mass == b.mass
        np.testing.assert_allclose(a.p_CoScm_C, b.p_CoScm_C)
        np.testing.assert_allclose(a.I_Scm_C, b.I_Scm_C)


def test_held_object_moves_inertia_through_the_grasp(scenario):
    obj = scenario.object("kindle_box")
    X_OC = RigidTransform(RollPitchYaw(np.pi, 0.3, np.pi / 2), [0.01, 0.02, 0.014])
    held = held_object_of(dataclasses.replace(obj, grasp=Transform(X_OC)))
    plain = held_object_of(obj)  # grasp with R_OC diagonal
    I_O = np.diag(np.abs(np.diag(plain.I_Scm_C)))  # principal moments in O
    R_CO = X_OC.rotation().inverse().matrix()
    np.testing.assert_allclose(held.I_Scm_C, R_CO @ I_O @ R_CO.T, atol=1e-12)
    np.testing.assert_allclose(held.p_CoScm_C, -R_CO @ X_OC.translation(), atol=1e-12)


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(mass=0.0, p_CoScm_C=np.zeros(3), I_Scm_C=np.eye(3)), "mass"),
        (dict(mass=1.0, p_CoScm_C=np.zeros(2), I_Scm_C=np.eye(3)), "p_CoScm_C"),
        (
            dict(mass=1.0, p_CoScm_C=np.zeros(3), I_Scm_C=np.triu(np.ones((3, 3)))),
            "symmetric",
        ),
    ],
)
def test_held_object_rejects_bad_input(kwargs, message):
    with pytest.raises(ValueError, match=message):
        HeldObject(**kwargs)


def test_plant_with_free_bodies_is_rejected(scenario, held):
    plant = MultibodyPlant(0.0)
    add_scenario_models(plant, scenario, ObjectMode.FREE)
    plant.Finalize()
    with pytest.raises(ValueError, match="only the path's joints"):
        path_wrench_coefficients(plant, held, HOME, HOME, HOME)


def test_gravity_term_is_the_cup_rotation_of_g(plant, held):
    """c(s) = -m [[p]x; 1] R_CW g_W, with R_WC from Drake's frame pose.

    The shipped arm's joint 1 is vertical, so the coefficients read gravity
    in C from its Jacobian column; with a tilted gravity no joint fits and
    they take the cup's rotation. Both must equal the reference.
    """
    from rt_drake.dynamics.cup_frame import (
        CupFrame,
        vertical_base_joint,
    )

    spline = _path()
    s = np.linspace(0.0, 1.0, 25)
    q = spline(s)
    context = plant.CreateDefaultContext()
    frame = plant.GetFrameByName(CUP_FRAME)
    cup = CupFrame.of(plant)
    assert vertical_base_joint(plant, cup) == (
        0,
        pytest.approx(-9.81),
    )
    gravity = plant.mutable_gravity_field()
    g_original = gravity.gravity_vector()
    p = held.p_CoScm_C
    try:
        for g_W in (g_original, np.array([1.0, 0.0, -9.81])):
            gravity.set_gravity_vector(g_W)
            c = path_wrench_coefficients(plant, held, q, spline(s, 1), spline(s, 2)).c
            for qi, ci in zip(q, c, strict=True):
                plant.SetPositions(context, qi)
                R_WC = frame.CalcRotationMatrixInWorld(context).matrix()
                g_C = R_WC.T @ g_W
                expected = -held.mass * np.hstack([np.cross(p, g_C), g_C])
                np.testing.assert_allclose(ci, expected, rtol=1e-12, atol=1e-12)
        assert vertical_base_joint(plant, cup) is None
    finally:
        gravity.set_gravity_vector(g_original)
