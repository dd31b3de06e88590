"""The compliant lip's peel rows against a ring of springs, an LP and the simulation.

- Default: a cup without ``peel_fraction`` is the paper's rim model: the
  same fields (cache key), the same set.
- The rows against the closed form: the ring of equal lip springs on a rigid
  face, solved here as statics (three equilibrium equations, no closed form
  used), first lifts at ``|M_t| = N0 r / 2``; the rows allow exactly
  ``c N0 r`` at the polygon's corners and between ``cos(pi / K)`` of it and
  it elsewhere, ``N0 = P A + f_z``.
- The intersection against an independent LP of the rim model.
- The bellows simulation's lip (tests/bellows_rig.py) leaks at a moment at
  or above the planner's peel limit for the catalogue cup.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from bellows_rig import make_rig

from rt_drake.contact import (
    CupMount,
    CupParameters,
    contact_wrench_polytope,
    is_realizable_lp,
    peel_rows,
    with_suction_force,
)
from rt_drake.contact.peel import PEEL_SIDES
from rt_drake.contact.tool import ToolParameterError, ToolParameters
from rt_drake.contact.tool_polytope import tool_wrench_polytope
from rt_drake.contact.wrench_polytope import check_polytope
from rt_drake.errors import InputError, ScenarioError
from rt_drake.model.cup_physics import load_bellows_cup
from rt_drake.model.resources import resolve_scenario_path
from rt_drake.model.scenario import load_scenario

#: The bellows scenarios' planner cup (friction of the catalogue's lip).
CUP = CupParameters(friction=0.6, suction_force=20.0)
FRACTION = 0.5


@pytest.fixture(scope="module")
def rim():
    return contact_wrench_polytope(CUP)


@pytest.fixture(scope="module")
def peeled():
    return contact_wrench_polytope(dataclasses.replace(CUP, peel_fraction=FRACTION))


def ring_first_lift(N0: float, radius: float, psi: float, n: int = 720) -> float:
    """N m: the tilting moment (about the axis at angle psi + pi/2) that first
    lifts a point of a ring of n equal linear springs pressed on a rigid face.

    The face's small motion (d, theta_x, theta_y) presses point i by
    ``d + theta_x y_i - theta_y x_i``; the three equilibrium equations (load
    N0, moments M_x, M_y) give it, linear in M; the first lift is where the
    least spring force reaches zero.
    """
    angles = 2 * np.pi * np.arange(n) / n
    x, y = radius * np.cos(angles), radius * np.sin(angles)
    basis = np.stack([np.ones(n), y, -x], axis=1)  # compression per motion
    # Equilibrium: [sum f, sum f y, -sum f x] = [N0, M_x, M_y] (k = 1).
    A = basis.T @ basis
    direction = np.array([np.cos(psi), np.sin(psi)])

    def least_force(moment: float) -> float:
        load = np.array([N0, *(moment * direction)])
        return float((basis @ np.linalg.solve(A, load)).min())

    # Linear in the moment: the force at zero and its slope give the lift.
    at_zero, slope = least_force(0.0), least_force(1.0) - least_force(0.0)
    return -at_zero / slope


def largest_moment(F: np.ndarray, g: np.ndarray, wrench: np.ndarray, psi: float):
    """N m: the largest t with ``wrench + t [cos psi, sin psi, 0..]`` in F w <= g."""
    step = np.zeros(6)
    step[:2] = np.cos(psi), np.sin(psi)
    rate, room = F @ step, g - F @ wrench
    return float(np.min(room[rate > 0] / rate[rate > 0]))


def test_default_cup_is_the_rim_model(rim):
    assert CupParameters().peel_fraction is None
    assert "peel_fraction" not in CUP.as_dict()  # so the cache key is the paper's
    with_peel = dataclasses.replace(CUP, peel_fraction=FRACTION).as_dict()
    assert with_peel == {**CUP.as_dict(), "peel_fraction": FRACTION}
    # No row of the rim set bounds the tilt by the axial force alone.
    peel_F, _ = peel_rows(dataclasses.replace(CUP, peel_fraction=FRACTION))
    assert np.abs(rim.F @ peel_F.T).max() < 1 - 1e-6


@pytest.mark.parametrize("f_z", [-6.5, 0.0, 4.0])
def test_rows_against_the_ring_of_springs(peeled, f_z):
    """At the corners the limit is c / (1/2) times the ring's first lift."""
    wrench = np.array([0, 0, 0, 0, 0, f_z])
    N0 = CUP.suction_force + f_z
    F, g = peel_rows(peeled.cup)
    for j in range(2 * PEEL_SIDES):
        psi = np.pi * j / PEEL_SIDES  # corners (even j) and facet middles
        ring = ring_first_lift(N0, CUP.radius, psi)
        assert ring == pytest.approx(N0 * CUP.radius / 2, rel=1e-9)
        allowed = largest_moment(F, g, wrench, psi)
        share = np.cos(np.pi / PEEL_SIDES) if j % 2 else 1.0
        assert allowed == pytest.approx(FRACTION / 0.5 * ring * share, rel=1e-9)
        # The intersection never allows more, in any direction.
        assert largest_moment(peeled.F, peeled.g, wrench, psi) <= allowed + 1e-12


@pytest.mark.parametrize("fraction", [FRACTION, 0.74])
def test_intersection_against_an_lp_of_the_rim(rim, peeled, fraction):
    """0.74: the octagon's rows meet the rim's edges (Qhull merges facets)."""
    if fraction != FRACTION:
        peeled = contact_wrench_polytope(
            dataclasses.replace(CUP, peel_fraction=fraction)
        )
    check_polytope(peeled)
    rng = np.random.default_rng(0)
    # Wrenches around the boundary: the vertices of both sets scaled by 0.8-1.2.
    picks = np.vstack([rim.vertices[::13], peeled.vertices[::37]])
    wrenches = picks * rng.uniform(0.8, 1.2, size=(len(picks), 1))
    F, g = peel_rows(peeled.cup)
    margin = np.min(g - wrenches @ F.T, axis=1)
    distance = np.abs(margin)
    clear = distance > 1e-6  # away from the peel rows' boundary
    expected = is_realizable_lp(wrenches, CUP, tol=1e-9) & (margin >= 0)
    inside = peeled.contains(wrenches, tol=1e-9)
    assert np.count_nonzero(expected[clear]) > 20
    assert np.count_nonzero(~expected[clear]) > 20
    np.testing.assert_array_equal(inside[clear], expected[clear])
    # Every peel row is a facet: a tilt that lifts the lip is bound by it.
    assert all(np.any(np.all(np.isclose(peeled.F, row), axis=1)) for row in F)


def test_suction_translates_the_peel_set(peeled):
    weaker = dataclasses.replace(peeled.cup, suction_force=14.7)
    moved = with_suction_force(peeled, 14.7)
    direct = contact_wrench_polytope(weaker)
    wrenches = np.vstack([direct.vertices * 0.98, direct.vertices * 1.02])
    assert direct.contains(wrenches).any() and not direct.contains(wrenches).all()
    np.testing.assert_array_equal(moved.contains(wrenches), direct.contains(wrenches))


def test_bad_peel_fraction_is_refused(peeled):
    for value in (0.0, -0.5, 1.5, float("nan"), "half", True):
        with pytest.raises(InputError, match="peel_fraction"):
            CupParameters(peel_fraction=value)
    with pytest.raises(InputError, match="peel_fraction"):
        peel_rows(CUP)
    cup = dataclasses.replace(CUP, peel_fraction=FRACTION)
    one = tool_wrench_polytope(ToolParameters.single(cup))
    np.testing.assert_array_equal(one.F, peeled.F)
    two = ToolParameters(
        cups=(CupMount(cup), CupMount(CUP, p_TC=np.array([0.1, 0.0, 0.0])))
    )
    with pytest.raises(ToolParameterError, match="peel_fraction"):
        tool_wrench_polytope(two)  # 'any': no per-cup share to bound


def test_simulated_lip_leaks_at_or_above_the_peel_limit():
    """The bellows cup of the catalogue, no gravity, a moment about x_C ramping
    on the box: the seal breaks (the simulation's leak) at a moment at or
    above the largest the planner's set of that cup allows against it."""
    catalogue = load_bellows_cup("vs060_bellows")
    cup = CupParameters(
        radius=catalogue.radius,
        friction=catalogue.friction,
        suction_force=catalogue.suction_force,
        peel_fraction=FRACTION,
    )
    polytope = contact_wrench_polytope(cup)
    # The lip holds the box against +M_x: its wrench on the box is -M_x.
    planner = largest_moment(polytope.F, polytope.g, np.zeros(6), np.pi)
    assert planner == pytest.approx(FRACTION * cup.radius * cup.suction_force)
    rate, step = 0.1, 0.005  # N m / s; s, how finely the seal is watched
    rig = make_rig(catalogue, np.array([rate, 0, 0, 0, 0, 0]), gravity=False)
    t = t_start = 0.1
    while True:
        t += step
        rig.simulator.AdvanceTo(t)
        if not rig.sealed():
            break
        assert t < 5.0, "the seal held to 5 s"
    leak = rate * (t - t_start)
    assert planner <= leak
    # And the planner's limit is a peel, not a tip: below the rim's moment.
    rim = contact_wrench_polytope(dataclasses.replace(cup, peel_fraction=None))
    assert planner < largest_moment(rim.F, rim.g, np.zeros(6), np.pi)


def test_scenario_key_loads_and_a_bad_value_names_it(tmp_path):
    shipped = resolve_scenario_path("random_transport_uncertain_bellows")
    assert load_scenario(shipped).cup.peel_fraction == FRACTION
    text = shipped.read_text().replace("peel_fraction: 0.5", "peel_fraction: 1.5")
    bad = tmp_path / "bad.yaml"
    bad.write_text(text)
    with pytest.raises(ScenarioError, match=r"bad.yaml: key 'cup'.*peel_fraction.*1.5"):
        load_scenario(bad)


def test_intersection_when_the_rim_set_leaves_out_the_zero_wrench():
    """Suction above the rim's capacity (4 x 6.5 N < 29.9 N): the rim's set
    does not contain 0 (some g < 0), the intersection starts from an LP's
    interior point and still agrees with the LP of the rim."""
    cup = CupParameters(
        radius=0.00885, points=4, friction=0.82, sides=3,
        suction_force=29.9, max_normal_force=6.5, peel_fraction=0.5,
    )  # fmt: skip
    rim = contact_wrench_polytope(dataclasses.replace(cup, peel_fraction=None))
    assert rim.g.min() < 0
    peeled = contact_wrench_polytope(cup)
    check_polytope(peeled)
    rng = np.random.default_rng(2)
    centre = peeled.vertices.mean(axis=0)
    picks = np.vstack([rim.vertices, peeled.vertices])
    wrenches = centre + (picks - centre) * rng.uniform(0.8, 1.2, (len(picks), 1))
    F, g = peel_rows(cup)
    margin = np.min(g - wrenches @ F.T, axis=1)
    clear = np.abs(margin) > 1e-6
    expected = is_realizable_lp(wrenches, cup, tol=1e-9) & (margin >= 0)
    assert 10 < np.count_nonzero(expected[clear]) < np.count_nonzero(clear) - 10
    np.testing.assert_array_equal(
        peeled.contains(wrenches, tol=1e-9)[clear], expected[clear]
    )
