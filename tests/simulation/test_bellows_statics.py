"""The bellows cup alone against its closed forms (no arm, no planner).

Rig (tests/bellows_rig.py): the tool fixed, its cup frame C
pointing down, a 0.551 kg box hanging on the lip under vacuum, and a wrench
ramping on the box at the face point under the lip's centre.

- pull-off: a force pulling the box straight off along +z_C comes off at
  ``f = P A - m g`` (the vacuum holds the weight and the pull);
- sag and shear: the bellows stretches by ``(m + m_lip) g / k_axial`` and a
  steady shear f deflects the lip by ``f / k_lateral``;
- peel: a growing moment tilts the box on the ring of n springs
  ``k = K / n`` at radius r and lifts the far side; the seal breaks when
  the largest lift reaches the leak gap. The reference solves the ring's
  statics (rigid box, linear unilateral springs) independently of Drake.
"""

from __future__ import annotations

import numpy as np
import pytest
from bellows_rig import GRAVITY, MASS, make_rig
from scipy.optimize import brentq

from rt_drake.model.cup_physics import BellowsCup, load_bellows_cup

#: N/s and N m/s: slow ramps (the bellows modes are 5-7 Hz).
PULL_RATE = 4.0
PEEL_RATE = 0.1
STEP = 0.005  # s, how finely the seal is watched


@pytest.fixture(scope="module")
def cup() -> BellowsCup:
    return load_bellows_cup("vs060_bellows")


def _seal_breaks(rig, rate: float, t_start: float = 0.1, t_max: float = 5.0) -> float:
    """The ramp's value (rate x elapsed time) when the seal first breaks."""
    t = t_start
    while t < t_max:
        t += STEP
        rig.simulator.AdvanceTo(t)
        if not rig.sealed():
            return rate * (t - t_start)
    raise AssertionError(f"the seal held to t = {t_max} s")


def ring_peel_moment(cup: BellowsCup) -> float:
    """N m: the moment at which a ring of springs leaks under the full pull.

    Points j at ``y_j = r sin(2 pi j / n)``, stiffness ``k = K / n``. A rigid
    face turned by theta about x_C, with the lip centre pressed in by d,
    lifts point j by ``g_j = theta y_j - d``; the springs push
    ``f_j = k max(-g_j, 0)``. At the leak, ``max_j g_j = h``: d = theta
    y_max - h, and theta solves ``sum_j f_j = P A s(-d)`` (the pull, with
    s the gap law: full while the centre is pressed in). The moment is
    ``M = -sum_j f_j y_j``.
    """
    n, r, h = cup.lip_points, cup.radius, cup.leak_gap
    k = cup.lip_stiffness / n
    y = r * np.sin(2 * np.pi * np.arange(n) / n)

    def forces(theta: float) -> np.ndarray:
        d = theta * y.max() - h
        return k * np.clip(d - theta * y, 0.0, None)

    def balance(theta: float) -> float:
        d = theta * y.max() - h
        pull = cup.suction_force * np.clip(1.0 + d / cup.vacuum_range, 0.0, 1.0)
        return forces(theta).sum() - pull

    theta = brentq(balance, h / (2 * r) + 1e-9, 1.0)
    return float(-(forces(theta) * y).sum())


def test_pull_off_force_is_pressure_times_area_less_weight(cup):
    rig = make_rig(cup, np.array([0, 0, 0, 0, 0, PULL_RATE]))
    expected = cup.pressure * cup.effective_area - MASS * GRAVITY
    # The box comes off within 2 % (the ramp moves 0.02 N per step watched).
    assert _seal_breaks(rig, PULL_RATE) == pytest.approx(expected, rel=0.02)


def test_bellows_sags_and_shears_as_its_springs(cup):
    shear = 2.0  # N along x_C, ramped over 0.5 s then held
    rig = make_rig(cup, np.array([0, 0, 0, shear / 0.5, 0, 0]), t_hold=0.6)
    rig.simulator.AdvanceTo(2.0)
    p_CL = rig.X_CL().translation()
    assert p_CL[0] == pytest.approx(shear / cup.lateral_stiffness, rel=0.02)
    sag = (MASS + cup.lip_mass) * GRAVITY / cup.axial_stiffness
    assert p_CL[2] == pytest.approx(sag, rel=0.02)
    # The lip carried the shear by friction: the box did not slide on it.
    assert abs(rig.X_LO().translation()[0]) < 2e-5
    assert rig.sealed()


def test_peel_moment_matches_the_ring_model(cup):
    rig = make_rig(cup, np.array([PEEL_RATE, 0, 0, 0, 0, 0]), gravity=False)
    moment = _seal_breaks(rig, PEEL_RATE)
    reference = ring_peel_moment(cup)
    assert moment == pytest.approx(reference, rel=0.03)
    # Between the first lift of a linear ring (F r / 2) and tipping (F r).
    F_r = cup.suction_force * cup.radius
    assert F_r / 2 < reference < F_r


def test_ring_model_peel_moment_tends_to_tipping_for_a_stiff_lip(cup):
    """The reference itself against the rigid ring's closed form.

    A rigid ring pivots on its near edge: at the leak the far edge is up by
    h, the centre by h / 2, so the pull is ``P A (1 - h / (2 R))`` (R the
    vacuum range) and its moment about the edge ``P A (1 - h / (2 R)) r``.
    """
    stiff = cup.scaled(lip_stiffness=1e4)
    rigid = cup.suction_force * (1 - cup.leak_gap / (2 * cup.vacuum_range))
    assert ring_peel_moment(stiff) == pytest.approx(rigid * cup.radius, rel=0.01)
