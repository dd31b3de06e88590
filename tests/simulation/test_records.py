"""The sequencer's pose arithmetic: slip on the lip, motion on the tool."""

from __future__ import annotations

import math

import pytest
from pydrake.math import RigidTransform, RollPitchYaw

from rt_drake.simulation.records import ObjectRecord, with_slip


def test_a_bellows_deflection_moves_the_object_on_the_tool_not_on_the_lip():
    """Lip and object twist 4 deg and shift 3 mm together: no slip, 3 mm on C."""
    X_LO = RigidTransform([0.0, 0.0, 0.02])
    X_CL = RigidTransform(RollPitchYaw(0.0, 0.0, math.radians(4.0)), [3e-3, 0, 0])
    record = with_slip(ObjectRecord("notebook"), X_LO, X_LO, X_LO, X_CL @ X_LO)
    assert record.max_slip_translation == 0.0
    assert record.max_slip_rotation == 0.0
    # X_CO = X_CL X_LO: the origin moves by p_CL (X_LO's translation is along
    # the twist's axis), the frame turns by the twist.
    assert record.max_on_tool_translation == pytest.approx(3e-3, abs=1e-12)
    assert record.max_on_tool_rotation == pytest.approx(math.radians(4.0), abs=1e-12)


def test_the_largest_motion_is_kept():
    """A later, smaller displacement does not lower the record."""
    X = RigidTransform()
    far = RigidTransform([0.0, 0.004, 0.0])
    near = RigidTransform([0.0, 0.001, 0.0])
    record = with_slip(ObjectRecord("box"), X, far, X, far)
    record = with_slip(record, X, near, X, near)
    assert record.max_slip_translation == pytest.approx(0.004)
    assert record.max_on_tool_translation == pytest.approx(0.004)
