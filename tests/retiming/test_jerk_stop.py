"""Jerk-limited retiming refuses, typed, a path no motion can pass.

Reference: where the velocity cap on ``x = s'^2`` is 0 (a joint's q'
unbounded there, or its velocity limit 0), every motion has ``s' = 0`` and
stops for good, so no finite-time profile exists (closed form). The cap is
set to 0 between two grid points of TOPP-RA, where only the jerk LPs' points
see it.
"""

from __future__ import annotations

import numpy as np
import pytest

from rt_drake.retiming import JointLimits, PathNotControllableError, _solve, retime

HOME = np.array([0.0, 0.35, 1.75, 0.0, 1.04, 0.0])
#: The window where the cap is 0: around a jerk LP point (1/8 of the
#: segment [0.4949, 0.5000] of the 100-point grid), away from grid points.
WINDOW = (0.5010, 0.5015)


def test_a_point_that_no_motion_passes_is_a_typed_refusal(plant, scenario, monkeypatch):
    sample_path = _solve.sample_path

    def stopped(*args, **kwargs):
        samples = sample_path(*args, **kwargs)
        inside = (samples.s > WINDOW[0]) & (samples.s < WINDOW[1])
        return samples._replace(x_cap=np.where(inside, 0.0, samples.x_cap))

    plain = JointLimits.from_plant(plant, scenario.robot)
    limits = JointLimits(
        plain.velocity, plain.acceleration, jerk=20.0 * plain.acceleration
    )
    path = np.array([HOME, HOME + [0.5, -0.2, 0.3, 0.1, 0.2, 0.4]])
    free = retime(plant, path, limits)  # the same path passes without the cap
    assert np.isfinite(free.duration)
    monkeypatch.setattr(_solve, "sample_path", stopped)
    with pytest.raises(PathNotControllableError, match=r"s' = 0\) for s in") as error:
        retime(plant, path, limits)
    message = str(error.value)
    first, last = (float(v) for v in message.split("[")[1].split("]")[0].split(","))
    assert first == pytest.approx(error.value.s, abs=1e-4)
    # The stop named covers the window, and no more than its two segments.
    assert first <= WINDOW[0] and WINDOW[1] <= last and last - first <= 0.02
    assert len(message.splitlines()) == 1
