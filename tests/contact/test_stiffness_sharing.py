"""The stiffness-split wrench set of a tool of bellows cups, against references.

References, none of which forms the split S_i = K_Ci Ad_i^T K^-1:

- a spring network solved numerically: each cup's deflection under a rigid
  displacement of the object computed from the geometry (rotate and shift
  the cup's frame, by scipy's Rotation; Jacobian by central differences),
  equilibrium by virtual work solved with ``numpy.linalg.lstsq``, each cup's
  load its spring's force; then each load checked by the rim-force LP
  (:func:`~rt_drake.contact.lp_residual`, the pyramids' H-form);
- closed forms for two equal cups on T's x axis (a shear splits equally; a
  torsion about T is the cups' own torsion plus a shear couple; a tilt is
  the cups' tilt plus an axial couple);
- one cup: the cup's own set, moved to T (the tool LP over its rim forces).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from rt_drake.contact import (
    CupMount,
    CupParameters,
    CupStiffness,
    ToolParameterError,
    ToolParameters,
    lp_residual,
    stiffness_shared_set,
    stiffness_split,
)
from rt_drake.errors import InputError

#: The catalogue's bellows (models/cups/vs060_bellows_20n.yaml).
BELLOWS = CupStiffness(axial=700.0, lateral=1000.0, tilt=2.0, torsion=1.0)
CUP = CupParameters(friction=0.6)
A = 0.06  # m: half the cups' spacing
TWO = ToolParameters(
    cups=(
        CupMount(CUP, np.eye(3), [A, 0.0, 0.0], BELLOWS),
        CupMount(CUP, np.eye(3), [-A, 0.0, 0.0], BELLOWS),
    )
)
#: Two different cups and bellows, one turned about z and tilted, off T's plane.
TURNED = Rotation.from_euler("zx", [90.0, 20.0], degrees=True).as_matrix()
UNEQUAL = ToolParameters(
    cups=(
        CupMount(
            CupParameters(points=4, sides=3, friction=0.5),
            np.eye(3),
            [0.05, 0.01, 0.0],
            CupStiffness(axial=500.0, lateral=800.0, tilt=1.5, torsion=0.7),
        ),
        CupMount(
            CupParameters(radius=0.02, suction_force=30.0, friction=0.6),
            TURNED,
            [-0.04, 0.03, 0.01],
            BELLOWS,
        ),
    )
)
SCALE = np.array([0.2, 0.2, 0.1, 6.0, 6.0, 20.0])  # N m, N: typical loads


def _cup_deflection(mount: CupMount, twist: np.ndarray) -> np.ndarray:
    """``[theta; x]`` of the cup in C for the object moved by ``twist`` in T.

    The object turns by the rotation vector ``twist[:3]`` about T's origin and
    shifts by ``twist[3:]``: the point of it at C's origin goes to ``R p +
    x``, its frame turns by R. Both expressed in C.
    """
    R = Rotation.from_rotvec(twist[:3])
    p = np.array(mount.p_TC)
    moved = R.apply(p) + twist[3:] - p
    return np.concatenate([mount.R_TC.T @ twist[:3], mount.R_TC.T @ moved])


def _network_loads(tool: ToolParameters, wrenches: np.ndarray) -> np.ndarray:
    """(N, cups, 6): each cup's load, from the spring network's equilibrium.

    Virtual work: the object's twist d balances ``sum_i J_i^T K_i J_i d = w``
    with J_i the deflection's Jacobian (central differences of the geometry),
    solved by least squares; cup i then carries ``K_i J_i d`` (in C_i).
    """
    step = 1e-6
    jacobians = []
    for mount in tool.cups:
        J = np.zeros((6, 6))
        for k in range(6):
            e = np.zeros(6)
            e[k] = step
            J[:, k] = (_cup_deflection(mount, e) - _cup_deflection(mount, -e)) / (
                2 * step
            )
        jacobians.append(J)
    stiffness = [m.stiffness.matrix() for m in tool.cups]
    K = sum(J.T @ Kc @ J for J, Kc in zip(jacobians, stiffness, strict=True))
    twists = np.linalg.lstsq(K, wrenches.T, rcond=None)[0].T
    return np.stack(
        [twists @ (Kc @ J).T for J, Kc in zip(jacobians, stiffness, strict=True)],
        axis=1,
    )


def _about_tool(tool: ToolParameters, loads: np.ndarray) -> np.ndarray:
    """Sum the cups' loads about T's origin in T (forces turned, moments moved)."""
    total = np.zeros((len(loads), 6))
    for i, mount in enumerate(tool.cups):
        f = loads[:, i, 3:] @ mount.R_TC.T
        total[:, 3:] += f
        total[:, :3] += loads[:, i, :3] @ mount.R_TC.T + np.cross(mount.p_TC, f)
    return total


@pytest.mark.parametrize("tool", [TWO, UNEQUAL], ids=["two", "unequal"])
def test_the_set_holds_a_wrench_iff_every_cup_of_the_spring_network_holds_its_load(
    tool,
):
    rng = np.random.default_rng(1)
    directions = rng.normal(size=(60, 6)) * SCALE
    wrenches = directions * rng.uniform(0.2, 1.5, size=(60, 1))
    loads = _network_loads(tool, wrenches)
    # The network is a valid reference: its loads carry the whole wrench.
    np.testing.assert_allclose(_about_tool(tool, loads), wrenches, atol=1e-7)
    # And the split is the network's.
    split = stiffness_split(tool)
    np.testing.assert_allclose(
        np.einsum("cij,nj->nci", split, wrenches), loads, rtol=1e-6, atol=1e-7
    )
    residual = np.column_stack(
        [lp_residual(loads[:, i], mount.cup) for i, mount in enumerate(tool.cups)]
    )
    held_by_cups = residual.max(axis=1) <= 1e-7
    shared = stiffness_shared_set(tool)
    distance = (wrenches @ shared.F.T - shared.g).max(axis=1)
    assert 5 < held_by_cups.sum() < 55  # both kinds drawn
    clear = (np.abs(distance) > 1e-6) & ((residual.max(axis=1) > 1e-5) | held_by_cups)
    assert clear.sum() >= 50
    np.testing.assert_array_equal(
        (distance <= 1e-9)[clear], held_by_cups[clear], err_msg=str(distance)
    )


def test_two_equal_cups_split_as_the_closed_forms():
    split = stiffness_split(TWO)
    k, k_t, k_a, k_tilt = 1000.0, 1.0, 700.0, 2.0
    # A shear splits equally, and nothing else.
    for axis in (3, 4, 5):
        w = np.zeros(6)
        w[axis] = 8.0
        for S in split:
            np.testing.assert_allclose(S @ w, w / 2, atol=1e-12)
    # Torsion about T: one turn r_z; each cup turns by it and shifts by
    # r_z z x p, so cup i carries k_t r_z of torsion and k r_z (+-A) of y-shear.
    tau = 0.3
    r_z = tau / (2 * k_t + 2 * k * A**2)
    for S, sign in zip(split, (1.0, -1.0), strict=True):
        np.testing.assert_allclose(
            S @ [0, 0, tau, 0, 0, 0], [0, 0, k_t * r_z, 0, sign * k * A * r_z, 0]
        )
    # Tilt about y: each cup tilts by theta and moves -+A theta along z.
    theta = tau / (2 * k_tilt + 2 * k_a * A**2)
    for S, sign in zip(split, (1.0, -1.0), strict=True):
        np.testing.assert_allclose(
            S @ [0, tau, 0, 0, 0, 0],
            [0, k_tilt * theta, 0, 0, 0, -sign * k_a * A * theta],
        )


@pytest.mark.parametrize(
    "stiffness", [BELLOWS, CupStiffness(1.0, 50.0, 0.01, 3.0)], ids=["bellows", "other"]
)
def test_one_cup_is_the_cups_own_set_whatever_its_stiffness(stiffness):
    tool = ToolParameters(cups=(CupMount(CUP, TURNED, [0.01, -0.02, 0.0], stiffness),))
    shared = stiffness_shared_set(tool)
    wrenches = np.random.default_rng(2).normal(size=(80, 6)) * SCALE
    distance = (wrenches @ shared.F.T - shared.g).max(axis=1)
    residual = lp_residual(wrenches, tool)  # the cup's rim forces, mapped to T
    assert 5 < (residual <= 1e-7).sum() < 75
    clear = np.abs(distance) > 1e-6
    np.testing.assert_array_equal(distance[clear] <= 0, residual[clear] <= 1e-7)


def test_a_cup_without_stiffness_or_a_bad_stiffness_is_refused():
    bare = ToolParameters(
        cups=(TWO.cups[0], dataclasses.replace(TWO.cups[1], stiffness=None))
    )
    with pytest.raises(ToolParameterError, match="cup 1: .*stiffness.*got none"):
        stiffness_shared_set(bare)
    for field in ("axial", "lateral", "tilt", "torsion"):
        for value in (0.0, -1.0, float("nan"), float("inf"), True):
            with pytest.raises(InputError, match=f"stiffness {field} must be"):
                CupStiffness(**{**BELLOWS.as_dict(), field: value})
