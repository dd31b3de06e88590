"""The outer parameter set Q contains every object of the uncertainty set."""

import numpy as np
import pytest

from rt_drake.retiming._robust_rows import (
    Layout,
    vertex_weights,
)
from rt_drake.retiming._set_tables import parameter_columns
from rt_drake.types.held_object import HeldObject
from rt_drake.types.object_uncertainty import ObjectUncertainty
from rt_drake.uncertainty.inertial_set import (
    held_object,
    inertial_parameters,
    object_list,
    parallel_axes,
    uncertain_object,
)

NOTEBOOK = HeldObject(
    mass=0.551,
    p_CoScm_C=np.array([0.0, 0.0, 0.0125]),
    I_Scm_C=np.diag([9.28e-4, 2.11e-3, 2.98e-3]),
)


def notebook(R: np.ndarray) -> HeldObject:
    """The notebook held with its axes (its principal axes) at R_CO = R."""
    return HeldObject(
        NOTEBOOK.mass,
        NOTEBOOK.p_CoScm_C,
        R @ np.diag([9.28e-4, 2.11e-3, 2.98e-3]) @ R.T,
    )


SET = ObjectUncertainty(mass=0.2, com=[0.01, 0.01, 0.005], inertia=0.2)
#: A grasp whose object axes are not the cup's (cup at 180 deg about x, then
#: turned 30 deg about z).
_c, _s = np.cos(np.pi / 6), np.sin(np.pi / 6)
R_CO = np.array([[_c, -_s, 0.0], [_s, _c, 0.0], [0.0, 0.0, 1.0]]) @ np.diag(
    [1.0, -1.0, -1.0]
)


def _support(objects, direction):
    """max over Q of direction . pi, by the closed form of each box."""
    best = -np.inf
    for box in objects.boxes:
        B = direction @ box.unit + np.abs(box.com @ direction).sum()
        value = max(box.mass[0] * B, box.mass[1] * B)
        value += direction @ box.center + np.abs(box.inertia @ direction).sum()
        best = max(best, value)
    return best


def _members(held, uncertainty, R, count, rng, corners=False):
    """Points (m, p, I_Scm) of the uncertainty set (random, or at random corners).

    The whole box: also those whose moments break the triangle inequality
    (no body), which Q contains too.
    """
    moments, axes = np.linalg.eigh(held.I_Scm_C)
    draw = (
        (lambda n: rng.choice([-1.0, 1.0], n))
        if corners
        else (lambda n: rng.uniform(-1.0, 1.0, n))
    )
    for _ in range(count):
        m = held.mass * (1.0 + draw(1)[0] * uncertainty.mass)
        p = held.p_CoScm_C + R @ (draw(3) * uncertainty.com_half_widths)
        lam = moments * (1.0 + draw(3) * uncertainty.inertia)
        yield m, p, axes @ np.diag(lam) @ axes.T


def _parameters(m, p, I_Scm):
    """pi = (m, m p, I_Co) of a point of the set, by hand (not the code's)."""
    I_Co = I_Scm + m * (float(p @ p) * np.eye(3) - np.outer(p, p))
    entries = [I_Co[0, 0], I_Co[1, 1], I_Co[2, 2], I_Co[0, 1], I_Co[0, 2], I_Co[1, 2]]
    return np.concatenate([[m], m * p, entries])


def _is_body(I_Scm):
    moments = np.linalg.eigvalsh(I_Scm)
    return moments[2] <= moments[0] + moments[1]


def test_parameters_round_trip():
    held = HeldObject(0.7, np.array([0.01, -0.02, 0.03]), np.diag([1e-3, 2e-3, 3e-3]))
    back = held_object(inertial_parameters(held))
    assert back.mass == pytest.approx(held.mass)
    np.testing.assert_allclose(back.p_CoScm_C, held.p_CoScm_C, atol=1e-15)
    np.testing.assert_allclose(back.I_Scm_C, held.I_Scm_C, atol=1e-15)
    # Parallel axes: I_Co = I_Scm + m (|p|^2 1 - p p^T).
    p = held.p_CoScm_C
    np.testing.assert_allclose(parallel_axes(p) @ p, np.zeros(3), atol=1e-18)


@pytest.mark.parametrize("corners", [False, True])
@pytest.mark.parametrize("R", [np.diag([1.0, -1.0, -1.0]), R_CO])
def test_every_object_of_the_set_is_in_Q(corners, R):
    """pi of any object satisfies every support inequality of Q."""
    rng = np.random.default_rng(1)
    nominal = notebook(R)
    Q = uncertain_object(nominal, SET, R)
    directions = rng.normal(size=(400, 10)) * np.r_[1, [10] * 3, [1e3] * 6]
    supports = np.array([_support(Q, d) for d in directions])
    for member in _members(nominal, SET, R, 300, rng, corners):
        values = directions @ _parameters(*member)
        assert np.all(values <= supports + 1e-12 * np.abs(supports))


def test_vertices_are_objects_of_Q_and_attain_the_support():
    rng = np.random.default_rng(2)
    Q = uncertain_object(notebook(R_CO), SET, R_CO)
    columns, layout = parameter_columns(Q)
    # Principal axes along the object's: the moments' and S(delta)'s diagonal
    # generators are parallel and merge (3 + 3 off-diagonal).
    assert Q.vertex_count == 2 * 2**3 * 2**6
    # Misaligned about z (a nominal inertia not diagonal in O): only the z
    # generators merge, eight.
    assert uncertain_object(NOTEBOOK, SET, R_CO).vertex_count == 2 * 2**3 * 2**8
    keys = rng.integers(0, 2 ** (1 + 3 + 6), 50)
    vertices = vertex_weights(layout, keys, len(columns)) @ columns
    for direction in rng.normal(size=(20, 10)):
        assert np.max(vertices @ direction) <= _support(Q, direction) + 1e-12


def test_zero_width_is_the_nominal_object_and_lists_are_unions():
    assert uncertain_object(NOTEBOOK, ObjectUncertainty()).is_single()
    assert not uncertain_object(NOTEBOOK, SET).is_single()
    members = _members(NOTEBOOK, SET, np.eye(3), 40, np.random.default_rng(0))
    objects = [HeldObject(*member) for member in members if _is_body(member[2])][:5]
    many = object_list(objects)
    assert len(many.boxes) == 5 and not many.is_single()
    direction = np.random.default_rng(3).normal(size=10)
    expected = max(direction @ inertial_parameters(held) for held in objects)
    assert _support(many, direction) == pytest.approx(expected)
    columns, layout = parameter_columns(many)
    assert isinstance(layout, Layout) and columns.shape == (10, 10)
