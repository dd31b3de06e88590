"""Play a MOVE in the physics of the cycle and measure how the object slips.

A rollout runs the cycle's Diagram (the station and sequencer of ``rt-drake
run``) for one object: the arm starts at the grasp, the valve is on for the
attach wait, then the MOVE runs. An object that starts on the cup
(``random_transport.start_on_cup``) starts held: under the bellows cup at
rest on the bellows stretched by its weight, sealed, the valve on from t = 0
(:mod:`rt_drake.simulation._held_start`), not dropped onto relaxed bellows.
It succeeds when, during the MOVE, the object moves less than
:data:`SLIP_TRANSLATION` and turns less than :data:`SLIP_ROTATION` relative
to what touches it: the bellows cup's lip (``cup_physics: bellows``), else
the tool's cup frame. Its motion relative to the tool's cup frame (the slip
plus the bellows' elastic deflection; the slip itself under the rim cup) is
reported beside it. :func:`critical_speed` plays a MOVE faster and faster
until it slips (the paper saw slip at 120-140 %).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence

import numpy as np
from pydrake.geometry import Meshcat
from pydrake.multibody.tree import SpatialInertia
from pydrake.trajectories import PiecewisePolynomial, Trajectory

from rt_drake.model.scenario import (
    ObjectConfig,
    Scenario,
)
from rt_drake.model.vacuum import Vacuum
from rt_drake.retiming import TimeScaled
from rt_drake.simulation import UPDATE_PERIOD, Motion, run_cycle

#: m and rad: a rollout slipped if the object moved more on the cup.
SLIP_TRANSLATION = 5e-3
SLIP_ROTATION = math.radians(3.0)
#: Speed factors of the sweep, in order; the first one that slips is critical.
SPEED_FACTORS = (1.0, 1.1, 1.2, 1.3, 1.4, 1.6, 1.8, 2.0, 2.5, 3.0)
#: s, the attach and detach waits of a rollout (shorter than a cycle's 1 s).
ROLLOUT_WAIT_S = 0.3


@dataclasses.dataclass(frozen=True)
class Rollout:
    """One simulated MOVE: its slip (m, rad) and whether it stayed put.

    ``slip_*``: the object's largest motion on the lip (the rim cup: on the
    tool's cup frame); ``on_tool_*``: on the tool's cup frame, the slip plus
    the bellows' deflection.
    """

    slip_translation: float
    slip_rotation: float
    on_tool_translation: float = 0.0
    on_tool_rotation: float = 0.0

    @property
    def success(self) -> bool:
        """Slip under 5 mm and 3 deg."""
        return (
            self.slip_translation < SLIP_TRANSLATION
            and self.slip_rotation < SLIP_ROTATION
        )

    def as_dict(self) -> dict[str, float]:
        """``max_translation_mm``, ``max_rotation_deg`` (the slip), and on the tool."""
        return {
            "max_translation_mm": 1e3 * self.slip_translation,
            "max_rotation_deg": math.degrees(self.slip_rotation),
            "on_tool_translation_mm": 1e3 * self.on_tool_translation,
            "on_tool_rotation_deg": math.degrees(self.on_tool_rotation),
        }


class Replay:
    """A MotionSource that stands at the grasp, then plays a given MOVE."""

    def __init__(self, q_grasp: np.ndarray, move: Trajectory) -> None:
        self._hold = PiecewisePolynomial.ZeroOrderHold(
            [0.0, UPDATE_PERIOD], np.column_stack([q_grasp, q_grasp])
        )
        self._move = move

    def pick(  # noqa: D102
        self, q_start: np.ndarray, obj: ObjectConfig, retreat: bool
    ) -> Motion:
        return Motion(self._hold)

    def move(  # noqa: D102
        self, q_start: np.ndarray, obj: ObjectConfig, pick: Motion | None
    ) -> Motion:
        return Motion(self._move)


def rollout_scenario(trial: Scenario, q_grasp: np.ndarray) -> Scenario:
    """The ``trial`` scenario (object at its sampled start), the arm at the grasp.

    The attach and detach waits are shortened to :data:`ROLLOUT_WAIT_S`.
    """
    return dataclasses.replace(
        trial,
        robot=dataclasses.replace(trial.robot, home=[float(q) for q in q_grasp]),
        vacuum=Vacuum(attach_s=ROLLOUT_WAIT_S, detach_s=ROLLOUT_WAIT_S),
    )


def simulate_move(
    scenario: Scenario,
    q_grasp: np.ndarray,
    move: Trajectory,
    speed: float = 1.0,
    meshcat: Meshcat | None = None,
    object_inertias: dict[str, SpatialInertia] | None = None,
) -> Rollout:
    """Play ``move`` (``speed`` times faster) in the cycle's physics; measure slip.

    With ``meshcat``, the run is recorded there for an offline replay
    (``meshcat.StaticHtml()``). ``object_inertias``: the objects' true
    inertias, if not their models' (:func:`~rt_drake.simulation.run_cycle`).
    An object that starts on the cup (``random_transport.start_on_cup``)
    starts held: under the bellows cup, sealed and at rest on the stretched
    bellows, as a pick leaves it (``run_cycle``'s ``held_at_start``).
    """
    trajectory = move if speed == 1.0 else TimeScaled(move, speed)
    transport = scenario.random_transport
    result = run_cycle(
        scenario,
        Replay(q_grasp, trajectory),
        meshcat=meshcat,
        max_sim_time=30.0,
        object_inertias=object_inertias,
        held_at_start=transport is not None and transport.start_on_cup,
    )
    (record,) = result.records
    return Rollout(
        record.max_slip_translation,
        record.max_slip_rotation,
        record.max_on_tool_translation,
        record.max_on_tool_rotation,
    )


def critical_speed(
    scenario: Scenario,
    q_grasp: np.ndarray,
    move: Trajectory,
    factors: Sequence[float] = SPEED_FACTORS,
    object_inertias: dict[str, SpatialInertia] | None = None,
) -> tuple[float | None, list[tuple[float, Rollout]]]:
    """The first factor of ``factors`` at which the object slips (None: never).

    ``object_inertias``: the objects' true inertias, as in :func:`simulate_move`.
    """
    sweep: list[tuple[float, Rollout]] = []
    for factor in factors:
        rollout = simulate_move(
            scenario, q_grasp, move, factor, object_inertias=object_inertias
        )
        sweep.append((factor, rollout))
        if not rollout.success:
            return factor, sweep
    return None, sweep


__all__ = [
    "ROLLOUT_WAIT_S",
    "SLIP_ROTATION",
    "SLIP_TRANSLATION",
    "SPEED_FACTORS",
    "Replay",
    "Rollout",
    "critical_speed",
    "rollout_scenario",
    "simulate_move",
]
