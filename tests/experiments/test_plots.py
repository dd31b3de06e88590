"""Plots of the transport experiment."""

from __future__ import annotations

import numpy as np

from rt_drake.experiments._plots import plot_profiles


def test_profiles_plot_takes_two_grids(tmp_path):
    """The retimes with and without the constraint may refine different grids."""
    s_c, s_u = np.linspace(0, 1, 118), np.linspace(0, 1, 110)
    trial = {
        "index": 0,
        "profiles": {
            "s": s_c.tolist(),
            "sd_constrained": (1 + s_c * (1 - s_c)).tolist(),
            "sd_velocity_limit": (2 + 0 * s_c).tolist(),
            "s_unconstrained": s_u.tolist(),
            "sd_unconstrained": (1.5 + s_u * (1 - s_u)).tolist(),
        },
    }
    written = plot_profiles(trial, tmp_path / "sd.png")
    assert written.stat().st_size > 1000
