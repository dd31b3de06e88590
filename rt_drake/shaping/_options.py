"""Options and result of :func:`rt_drake.shaping.optimize_move`."""

from __future__ import annotations

import dataclasses
from typing import Protocol

import numpy as np
from pydrake.math import RigidTransform

from rt_drake import arguments
from rt_drake.errors import InputError
from rt_drake.model.scenario import MOVE_EVALUATIONS, PlanningConfig
from rt_drake.planning.result import PlannedPath
from rt_drake.planning.scene import PlanningScene
from rt_drake.retiming import RetimeResult
from rt_drake.types.path import GeometricPath
from rt_drake.types.phase import Phase

#: deg: the tilt allowed when ``max_tilt_deg`` is 0 (cup kept vertical).
VERTICAL_TOLERANCE_DEG = 0.5
#: m: largest horizontal drift of the cup along a vertical end segment.
VERTICAL_DRIFT = 1e-3


class MoveOptimizerError(InputError):
    """Bad optimiser options (an :class:`~rt_drake.errors.InputError`)."""


class MovePlanner(Protocol):
    """What :func:`optimize_move` uses of the cycle planner (CyclePlanner)."""

    scene: PlanningScene

    def plan_move(
        self,
        q_grasp: np.ndarray,
        name: str,
        X_WO_goal: RigidTransform | None = None,
        reach: PlannedPath | None = None,
    ) -> PlannedPath:
        """The spline MOVE of ``name`` from ``q_grasp`` (scene left prepared)."""

    def prepare(
        self,
        phase: Phase,
        name: str,
        q_start: np.ndarray,
        X_OC: RigidTransform | None = None,
    ) -> PlanningScene:
        """Set the scene's objects for a phase (MOVE: ``name`` carried at X_OC)."""


@dataclasses.dataclass(frozen=True)
class MoveOptimizerOptions:
    """Settings of :func:`optimize_move`.

    Attributes:
        max_tilt_deg: Largest angle (deg) between the cup axis and gravity on
            the path; 0 keeps the cup vertical (within 0.5 deg).
        max_evaluations: The search's budget: CMA-ES stops before the first
            generation that starts with this many candidate paths scored
            (the starts included). No clock is read: the same spline path
            and seed give the same path on an idle or a loaded machine.
        vertical_height: Length (m) of the vertical segment at each end.
        vertical_points: Waypoints on each vertical segment.
        via_points: Free via points K (n K parameters); if the search finds
            no feasible path, the paths through K + 1 and K + 2 of the spline
            path's corners are tried.
        joint_scale: rad per unit of the search's parameters (one for all
            joints, or one per joint).
        sigma: CMA-ES's initial step size (units of the parameters; 0.2
            and 240 paths, against 0.5 and 200 before, brought the shaped
            MOVE from 1.9-2.8 % to 1.5-2.0 % of the KTO reference solved
            from the earlier paths, BENCHMARKS.md).
        search_gridpoints: Points of the search's TOPP-RA grid.
        search_grid_weight: Where they are: at equal steps of the measure
            of :func:`~._finish.adaptive_grid` with this weight w (1: equal
            steps of time) along the spline path's retimed profile; None:
            uniform in s.
        search_end_points: E, each candidate's own grid points over each
            of its vertical ends (:class:`~._surrogate.EndGrid`; 0, the
            default: none, the search grid is the same for all candidates;
            4 gave +2.81 % and +2.20 % against the KTO reference on seeds
            1 and 11, against +2.78 % and +2.58 %, BENCHMARKS.md).
        search_end_span: f, each end span as a multiple of the vertical
            segment's share of s.
        final_gridpoints: Points of the final adaptive grid
            (:func:`~._finish.retime_adaptive`).
        starts: Warm starts from the library (:mod:`._starts`) evaluated
            with x = 0 before the search (0: none).
        clearance_margin: Clearance (m) the search keeps (estimate).
        population: CMA-ES's candidates per generation (default 4 + 3 ln d).
        seed: Seed of CMA-ES.
        finish_tries: The finish checks and retimes at most this many of the
            best candidates, best first.
    """

    max_tilt_deg: float = 45.0
    max_evaluations: int = MOVE_EVALUATIONS
    vertical_height: float = 0.03
    vertical_points: int = 2
    via_points: int = 2
    joint_scale: float | tuple[float, ...] = 0.1
    sigma: float = 0.2
    search_gridpoints: int = 24
    search_grid_weight: float | None = 1.0
    search_end_points: int = 0
    search_end_span: float = 3.0
    final_gridpoints: int = 400
    clearance_margin: float = 0.01
    population: int | None = None
    seed: int = 0
    starts: int = 12
    finish_tries: int = 3

    def __post_init__(self) -> None:
        for field in dataclasses.fields(self):
            value = getattr(self, field.name)
            if field.name == "joint_scale" or value is None:
                continue
            arguments.number(
                value,
                field.name,
                where="MoveOptimizerOptions",
                error=MoveOptimizerError,
            )
        arguments.array(
            self.joint_scale,
            "joint_scale",
            ("...",),
            where="MoveOptimizerOptions",
            error=MoveOptimizerError,
        )
        checks = {
            "max_tilt_deg": 0.0 <= self.max_tilt_deg < 90.0,
            "max_evaluations": self.max_evaluations >= 1,
            "vertical_height": self.vertical_height > 0.0,
            "vertical_points": self.vertical_points >= 1,
            "via_points": self.via_points >= 1,
            "joint_scale": bool(np.all(np.asarray(self.joint_scale) > 0.0)),
            "sigma": self.sigma > 0.0,
            "search_gridpoints": self.search_gridpoints >= 4,
            "search_grid_weight": self.search_grid_weight is None
            or 0.0 <= self.search_grid_weight <= 1.0,
            "search_end_points": self.search_end_points >= 0,
            "search_end_span": self.search_end_span >= 1.0,
            "final_gridpoints": self.final_gridpoints >= 4,
            "clearance_margin": self.clearance_margin >= 0.0,
            "starts": self.starts >= 0,
            "finish_tries": self.finish_tries >= 1,
        }
        for name, ok in checks.items():
            if not ok:
                raise MoveOptimizerError(
                    f"MoveOptimizerOptions.{name} out of range: {getattr(self, name)!r}"
                )

    @classmethod
    def from_config(cls, planning: PlanningConfig) -> MoveOptimizerOptions:
        """The defaults with a scenario's ``planning`` tilt and evaluation budget."""
        return cls(
            max_tilt_deg=planning.max_tilt_deg,
            max_evaluations=planning.max_evaluations,
        )

    @property
    def tilt_bound(self) -> float:
        """rad: the tilt the path may reach (0.5 deg for max_tilt_deg 0)."""
        return float(np.radians(max(self.max_tilt_deg, VERTICAL_TOLERANCE_DEG)))


@dataclasses.dataclass(frozen=True)
class OptimizedMove:
    """Result of :func:`optimize_move`.

    Attributes:
        path: The returned path (the spline path if ``improved`` is False).
        retimed: Its retime under the grasp constraint (adaptive grid).
        spline: The planner's spline MOVE.
        spline_retimed: The spline path's retime on the same scheme.
        improved: Whether ``path`` is an optimised one.
        max_tilt_deg: Largest cup tilt along ``path`` (deg).
        evaluations: Candidate paths the search scored.
        wall_s: Wall time (s) of the optimisation (spline planning excluded).
        cpu_s: This process's CPU time (s) over the same span.
        retime_wall_s: Wall time (s) of the retime of ``path`` (part of
            ``wall_s``; the baseline's if ``path`` is the spline path).
        timings: Wall time (s) per stage (:mod:`._optimizer`), and this
            process's CPU time (s) per stage (``cpu_`` + stage).
        rejected: Why better candidates were turned down in the finish.
        played: The retime ``path`` is played with, if the shaping was
            given one (the pick's: under the jerk limits); None: ``retimed``.
        spline_played: The spline path's retime likewise.
    """

    path: GeometricPath
    retimed: RetimeResult
    spline: PlannedPath
    spline_retimed: RetimeResult
    improved: bool
    max_tilt_deg: float
    evaluations: int
    wall_s: float
    cpu_s: float
    retime_wall_s: float
    timings: dict[str, float]
    rejected: tuple[str, ...] = ()
    played: RetimeResult | None = None
    spline_played: RetimeResult | None = None

    @property
    def duration(self) -> float:
        """s, duration of the returned path."""
        return self.retimed.duration

    @property
    def spline_duration(self) -> float:
        """s, duration of the spline path (same retime scheme)."""
        return self.spline_retimed.duration


__all__ = [
    "MoveOptimizerError",
    "MoveOptimizerOptions",
    "MovePlanner",
    "OptimizedMove",
    "VERTICAL_DRIFT",
    "VERTICAL_TOLERANCE_DEG",
]
