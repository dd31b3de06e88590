"""Random transport queries (the paper's Table I): object poses from regions.

A scenario's ``random_transport`` gives a start and a goal region: boxes of
the object frame's position (m, world) and yaw ranges (deg, about world z).
Objects keep the scenario's roll and pitch (zero: lying flat).
"""

from __future__ import annotations

import numpy as np
from pydrake.math import RigidTransform, RotationMatrix

from rt_drake.errors import ScenarioError
from rt_drake.model.scenario import (
    Region,
    Scenario,
)


def sample_pose(region: Region, rng: np.random.Generator) -> RigidTransform:
    """X_WO uniform in the region's box and yaw range."""
    p = rng.uniform(region.lower, region.upper)
    yaw = np.radians(rng.uniform(region.yaw_deg[0], region.yaw_deg[1]))
    return RigidTransform(RotationMatrix.MakeZRotation(yaw), p)


def sample_transports(
    scenario: Scenario, count: int, seed: int = 0
) -> list[tuple[RigidTransform, RigidTransform]]:
    """``count`` (X_WO start, X_WO goal) pairs of the transported object.

    Raises:
        ScenarioError: the scenario has no ``random_transport`` section.
    """
    transport = scenario.random_transport
    if transport is None:
        raise ScenarioError("the scenario has no 'random_transport' section")
    rng = np.random.default_rng(seed)
    return [
        (
            sample_pose(transport.start_region, rng),
            sample_pose(transport.goal_region, rng),
        )
        for _ in range(count)
    ]


__all__ = ["sample_pose", "sample_transports"]
