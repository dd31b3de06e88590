"""Each bellows cup's peel rows in the stiffness-split set, against closed forms.

``tool.load_sharing: stiffness`` gives cup i the share ``S_i w`` of the
wrench and keeps it in the cup's own set, which for a cup with
``peel_fraction`` c includes the lip's peel rows ``|M_t| <= c r (P A +
f_z)`` (:mod:`rt_drake.contact.peel`; the octagon's corners lie on C's x and
y axes, so along those axes the limit is exact). Closed forms for two equal
cups at ``+-a`` on T's x axis, bellows of axial, tilt stiffness ``k_a, k_t``
(springs in parallel, small angles), a net axial force ``F_z`` on the object:

- a moment ``M_x`` about the pair's line turns both cups' lips alike and moves
  neither along its axis: each carries ``M_x / 2`` on ``P A + F_z / 2``, so
  the tool peels at ``M_x = 2 c r (P A + F_z / 2)``;
- a moment ``M_y`` across the pair turns the tool by ``theta = M_y / K_y``,
  ``K_y = 2 k_t + 2 k_a a^2``: each cup's lip carries ``k_t theta`` and one
  cup's axial load falls by ``k_a a theta``, so it peels at ``k_t theta = c r
  (P A + F_z / 2 - k_a a theta)``: ``M_y = c r (P A + F_z / 2) K_y / (k_t + c
  r k_a a)``.

The rim model alone (no peel) lets either moment grow further; the other
splits refuse a cup's peel limit with a one-line error.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from rt_drake.contact import (
    CupMount,
    CupParameters,
    CupStiffness,
    LoadSharing,
    SharedLoadSet,
    ToolParameterError,
    ToolParameters,
    stiffness_shared_set,
    tool_wrench_polytope,
)
from rt_drake.contact.tool import refuse_peel

BELLOWS = CupStiffness(axial=700.0, lateral=1000.0, tilt=2.0, torsion=1.0)
C = 0.5  # the peel fraction
CUP = CupParameters(friction=0.6, suction_force=14.7, peel_fraction=C)
A = 0.06  # m, half the cups' spacing
F_Z = -10.0  # N, the net axial force the cups put on the object (its weight)


def _tool(cup: CupParameters) -> ToolParameters:
    return ToolParameters(
        cups=(
            CupMount(cup, np.eye(3), [A, 0.0, 0.0], BELLOWS),
            CupMount(cup, np.eye(3), [-A, 0.0, 0.0], BELLOWS),
        )
    )


def _largest(F: np.ndarray, g: np.ndarray, base: np.ndarray, u: np.ndarray) -> float:
    """Largest t with ``F (base + t u) <= g``."""
    rate, room = F @ u, g - F @ base
    assert (room > 0).all(), "the base wrench must lie inside"
    return float((room[rate > 1e-12] / rate[rate > 1e-12]).min())


BASE = np.array([0.0, 0.0, 0.0, 0.0, 0.0, F_Z])
N0 = CUP.suction_force + F_Z / 2  # each cup's lip load at the base


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_a_moment_along_the_pair_peels_both_lips_at_the_closed_form(sign):
    shared = stiffness_shared_set(_tool(CUP))
    u = np.array([sign, 0, 0, 0, 0, 0])
    limit = _largest(shared.F, shared.g, BASE, u)
    assert limit == pytest.approx(2 * C * CUP.radius * N0, rel=1e-9)
    rim = stiffness_shared_set(_tool(dataclasses.replace(CUP, peel_fraction=None)))
    assert _largest(rim.F, rim.g, BASE, u) > 1.5 * limit


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_a_moment_across_the_pair_peels_the_unloaded_lip_at_the_closed_form(sign):
    shared = stiffness_shared_set(_tool(CUP))
    u = np.array([0, sign, 0, 0, 0, 0])
    limit = _largest(shared.F, shared.g, BASE, u)
    k_a, k_t, cr = BELLOWS.axial, BELLOWS.tilt, C * CUP.radius
    K_y = 2 * k_t + 2 * k_a * A**2
    assert limit == pytest.approx(cr * N0 * K_y / (k_t + cr * k_a * A), rel=1e-9)
    rim = stiffness_shared_set(_tool(dataclasses.replace(CUP, peel_fraction=None)))
    assert _largest(rim.F, rim.g, BASE, u) > 1.2 * limit


def test_the_peel_rows_are_the_cups_own_rows_through_the_split():
    """Every peel row of each cup, through S_i, is a row of the tool's set."""
    from rt_drake.contact import stiffness_split
    from rt_drake.contact.peel import peel_rows

    tool = _tool(CUP)
    shared = stiffness_shared_set(tool)
    F_p, g_p = peel_rows(CUP)
    for S in stiffness_split(tool):
        rows = F_p @ S
        norms = np.linalg.norm(rows, axis=1)
        rows, offsets = rows / norms[:, None], g_p / norms
        for row, offset in zip(rows, offsets, strict=True):
            match = np.abs(shared.F - row).max(axis=1) < 1e-9
            assert match.any() and np.allclose(shared.g[match], offset)


def test_the_other_splits_refuse_a_cups_peel_limit():
    tool = _tool(CUP)  # a tool may state it; a split that cannot use it refuses
    message = r"cup 0: peel_fraction 0.5 needs load sharing 'stiffness'.*'elastic'"
    with pytest.raises(ToolParameterError, match=message):
        SharedLoadSet.of(tool)
    with pytest.raises(ToolParameterError, match="needs load sharing 'stiffness'"):
        tool_wrench_polytope(tool)
    # One cup: its own set, peel rows and all, whatever the split.
    for sharing in LoadSharing:
        refuse_peel(ToolParameters.single(CUP), sharing)
