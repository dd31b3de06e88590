"""A trial's MOVE, planned as the experiments plan it: shared by the bellows tools.

``tools/bellows_trial.py`` (plays it) and ``tools/bellows_margin.py`` (rings
the bellows with it) import it as ``from _bellows_common import trial_move``:
a script's own directory, tools/, is the first entry of ``sys.path``.
"""

from __future__ import annotations

import dataclasses

import numpy as np
from pydrake.math import RigidTransform

from rt_drake.experiments._transport_experiment import (
    played_move,
    transport_scenario,
)
from rt_drake.model.scenario import ObjectConfig, Scenario
from rt_drake.simulation import Motion, OnlineMotions


@dataclasses.dataclass(frozen=True)
class TrialMove:
    """One trial's planned MOVE and what planned it.

    Attributes:
        scenario: The scenario holding only the object, at the trial's poses.
        motions: The planner and retimer (seeded as the experiment's trial).
        obj: The carried object, at its sampled start.
        move: The MOVE, planned and retimed under the grasp constraint.
        q_grasp: (nq,) the arm's configuration at the grasp (rad).
    """

    scenario: Scenario
    motions: OnlineMotions
    obj: ObjectConfig
    move: Motion
    q_grasp: np.ndarray


def trial_move(
    scenario: Scenario,
    name: str,
    X_WO_start: RigidTransform,
    X_WO_goal: RigidTransform,
    seed: int,
    index: int,
    jerk_limits: bool,
    robust: bool = True,
) -> TrialMove:
    """Plan trial ``index``'s MOVE of ``name`` as ``experiment transport`` does.

    The planner's seed is ``seed + index``; the grasp is the object sealed
    on the cup at ``X_WO_start`` (``random_transport.start_on_cup``: the
    fastest grasp yaw flip) or APPROACH and REACH from home. ``robust``:
    retime for the object's uncertainty set, if it has one
    (:class:`~rt_drake.simulation.OnlineMotions`), else for the nominal object
    (as ``experiment transport --robust`` plans its nominal MOVE).

    Raises:
        PlanningError, RetimeError: the MOVE does not plan or retime.
    """
    planned = transport_scenario(scenario, name, X_WO_start, X_WO_goal)
    motions = OnlineMotions(
        planned,
        grasp_constraint=True,
        seed=seed + index,
        robust=robust,
        optimize=False,
        jerk_limits=jerk_limits,
    )
    obj = planned.objects[0]
    move = played_move(scenario, motions, obj, X_WO_start)
    assert move.planned is not None
    return TrialMove(planned, motions, obj, move, move.planned.q_start)
