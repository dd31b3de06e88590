"""The static sag of an object held on bellows cups, against closed forms.

:func:`~rt_drake.simulation._held_start.hanging_twist` solves ``K d = w_g``
for the object and lips on the bushings. Two closed forms of springs in
parallel (small angles), the cups pointing down (C's +z along -z_W):

- two equal cups at +-a on x_W, the load's centre of mass under their
  midpoint: no turn, a drop of ``sum m g / (2 k_axial)``;
- one cup, the object's centre of mass ``e`` off its axis along x_W and
  ``h`` below the lip: the lip turns about y_W by ``m g e / k_tilt`` and drops
  by ``m g / k_axial`` (the twist about the lip's centre, where the cup's
  tilt and lateral springs do not couple).
"""

from __future__ import annotations

import numpy as np
import pytest
from pydrake.math import RigidTransform, RollPitchYaw

from rt_drake.model.cup_physics import load_bellows_cup
from rt_drake.simulation._held_start import bushing_stiffness, hanging_twist

G = np.array([0.0, 0.0, -9.81])
DOWN = RollPitchYaw(np.pi, 0.0, 0.0).ToRotationMatrix()  # C's +z along -z_W
CUP = load_bellows_cup("vs060_bellows")


def test_two_cups_drop_the_load_evenly():
    a, mass, lip = 0.06, 2.2, CUP.lip_mass
    X_WC = [RigidTransform(DOWN, [x, 0.0, 0.5]) for x in (a, -a)]
    masses = [mass, lip, lip]
    p_Wcm = [np.array([0.0, 0.0, 0.4775])]
    p_Wcm += [np.array([x, 0.0, 0.5]) for x in (a, -a)]
    d = hanging_twist(X_WC, bushing_stiffness(CUP), masses, p_Wcm, G, p_Wcm[0])
    drop = (mass + 2 * lip) * 9.81 / (2 * CUP.axial_stiffness)
    np.testing.assert_allclose(d, [0, 0, 0, 0, 0, -drop], atol=1e-12)
    assert drop == pytest.approx(0.0157, abs=2e-4)  # the guide's 15.7 mm


def test_one_cup_turns_by_the_offset_weight():
    e, h, mass = 0.01, 0.02, 0.551
    X_WC = [RigidTransform(DOWN, [0.3, 0.1, 0.5])]
    p_WC = X_WC[0].translation()
    p_Wcm = [p_WC + [e, 0.0, -h]]
    d = hanging_twist(X_WC, bushing_stiffness(CUP), [mass], p_Wcm, G, p_WC)
    expected = [0, mass * 9.81 * e / CUP.tilt_stiffness, 0, 0, 0]
    expected.append(-mass * 9.81 / CUP.axial_stiffness)
    np.testing.assert_allclose(d, expected, atol=1e-12)
    # The same sag about another point: the same motion of every point.
    p_WP = p_WC + [0.05, -0.02, 0.03]
    d_P = hanging_twist(X_WC, bushing_stiffness(CUP), [mass], p_Wcm, G, p_WP)
    np.testing.assert_allclose(d_P[:3], d[:3], atol=1e-12)
    np.testing.assert_allclose(
        d_P[3:] + np.cross(d_P[:3], p_WC - p_WP), d[3:], atol=1e-12
    )
