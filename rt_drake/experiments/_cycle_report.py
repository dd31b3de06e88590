"""The cycle report: ``report.json`` and a Markdown table like the paper's Table II.

Per object: planning wall times (s) of APPROACH, REACH, MOVE and the MOVE
retime (the paper's rows, however much of them ran ahead); the plan on the
critical path (s the arm waited for planning, :mod:`rt_drake.simulation.motion`
defines the clock); execution times (s, simulated) of APPROACH, REACH,
ATTACH, MOVE and DETACH; the object's slip during MOVE (max translation mm,
max rotation deg) on what touches it (the bellows cup's lip, else the tool's
cup frame), its motion on the tool's cup frame (``on_tool``: the slip plus the
bellows' deflection) and its placement error at the goal; the
MOVE's guarantee (what its retiming holds: the nominal object, every object
of its uncertainty set, or none); and its total, execution plus the plan on
the critical path (planning sequentially, as the paper did, the whole plan
is on it). For the cycle: the totals and the picks per hour,
``objects / total_s * 3600``.

With the floors (:func:`~rt_drake.experiments.cycle_floor.cycle_floors`),
each object and the cycle also carry ``floor_s``, the least time the arm's
joint limits allow through the same configurations and vertical lines
without the grasp (the motion floor) plus the ATTACH and DETACH times as
run, and ``floor_ratio = total_s / floor_s``. What the grasp costs apart
from that: ``grasp_price_s``, the MOVE's path at the acceleration limits
retimed with the grasp less without it (shaped MOVEs only; the key is
left out where it was not computed), and its sum for the cycle.
"""

from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path
from typing import Any

from rt_drake.atomic_file import write_text_atomically
from rt_drake.experiments.cycle_floor import ObjectFloor
from rt_drake.simulation.motion import PlanTimes
from rt_drake.simulation.records import ObjectRecord
from rt_drake.types.phase import Phase

#: Keys of ``plan_s``: APPROACH and REACH (plan + retime), MOVE (plan), and
#: the MOVE's retime, as the paper's Table II.
PLAN_KEYS = ("approach", "reach", "move", "retime")
#: The phases of ``exec_s``, in order (keys: their values).
EXEC_PHASES = (Phase.APPROACH, Phase.REACH, Phase.ATTACH, Phase.MOVE, Phase.DETACH)
EXEC_KEYS = tuple(phase.value for phase in EXEC_PHASES)
#: The files :func:`write_report` writes into its directory.
REPORT_FILES = ("report.json", "report.md")


@dataclasses.dataclass(frozen=True)
class PlanSeconds:
    """Planning wall times (s) of one object, the paper's Table II rows.

    Attributes:
        approach: APPROACH, plan and retime.
        reach: REACH, plan and retime.
        move: MOVE, plan.
        retime: MOVE, retime.
    """

    approach: float
    reach: float
    move: float
    retime: float

    def total(self) -> float:
        """The sum, in the order of :data:`PLAN_KEYS`."""
        return sum(dataclasses.astuple(self))


@dataclasses.dataclass(frozen=True)
class Slip:
    """The object's largest displacement on the cup while attached."""

    max_translation_mm: float
    max_rotation_deg: float


@dataclasses.dataclass(frozen=True)
class PlacementError:
    """The object's distance from its goal pose after DETACH."""

    translation_mm: float
    rotation_deg: float


@dataclasses.dataclass(frozen=True)
class ObjectReport:
    """The report entry of one object (see the module docstring).

    Attributes:
        name: The object.
        plan_s: Planning wall times.
        exec_s: Simulated seconds of each phase of :data:`EXEC_PHASES`, in
            that order.
        slip: Its slip during MOVE, on the lip (rim cup: the cup frame).
        on_tool: Its motion during MOVE on the tool's cup frame: the slip
            plus the bellows' deflection.
        placement_error: Its error at the goal.
        plan_on_critical_path_s: Simulated seconds the arm waited for plans.
        move_suction_force_n: The vacuum's force when the MOVE started, N.
        guarantee: What the MOVE's retiming holds, in words.
        floor: Its motion floor, or None if not computed.
        grasp_price_s: What the grasp cost its MOVE's path, s (NaN: not
            computed; ``ObjectRecord.grasp_price_s``).
    """

    name: str
    plan_s: PlanSeconds
    exec_s: dict[Phase, float]
    slip: Slip
    placement_error: PlacementError
    plan_on_critical_path_s: float
    move_suction_force_n: float
    guarantee: str
    floor: ObjectFloor | None = None
    grasp_price_s: float = float("nan")
    on_tool: Slip = Slip(0.0, 0.0)

    @property
    def total_s(self) -> float:
        """Execution plus the plan on the critical path, s."""
        return self.plan_on_critical_path_s + sum(self.exec_s.values())

    @property
    def floor_s(self) -> float | None:
        """The motion floor plus ATTACH and DETACH as run, s (None: no floor)."""
        if self.floor is None:
            return None
        waits = self.exec_s.get(Phase.ATTACH, 0.0) + self.exec_s.get(Phase.DETACH, 0.0)
        return self.floor.motion_s + waits

    @property
    def floor_ratio(self) -> float | None:
        """``total_s / floor_s`` (None: no floor)."""
        floor = self.floor_s
        return None if floor is None or floor <= 0 else self.total_s / floor

    def as_dict(self) -> dict[str, Any]:
        """The entry of ``report.json`` (phases keyed by their values)."""
        return {
            "name": self.name,
            "plan_s": dataclasses.asdict(self.plan_s),
            "exec_s": {phase.value: s for phase, s in self.exec_s.items()},
            "slip": dataclasses.asdict(self.slip),
            "on_tool": dataclasses.asdict(self.on_tool),
            "placement_error": dataclasses.asdict(self.placement_error),
            "plan_on_critical_path_s": self.plan_on_critical_path_s,
            "move_suction_force_n": self.move_suction_force_n,
            "guarantee": self.guarantee,
            "total_s": self.total_s,
            **self._floor_dict(),
            **_if_finite("grasp_price_s", self.grasp_price_s),
        }

    def _floor_dict(self) -> dict[str, Any]:
        if self.floor is None:
            return {}
        segments = dataclasses.asdict(self.floor)
        del segments["name"]
        return {
            "floor_s": self.floor_s,
            "floor_ratio": self.floor_ratio,
            "floor_segments_s": segments,
        }


@dataclasses.dataclass(frozen=True)
class RunSettings:
    """How the cycle was run (``rt-drake run``'s flags and what it measured).

    Attributes:
        scenario: The scenario file.
        grasp_constraint: Whether the MOVEs were retimed under the grasp.
        speed: The MOVEs' speed factor.
        pipelined_planning: Whether planning ran ahead of execution.
        vacuum: The vacuum model (``fixed``, ``first_order``).
        time_step_s: The simulation step, s.
        sim_time_s: Simulated time of the whole cycle, s.
        max_tracking_error_rad: The arm's largest tracking error, rad.
        simulation_wall_s: Wall time of the simulation, s.
        cup_physics: The simulated cup (``rim``, ``bellows``).
    """

    scenario: str
    grasp_constraint: bool
    speed: float
    pipelined_planning: bool
    vacuum: str
    time_step_s: float
    sim_time_s: float
    max_tracking_error_rad: float
    simulation_wall_s: float
    cup_physics: str = "rim"


@dataclasses.dataclass(frozen=True)
class CycleReport:
    """The whole report: one entry per object, the totals, how it was run.

    ``total_s`` and ``plan_on_critical_path_s`` sum the objects';
    ``mean_cycle_s`` is ``total_s`` per object and ``picks_per_hour``
    ``objects / total_s * 3600``.
    """

    objects: tuple[ObjectReport, ...]
    run: RunSettings | None = None

    @property
    def total_s(self) -> float:
        """Execution plus the plan on the critical path, all objects, s."""
        return math.fsum(o.total_s for o in self.objects)

    @property
    def plan_on_critical_path_s(self) -> float:
        """Simulated seconds the arm waited for plans, all objects."""
        return math.fsum(o.plan_on_critical_path_s for o in self.objects)

    @property
    def mean_cycle_s(self) -> float:
        """``total_s`` per object (NaN without objects)."""
        n = len(self.objects)
        return self.total_s / n if n else float("nan")

    @property
    def floor_s(self) -> float | None:
        """The objects' floors summed, s (None if any is missing)."""
        floors = [o.floor_s for o in self.objects]
        if not floors or any(f is None for f in floors):
            return None
        return math.fsum(f for f in floors if f is not None)

    @property
    def floor_ratio(self) -> float | None:
        """``total_s / floor_s`` for the cycle (None: no floor)."""
        floor = self.floor_s
        return None if floor is None or floor <= 0 else self.total_s / floor

    @property
    def grasp_price_s(self) -> float:
        """The objects' ``grasp_price_s`` summed, s (NaN if any is missing)."""
        return math.fsum(o.grasp_price_s for o in self.objects)

    @property
    def picks_per_hour(self) -> float:
        """``objects / total_s * 3600`` (0 if no time passed)."""
        total = self.total_s
        return 3600.0 * len(self.objects) / total if total > 0 else 0.0

    def as_dict(self) -> dict[str, Any]:
        """The content of ``report.json``: objects, totals, then the settings."""
        return {
            "objects": [o.as_dict() for o in self.objects],
            "total_s": self.total_s,
            "plan_on_critical_path_s": self.plan_on_critical_path_s,
            "mean_cycle_s": self.mean_cycle_s,
            "picks_per_hour": self.picks_per_hour,
            **(
                {}
                if self.floor_s is None
                else {"floor_s": self.floor_s, "floor_ratio": self.floor_ratio}
            ),
            **_if_finite("grasp_price_s", self.grasp_price_s),
            **({} if self.run is None else dataclasses.asdict(self.run)),
        }

    def to_json(self) -> str:
        """The text of ``report.json`` (indented, with a final newline)."""
        return json.dumps(self.as_dict(), indent=2) + "\n"


def object_report(
    record: ObjectRecord, floor: ObjectFloor | None = None
) -> ObjectReport:
    """The report entry of one object (see the module docstring)."""
    times = record.plan_times
    none = PlanTimes()
    return ObjectReport(
        name=record.name,
        plan_s=PlanSeconds(
            approach=times.get(Phase.APPROACH, none).total_s,
            reach=times.get(Phase.REACH, none).total_s,
            move=times.get(Phase.MOVE, none).plan_s,
            retime=times.get(Phase.MOVE, none).retime_s,
        ),
        exec_s={phase: record.exec_s.get(phase, 0.0) for phase in EXEC_PHASES},
        slip=Slip(
            max_translation_mm=1000.0 * record.max_slip_translation,
            max_rotation_deg=math.degrees(record.max_slip_rotation),
        ),
        on_tool=Slip(
            max_translation_mm=1000.0 * record.max_on_tool_translation,
            max_rotation_deg=math.degrees(record.max_on_tool_rotation),
        ),
        placement_error=PlacementError(
            translation_mm=1000.0 * record.placement_translation,
            rotation_deg=math.degrees(record.placement_rotation),
        ),
        plan_on_critical_path_s=record.plan_on_critical_path_s,
        move_suction_force_n=record.move_suction_force,
        guarantee=record.guarantee,
        floor=floor,
        grasp_price_s=record.grasp_price_s,
    )


def cycle_report(
    records: tuple[ObjectRecord, ...],
    run: RunSettings | None = None,
    floors: tuple[ObjectFloor, ...] | None = None,
) -> CycleReport:
    """The whole report of ``records`` (see :class:`CycleReport`).

    ``floors``: the objects' motion floors (matched by name), or None.
    """
    by_name = {f.name: f for f in floors or ()}
    return CycleReport(
        tuple(object_report(r, by_name.get(r.name)) for r in records), run
    )


def table_markdown(report: CycleReport) -> str:
    """Table II of the paper for this run: one column per object."""
    objects = report.objects
    header = "| | " + " | ".join(o.name for o in objects) + " |"
    rule = "|---|" + "---:|" * len(objects)
    rows = [header, rule]

    def row(label: str, values: list[float], fmt: str = "{:.3f}") -> None:
        rows.append(f"| {label} | " + " | ".join(fmt.format(v) for v in values) + " |")

    for key, label in zip(
        PLAN_KEYS,
        ("APPROACH plan", "REACH plan", "MOVE plan", "MOVE retime"),
        strict=True,
    ):
        row(label, [getattr(o.plan_s, key) for o in objects])
    row("**Total plan**", [o.plan_s.total() for o in objects])
    row("plan on critical path", [o.plan_on_critical_path_s for o in objects])
    for phase in EXEC_PHASES:
        key = phase.value
        label = (
            f"{key.upper()} delay"
            if phase in (Phase.ATTACH, Phase.DETACH)
            else f"{key.upper()} exec."
        )
        row(label, [o.exec_s[phase] for o in objects])
    row("**Total exec.**", [sum(o.exec_s.values()) for o in objects])
    row("**Total (critical plan + exec.)**", [o.total_s for o in objects])
    row("slip (mm)", [o.slip.max_translation_mm for o in objects], "{:.2f}")
    row("slip (deg)", [o.slip.max_rotation_deg for o in objects], "{:.2f}")
    row("on tool (mm)", [o.on_tool.max_translation_mm for o in objects], "{:.2f}")
    row("on tool (deg)", [o.on_tool.max_rotation_deg for o in objects], "{:.2f}")
    row(
        "placement error (mm)",
        [o.placement_error.translation_mm for o in objects],
        "{:.1f}",
    )
    row(
        "placement error (deg)",
        [o.placement_error.rotation_deg for o in objects],
        "{:.1f}",
    )
    if report.floor_s is not None:
        row("floor (joint limits, no grasp)", [o.floor_s or 0.0 for o in objects])
        row("floor ratio (total / floor)", [o.floor_ratio or 0.0 for o in objects])
    if any(math.isfinite(o.grasp_price_s) for o in objects):
        row("grasp price (MOVE, acc. limits)", [o.grasp_price_s for o in objects])
    return "\n".join(rows) + "\n"


def summary_line(report: CycleReport) -> str:
    """``4 objects in 17.2 s: 4.30 s per object, 837 picks per hour ...``."""
    n = len(report.objects)
    return (
        f"{n} objects in {report.total_s:.3f} s: {report.mean_cycle_s:.3f} s "
        f"per object, {report.picks_per_hour:.0f} picks per hour; plan on the "
        f"critical path {report.plan_on_critical_path_s:.3f} s"
        + (
            ""
            if report.floor_s is None or report.floor_ratio is None
            else f"; floor {report.floor_s / n:.3f} s per object, "
            f"{report.floor_ratio:.3f}x of it"
        )
    )


def _if_finite(key: str, value: float) -> dict[str, float]:
    """``{key: value}``, or nothing if ``value`` is NaN (not computed)."""
    return {} if math.isnan(value) else {key: value}


def write_report(report: CycleReport, out_dir: Path) -> tuple[Path, Path]:
    """Write ``report.json`` and ``report.md`` into ``out_dir``; return both paths.

    Each file is written atomically (:mod:`rt_drake.atomic_file`).
    """
    json_path = out_dir / REPORT_FILES[0]
    md_path = out_dir / REPORT_FILES[1]
    write_text_atomically(json_path, report.to_json())
    lines = [
        "# Pick-and-place cycle",
        "",
        "Times in seconds: planning is wall time on this machine, execution is",
        "simulated time. Slip: the object's largest displacement relative to the",
        "cup while attached. Total = the plan on the critical path (what the arm",
        "waited for planning) + exec.; planned sequentially, as in the paper's",
        "Table II, all of the plan is on the critical path.",
        "",
        table_markdown(report),
        summary_line(report),
        "",
        "What each MOVE's retiming guarantees the cup holds:",
        "",
        *(f"- {o.name}: {o.guarantee or '-'}" for o in report.objects),
    ]
    write_text_atomically(md_path, "\n".join(lines) + "\n")
    return json_path, md_path


__all__ = [
    "EXEC_KEYS",
    "EXEC_PHASES",
    "REPORT_FILES",
    "PLAN_KEYS",
    "CycleReport",
    "ObjectReport",
    "PlacementError",
    "PlanSeconds",
    "RunSettings",
    "Slip",
    "cycle_report",
    "object_report",
    "summary_line",
    "table_markdown",
    "write_report",
]
