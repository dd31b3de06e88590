"""What the protective-stop tests share (tests/retiming/test_stop*.py).

The notebook held on ``BACK`` (tests/grasp_paths.py), where its grasp binds:
the module fixtures ``limits`` (the plant's joint limits, with jerk limits
where a module asks for them), ``grasp`` (its grasp constraint) and ``move``
(``BACK`` retimed under both); and two references built apart
from the stop code: the path spline rebuilt with scipy and the joint jerk by
finite differences of 1 kHz samples' accelerations.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from grasp_paths import BACK
from scipy.interpolate import CubicSpline

from rt_drake.model.held import held_object_of
from rt_drake.retiming import GraspConstraint, JointLimits, chord_knots, retime

#: Jerk limits per second of the acceleration limits (the shipped scenarios').
JERK_PER_ACCELERATION = 20.0


def notebook_grasp(scenario) -> GraspConstraint:
    """The grasp constraint of the scenario's notebook under its cup."""
    return GraspConstraint.for_cup(
        held_object_of(scenario.object("notebook")), scenario.cup
    )


def notebook_fixtures(jerk: bool):
    """The module fixtures ``limits``, ``grasp`` and ``move`` of a stop test.

    ``limits``: ``stop_limits(plant, scenario, jerk)``; ``grasp``: the
    notebook's; ``move``: ``BACK`` retimed under both. A module binds them
    with ``limits, grasp, move = notebook_fixtures(jerk=...)``.
    """

    @pytest.fixture(scope="module")
    def limits(plant, scenario):
        return stop_limits(plant, scenario, jerk)

    @pytest.fixture(scope="module")
    def grasp(scenario):
        return notebook_grasp(scenario)

    @pytest.fixture(scope="module")
    def move(plant, limits, grasp):
        return retime(plant, BACK, limits, grasp)

    return limits, grasp, move


def stop_limits(plant, scenario, jerk: bool) -> JointLimits:
    """The plant's joint limits; with ``jerk``, ``JERK_PER_ACCELERATION`` times
    the acceleration limits as jerk limits (rad/s^3)."""
    plain = JointLimits.from_plant(plant, scenario.robot)
    if not jerk:
        return plain
    return dataclasses.replace(plain, jerk=JERK_PER_ACCELERATION * plain.acceleration)


def back_spline() -> CubicSpline:
    """``BACK`` as the clamped chord-length cubic spline, built with scipy."""
    return CubicSpline(chord_knots(BACK), BACK, bc_type="clamped")


def jerk_by_differences(trajectory, start: float, end: float) -> np.ndarray:
    """Joint jerk (M-1, n; rad/s^3) from the 1 kHz samples' accelerations."""
    times = np.append(np.arange(start, end, 1e-3), end)
    vdot = trajectory.sample(times, order=2)[2]
    return np.diff(vdot, axis=0) / np.diff(times)[:, None]


def assert_at_rest_on_back(whole, s_stop: float, t: float, at_rest: float) -> None:
    """``whole`` (a stop's whole trajectory) ends at rest on ``BACK``.

    At its end the joint velocity is below ``at_rest`` (rad/s) and q is
    ``BACK(s_stop)`` (by ``back_spline``, 1e-9 rad); 40 samples from ``t``
    to the end each lie within 2e-3 rad of the path sampled every 5e-5 in s.
    """
    spline = back_spline()
    end = whole.end_time()
    assert np.abs(whole.EvalDerivative(end, 1)).max() < at_rest
    assert np.allclose(whole.value(end).ravel(), spline(s_stop), atol=1e-9)
    times = np.linspace(t, end, 40)
    q = np.hstack([whole.value(tk) for tk in times]).T
    dense = np.linspace(0.0, 1.0, 20001)
    nearest = np.abs(q[:, None, :] - spline(dense)[None]).max(axis=2).min(axis=1)
    assert nearest.max() < 2e-3
