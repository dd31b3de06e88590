"""What one run of the optimiser's stages shapes, and the clock of its stages.

- :class:`ShapeTask`: the scene, the planner's path, the grasp (None for a
  pick), the path family and the final checks that
  :meth:`~._optimizer.MoveOptimizer.shape` runs its search and finish on
  (:meth:`~._optimizer.MoveOptimizer.optimize` makes a MOVE's,
  :func:`~._pick_shaping.shape_pick` a pick's);
- :class:`StageClock`: the wall and CPU time of each stage;
- :class:`Found`: the candidate the finish keeps.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable

from rt_drake.planning.result import PlannedPath
from rt_drake.planning.scene import PlanningScene
from rt_drake.retiming import GraspConstraint, RetimeResult
from rt_drake.shaping._family import PathFamily
from rt_drake.types.path import GeometricPath


class StageClock:
    """``with watch("stage"):`` adds the block's wall time to timings[stage].

    And this process's CPU time to ``timings["cpu_" + stage]``.
    """

    def __init__(self, timings: dict[str, float] | None) -> None:
        self.timings = dict(timings or {})
        for key in ("setup", "baseline", "search", "finish"):
            self.timings.setdefault(key, 0.0)
            self.timings.setdefault(f"cpu_{key}", 0.0)
        self._stage = ""
        self._start = self._cpu = 0.0
        #: wall and CPU clocks (s) when it was made
        self.wall, self.cpu = time.perf_counter(), time.process_time()

    def __call__(self, stage: str) -> StageClock:
        self._stage = stage
        return self

    def __enter__(self) -> StageClock:
        self._start, self._cpu = time.perf_counter(), time.process_time()
        return self

    def __exit__(self, *exc) -> None:
        self.timings[self._stage] += time.perf_counter() - self._start
        self.timings[f"cpu_{self._stage}"] += time.process_time() - self._cpu


@dataclasses.dataclass(frozen=True)
class ShapeTask:
    """What :meth:`MoveOptimizer.shape` shapes, and how a candidate is kept.

    Attributes:
        scene: The planning scene as the motion sees it.
        spline: The planner's path (the baseline, same ends).
        grasp: The held object's grasp constraint, None for a pick.
        family: The path family through ``via`` free via points.
        certify: None if a candidate path passes the final checks, else why not.
        tilt_bound: rad, the search's tilt bound (pi: none).
        span: The part of ``spline`` (s) whose clearance sets the search's
            clearance threshold (None: :class:`.Objective`'s default).
        starts: Warm starts from the library.
        played: The retime the motion is played with, from the path and
            its acceleration-limited retime (e.g. under jerk limits), or
            None: that retime itself. With it, the finish retimes each
            candidate so and keeps the fastest that beats the baseline's.
    """

    scene: PlanningScene
    spline: PlannedPath
    grasp: GraspConstraint | None
    family: Callable[[int], PathFamily]
    certify: Callable[[PathFamily, GeometricPath], str | None]
    tilt_bound: float
    span: tuple[float, float] | None
    starts: int
    played: Callable[[GeometricPath, RetimeResult], RetimeResult] | None = None


@dataclasses.dataclass
class Found:
    """The finish's kept candidate (``path`` None: none), and why others were not."""

    path: GeometricPath | None = None
    retimed: RetimeResult | None = None
    played: RetimeResult | None = None
    wall_s: float = 0.0
    rejected: list[str] = dataclasses.field(default_factory=list)


__all__ = ["Found", "ShapeTask", "StageClock"]
