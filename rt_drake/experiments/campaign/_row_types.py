"""What one row of a campaign is: its key, its variant and its results.

Plain data (no Drake), pickled between the driver and its workers:

- :class:`Variant`: the comparisons a campaign can run (a closed set; each
  has a function in :mod:`._variants`).
- :class:`RowKey`: the combination of one row: object, cup, seed, trial,
  variant (the primary key of the results table).
- :class:`Task`: a row to compute, as the driver sends it to a worker
  (light: a worker unpickles it before it loads the simulation).
- :class:`RowResult`: what a variant computed for it; :class:`Status` says
  whether it ran (``ok``), was infeasible (``infeasible``: a typed
  :class:`~rt_drake.errors.RtDrakeError`, e.g. the object slips off the cup
  even at rest), failed unexpectedly (``error``: a bug, recorded with its
  type and message) or lost its worker twice (``crashed``).
"""

from __future__ import annotations

import dataclasses
import enum
from typing import Any

from rt_drake.experiments.campaign._campaign_errors import CampaignError


class Variant(enum.Enum):
    """A comparison a campaign runs on every (object, cup, trial).

    - ``constrained``: the MOVE retimed under the exact grasp constraint,
      played in the physics at speed 1.
    - ``unconstrained``: the same path retimed under the joint limits
      only, played at speed 1.
    - ``speed_sweep``: the constrained MOVE played faster and faster
      (:data:`~rt_drake.experiments._rollout.SPEED_FACTORS`) until the object
      slips: the critical speed factor.
    - ``optimized``: the MOVE path optimised for speed from the same grasp
      to the same goal (:class:`~rt_drake.shaping.MoveOptimizer`),
      retimed under the exact grasp constraint, played at speed 1; its
      ratio to the spline path's duration is in the row's detail.
    - ``robust``: the spline MOVE retimed to hold every object of the
      object's uncertainty set with every cup of the cup's range, played
      with a hard true object of the set and the worst cup; the price
      (robust / nominal duration) is in the row's detail.
    """

    CONSTRAINED = "constrained"
    UNCONSTRAINED = "unconstrained"
    SPEED_SWEEP = "speed_sweep"
    OPTIMIZED = "optimized"
    ROBUST = "robust"

    @classmethod
    def parse(cls, text: str) -> Variant:
        """The variant called ``text``; CampaignError listing the known ones."""
        try:
            return cls(text)
        except ValueError:
            known = ", ".join(v.value for v in cls)
            raise CampaignError(f"unknown variant {text!r} (known: {known})") from None


class Status(enum.Enum):
    """How a row ended."""

    OK = "ok"
    INFEASIBLE = "infeasible"
    ERROR = "error"
    CRASHED = "crashed"


@dataclasses.dataclass(frozen=True)
class RowKey:
    """One row's combination; unique in a campaign's database."""

    object: str
    cup: str
    seed: int
    trial: int
    variant: Variant

    @property
    def sort_key(self) -> tuple[str, str, int, int, str]:
        """(object, cup, seed, trial, variant name): a total order of rows."""
        return (self.object, self.cup, self.seed, self.trial, self.variant.value)

    def __str__(self) -> str:
        return (
            f"{self.object}/{self.cup}/seed {self.seed}/trial {self.trial}/"
            f"{self.variant.value}"
        )


@dataclasses.dataclass(frozen=True)
class Task:
    """One row to compute: the campaign file, its content hash and the row.

    Defined here, beside :class:`RowKey`, so that unpickling it imports
    no Drake (:mod:`._worker` computes it).
    """

    campaign_path: str
    content_hash: str
    key: RowKey


@dataclasses.dataclass(frozen=True)
class RowResult:
    """What a variant computed for one row (None: does not apply).

    Attributes:
        status: How the row ended.
        duration_s: The retimed MOVE's duration played at speed 1, s.
        speed: The speed factor of the row's (last) rollout.
        success: The object moved less than 5 mm and 3 deg on the cup in
            that rollout.
        slip_translation_mm: Its largest slip, mm.
        slip_rotation_deg: Its largest turn on the cup, deg.
        critical_speed: ``speed_sweep``: the first factor that slipped
            (None: it held up to the last factor).
        plan_s: Wall time of planning and retiming, s.
        simulate_s: Wall time of the physics rollouts, s.
        error: ``TypeName: message`` for a failed row.
        detail: Variant-specific extras (JSON-serialisable), e.g. the sweep.
    """

    status: Status
    duration_s: float | None = None
    speed: float | None = None
    success: bool | None = None
    slip_translation_mm: float | None = None
    slip_rotation_deg: float | None = None
    critical_speed: float | None = None
    plan_s: float | None = None
    simulate_s: float | None = None
    error: str | None = None
    detail: dict[str, Any] = dataclasses.field(default_factory=dict)

    @classmethod
    def failed(
        cls, status: Status, error: BaseException | str, plan_s: float | None = None
    ) -> RowResult:
        """A row that did not finish: its status and one-line error."""
        if isinstance(error, BaseException):
            error = f"{type(error).__name__}: {' '.join(str(error).split())}"
        return cls(status=status, error=error, plan_s=plan_s)


@dataclasses.dataclass(frozen=True)
class Outcome:
    """A finished row as the driver stores it.

    Attributes:
        key: The row's combination.
        result: What its variant computed.
        wall_s: Wall time of the task in its worker, s (None: crashed).
        cpu_s: CPU time of the task in its worker, s (None: crashed); far
            below ``wall_s`` when the machine is shared.
        worker: ``host:pid`` of the worker that ran it last.
        code_version: rt_drake's version and git commit in that worker.
        attempts: How many times it was started (2 after a retried crash).
    """

    key: RowKey
    result: RowResult
    wall_s: float | None
    cpu_s: float | None
    worker: str
    code_version: str
    attempts: int = 1


__all__ = ["Outcome", "RowKey", "RowResult", "Status", "Variant"]
