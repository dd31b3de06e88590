"""What a planning call returns: the path, the grasp it assumes, the timings."""

from __future__ import annotations

import dataclasses
import time

import numpy as np
from pydrake.math import RigidTransform

from rt_drake.types.path import GeometricPath
from rt_drake.types.phase import Phase


@dataclasses.dataclass(frozen=True)
class PlanTiming:
    """Wall time (s) of each stage of one planning call.

    Attributes:
        scene_s: updating the checker's object shapes for the phase.
        ik_s: inverse kinematics of the phase's poses (and their checks).
        rrt_s: straight-edge tries and OMPL RRT-Connect.
        shortcut_s: vertex reduction and random shortcuts.
        spline_s: fitting the spline(s).
        check_s: dense checks of the spline(s).
    """

    scene_s: float = 0.0
    ik_s: float = 0.0
    rrt_s: float = 0.0
    shortcut_s: float = 0.0
    spline_s: float = 0.0
    check_s: float = 0.0

    @property
    def total_s(self) -> float:
        """Sum of the stages (s)."""
        return (
            self.scene_s
            + self.ik_s
            + self.rrt_s
            + self.shortcut_s
            + self.spline_s
            + self.check_s
        )

    def summary(self) -> str:
        """One line, milliseconds: ``ik 2.1 rrt 3.0 ... total 9.8``."""
        stages = [f.name[:-2] for f in dataclasses.fields(self)]
        parts = [f"{name} {1e3 * getattr(self, name + '_s'):.1f}" for name in stages]
        return " ".join(parts) + f" total {1e3 * self.total_s:.1f} ms"


class Stopwatch:
    """Accumulates :class:`PlanTiming` stages: ``with watch("ik"): ...``."""

    def __init__(self) -> None:
        self.times = {f.name: 0.0 for f in dataclasses.fields(PlanTiming)}
        self._stage = ""
        self._start = 0.0

    def __call__(self, stage: str) -> Stopwatch:
        """Select the stage the next ``with`` block is timed into."""
        self._stage = f"{stage}_s"
        return self

    def __enter__(self) -> Stopwatch:
        self._start = time.perf_counter()
        return self

    def __exit__(self, *exc) -> None:
        """Add the time since ``__enter__`` to the stage."""
        self.times[self._stage] += time.perf_counter() - self._start

    def add(self, stage: str, seconds: float) -> None:
        """Add ``seconds`` to ``stage``."""
        self.times[f"{stage}_s"] += seconds

    def timing(self) -> PlanTiming:
        """The accumulated times."""
        return PlanTiming(**self.times)


@dataclasses.dataclass(frozen=True)
class PlannedPath:
    """A planned phase, ready for the retimer.

    Attributes:
        phase: APPROACH, REACH or MOVE.
        object: the object the phase is for.
        path: the collision-free spline q(s), s in [0, 1].
        polyline: the joint-space waypoints (rad) the spline was first fitted
            through, before refinement: the phase's anchors (IK solutions,
            REACH's IK line) when their spline was clean, else the connected
            polyline (edges checked, RRT-Connect where needed, shortcut).
        X_OC: the grasp used (pose of the cup frame C in the object frame O),
            the scenario's or its yaw flip about z_C.
        timing: wall time of each stage.
        descent: REACH and the blended pick only: the IK chain of the
            straight descent (rad, one configuration per ``LINE_STEP``, or
            closer, from the approach pose to the grasp), which a MOVE from
            the same grasp may lift along in reverse; None otherwise.
        lines_m: MOVE only: the heights (m) of its vertical lift above the
            grasp and of its vertical set-down above the place, 0.0 where
            the planner skipped that line; None for the other phases.
    """

    phase: Phase
    object: str
    path: GeometricPath
    polyline: np.ndarray
    X_OC: RigidTransform
    timing: PlanTiming
    descent: np.ndarray | None = None
    lines_m: tuple[float, float] | None = None

    @property
    def q_start(self) -> np.ndarray:
        """First configuration (rad)."""
        return self.path.waypoints[0]

    @property
    def q_goal(self) -> np.ndarray:
        """Last configuration (rad)."""
        return self.path.waypoints[-1]


__all__ = ["PlanTiming", "PlannedPath", "Stopwatch"]
