"""A Drake LeafSystem that retimes each new path it is given.

It is a thin wrapper of :func:`rt_drake.retiming.retime`: every request that
arrives on its input is retimed once, in an unrestricted-update event, and the
result kept in the Context's abstract state; the outputs read that state.
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.multibody.plant import MultibodyPlant
from pydrake.systems.framework import BasicVector, Context, LeafSystem, State

from rt_drake.dynamics.cup_frame import CupFrame
from rt_drake.errors import InputError
from rt_drake.retiming import (
    GraspConstraint,
    JointLimits,
    RetimeResult,
    retime,
    warm_up,
)


@dataclasses.dataclass(frozen=True, eq=False)
class RetimeRequest:
    """A path to retime, what is held, and when to start (s; None: on arrival).

    ``request_id`` (> 0) is the sender's number for the request: the
    :class:`Retimer` retimes a request whose id differs from the last one it
    handled (the port's value is copied on its way, so identity cannot tell).
    The sender numbers its requests, e.g. 1, 2, 3.
    """

    path: Any
    request_id: int
    grasp: GraspConstraint | None = None
    start_time: float | None = None

    def __post_init__(self) -> None:
        if self.request_id <= 0:
            raise InputError(f"request_id must be > 0, got {self.request_id}")


@dataclasses.dataclass(frozen=True, eq=False)
class RetimerState:
    """The Retimer's abstract state: the last request handled and its result."""

    request_id: int = 0
    result: RetimeResult | None = None


class Retimer(LeafSystem):
    """Retimes paths time-optimally under joint limits and grasp stability.

    .. pydrake_system::

        name: Retimer
        input_ports:
        - request
        output_ports:
        - trajectory
        - desired_state

    - ``request``: abstract, a :class:`RetimeRequest` or None.
    - ``trajectory``: abstract, the timed q(t) (``TimedPath``) of the last
      request, or None before the first.
    - ``desired_state``: ``[q; v]`` (rad, rad/s), 2n, of that trajectory at
      the context time (its end points held outside its time span);
      ``[q_initial; 0]`` before the first request.

    State: one abstract :class:`RetimerState`, changed only by a per-step
    unrestricted update that calls :func:`rt_drake.retiming.retime` when the
    request's ``request_id`` differs from the last one handled. A request
    that cannot be retimed raises its ``RetimeError`` from the simulator.

    Args:
        plant: Finalized arm-and-tool plant (see ``retime``); not modified.
        limits: Joint limits.
        q_initial: (n,) configuration held before the first request (rad).
        gridpoints: TOPP-RA grid size.
        cup: The cup frame C (default: the plant's ``suction_cup``).
    """

    def __init__(
        self,
        plant: MultibodyPlant,
        limits: JointLimits,
        q_initial: np.ndarray,
        gridpoints: int = 100,
        cup: CupFrame | None = None,
    ) -> None:
        super().__init__()
        self._plant = plant
        self._cup = cup or CupFrame.of(plant)
        self._limits = limits
        self._gridpoints = gridpoints
        self._q_initial = np.array(q_initial, dtype=float)
        n = plant.num_positions()
        if self._q_initial.shape != (n,):
            raise InputError(f"{self._q_initial.shape=} but {n=} positions")
        warm_up()  # compile the retimer's kernels now, not in the first event
        self._request_port = self.DeclareAbstractInputPort(
            "request", AbstractValue.Make(None)
        )
        self._state_index = self.DeclareAbstractState(
            AbstractValue.Make(RetimerState())
        )
        self._trajectory_port = self.DeclareAbstractOutputPort(
            "trajectory",
            lambda: AbstractValue.Make(None),
            self._CalcTrajectory,
            prerequisites_of_calc={self.abstract_state_ticket(self._state_index)},
        )
        self._desired_state_port = self.DeclareVectorOutputPort(
            "desired_state", 2 * n, self._CalcDesiredState
        )
        self.DeclarePerStepUnrestrictedUpdateEvent(self._Update)

    def get_request_input_port(self):
        """The ``request`` input port."""
        return self._request_port

    def get_trajectory_output_port(self):
        """The ``trajectory`` output port."""
        return self._trajectory_port

    def get_desired_state_output_port(self):
        """The ``desired_state`` output port."""
        return self._desired_state_port

    def _Update(self, context: Context, state: State) -> None:
        request = (
            self._request_port.Eval(context)
            if self._request_port.HasValue(context)
            else None
        )
        current = context.get_abstract_state(self._state_index).get_value()
        if request is None or request.request_id == current.request_id:
            return
        start = context.get_time() if request.start_time is None else request.start_time
        result = retime(
            self._plant,
            request.path,
            self._limits,
            request.grasp,
            self._gridpoints,
            start_time=start,
            cup=self._cup,
        )
        state.get_mutable_abstract_state(self._state_index).set_value(
            RetimerState(request.request_id, result)
        )

    def _CalcTrajectory(self, context: Context, output: AbstractValue) -> None:
        result = context.get_abstract_state(self._state_index).get_value().result
        output.set_value(None if result is None else result.trajectory)

    def _CalcDesiredState(self, context: Context, output: BasicVector) -> None:
        result = context.get_abstract_state(self._state_index).get_value().result
        if result is None:
            output.SetFromVector(np.concatenate([self._q_initial, 0 * self._q_initial]))
            return
        q, v = result.trajectory.sample(context.get_time(), order=1)
        output.SetFromVector(np.concatenate([q[0], v[0]]))


__all__ = ["RetimeRequest", "Retimer", "RetimerState"]
