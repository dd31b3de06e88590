"""The spring-split wrench set of a multi-cup tool, against independent LPs.

References: ``shared_load_residual`` (an LP over every rim force in its
pyramid's H-form, with the normal forces tied to a rigid displacement by
equality rows; it never forms the split matrix or a facet direction) and
``lp_residual`` (the free split, the Minkowski sum's LP).
"""

from __future__ import annotations

import numpy as np
import pytest

from rt_drake.contact import (
    CupMount,
    CupParameters,
    LoadSharing,
    SharedLoadSet,
    ToolParameterError,
    ToolParameters,
    lp_residual,
    shared_load_residual,
)
from rt_drake.contact.load_sharing import rim_springs
from rt_drake.errors import InputError

PAPER = CupParameters()
#: Two paper cups 0.12 m apart on T's x axis (scenarios/carton_two_cups.yaml).
TWO = ToolParameters(
    cups=(
        CupMount(PAPER, np.eye(3), [0.06, 0.0, 0.0]),
        CupMount(PAPER, np.eye(3), [-0.06, 0.0, 0.0]),
    )
)
#: Three cups of different models on a triangle, one turned about z.
TURN = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
THREE = ToolParameters(
    cups=(
        CupMount(
            CupParameters(points=4, sides=3, friction=0.5), np.eye(3), [0.05, 0, 0]
        ),
        CupMount(
            CupParameters(radius=0.02, suction_force=30.0), TURN, [-0.03, 0.04, 0]
        ),
        CupMount(CupParameters(points=5, sides=5), np.eye(3), [-0.03, -0.04, 0]),
    )
)
SCALE = np.array([0.3, 0.3, 0.3, 10.0, 10.0, 30.0])  # N m, N: typical loads


def _distance(shared: SharedLoadSet, wrenches: np.ndarray) -> np.ndarray:
    return (wrenches @ shared.F.T - shared.g).max(axis=-1)


@pytest.mark.parametrize("tool", [TWO, THREE], ids=["two", "three"])
def test_the_rows_agree_with_the_spring_lp_on_random_wrenches(tool):
    shared = SharedLoadSet.of(tool)
    wrenches = np.random.default_rng(0).normal(size=(150, 6)) * SCALE
    inside = _distance(shared, wrenches) <= 1e-9
    assert 10 < inside.sum() < 140  # both kinds drawn
    realizable = shared_load_residual(wrenches, tool) <= 1e-8
    assert np.array_equal(inside, realizable)


@pytest.mark.parametrize("tool", [TWO, THREE], ids=["two", "three"])
def test_the_rows_agree_with_the_spring_lp_at_the_boundary(tool):
    """Along random rays from 0: just inside is realizable, just outside not."""
    shared = SharedLoadSet.of(tool)
    rays = np.random.default_rng(1).normal(size=(30, 6)) * SCALE
    reach = shared.F @ rays.T
    step = np.min(np.where(reach > 0, shared.g[:, None] / reach, np.inf), axis=0)
    inner = shared_load_residual(rays * (step * (1 - 1e-4))[:, None], tool)
    outer = shared_load_residual(rays * (step * (1 + 1e-3))[:, None], tool)
    assert inner.max() <= 1e-8
    assert outer.min() > 1e-9


def test_springs_split_the_load_within_what_any_split_allows():
    """Every spring-held wrench is held by the free split, not the reverse."""
    shared = SharedLoadSet.of(TWO)
    wrenches = np.random.default_rng(2).normal(size=(120, 6)) * 0.3 * SCALE
    inside = _distance(shared, wrenches) <= 1e-9
    assert lp_residual(wrenches[inside], TWO).max() <= 1e-8
    # A yaw torque that needs the outer rim points loaded more than springs
    # load them: the free split holds it, the springs do not.
    hanging = np.array([0.0, 0.0, 0.0, 0.0, 0.0, -21.6])  # carries 2.2 kg
    yaw = np.array([0.0, 0.0, 1.0, 0.0, 0.0, 0.0])
    free = [lp_residual(hanging + t * yaw, TWO) <= 1e-8 for t in np.linspace(0, 2, 81)]
    springs = _distance(shared, hanging + np.linspace(0, 2, 81)[:, None] * yaw) <= 0
    assert np.sum(free) > np.sum(springs) > 0


def test_the_split_balances_the_load_as_a_rigid_displacement():
    """n(w) balances the normal wrench and lies on a plane over the rim
    (n_i = c1 y_i - c2 x_i + c3): the springs of a rigid displacement."""
    springs = rim_springs(THREE)
    wrench = np.array([0.2, -0.1, 0.05, 1.0, -2.0, 12.0])
    n = springs.normal_forces(wrench)
    x, y = springs.positions.T
    rim = wrench[[0, 1, 5]] - springs.suction
    assert np.allclose([n @ y, -(n @ x), n.sum()], rim)
    plane = np.column_stack([y, -x, np.ones_like(x)])
    c, *_ = np.linalg.lstsq(plane, n, rcond=None)
    assert np.allclose(plane @ c, n, atol=1e-12)


def test_two_cups_hold_the_carton_one_cup_cannot():
    # Gravity along +z_T (the carton hangs under the tool): the cups pull.
    carry = np.array([0.0, 0.0, 0.0, 0.0, 0.0, -2.2 * 9.81])
    assert SharedLoadSet.of(TWO).contains(carry)
    assert lp_residual(carry, PAPER) > 1.0  # one paper cup: 1.6 N short


def test_a_tilted_or_lifted_cup_is_refused_with_its_index():
    lifted = ToolParameters(
        cups=(TWO.cups[0], CupMount(PAPER, np.eye(3), [0, 0, 0.01]))
    )
    with pytest.raises(ToolParameterError, match="cup 1: elastic load sharing"):
        SharedLoadSet.of(lifted)
    c, s = np.cos(0.3), np.sin(0.3)
    tilt = np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])
    tilted = ToolParameters(cups=(CupMount(PAPER, tilt, [0.06, 0, 0]), TWO.cups[1]))
    with pytest.raises(ToolParameterError, match="cup 0: elastic load sharing"):
        SharedLoadSet.of(tilted)


def test_the_spring_lp_refuses_a_cup_that_is_not_a_tool():
    with pytest.raises(
        InputError, match="tool must be a ToolParameters, got CupParameters"
    ):
        shared_load_residual(np.zeros(6), PAPER)  # type: ignore[arg-type]


def test_load_sharing_names_its_choices():
    assert {m.value for m in LoadSharing} == {"elastic", "any", "stiffness"}
