"""The cycle report: ``report.json`` and a Markdown table like the paper's Table II.

Per object: planning wall times (s) of APPROACH, REACH, MOVE and the MOVE
retime (the paper's rows, however much of them ran ahead); the plan on the
critical path (s the arm waited for planning, :mod:`rt_drake.simulation.motion`
defines the clock); execution times (s, simulated) of APPROACH, REACH,
ATTACH, MOVE and DETACH; the object's slip on the cup while attached (max
translation mm, max rotation deg) and its placement error at the goal; the
MOVE's guarantee (what its retiming holds: the nominal object, every object
of its uncertainty set, or none); and its total, execution plus the plan on
the critical path (planning sequentially, as the paper did, the whole plan
is on it). For the cycle: the totals and the picks per hour,
``objects / total_s * 3600``.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

from rt_drake.atomic_file import write_text_atomically
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


def object_report(record: ObjectRecord) -> dict[str, Any]:
    """The report entry of one object (see the module docstring)."""
    times = record.plan_times
    none = PlanTimes()
    plan_s = {
        "approach": times.get(Phase.APPROACH, none).total_s,
        "reach": times.get(Phase.REACH, none).total_s,
        "move": times.get(Phase.MOVE, none).plan_s,
        "retime": times.get(Phase.MOVE, none).retime_s,
    }
    exec_s = {phase.value: record.exec_s.get(phase, 0.0) for phase in EXEC_PHASES}
    return {
        "name": record.name,
        "plan_s": plan_s,
        "exec_s": exec_s,
        "slip": {
            "max_translation_mm": 1000.0 * record.max_slip_translation,
            "max_rotation_deg": math.degrees(record.max_slip_rotation),
        },
        "placement_error": {
            "translation_mm": 1000.0 * record.placement_translation,
            "rotation_deg": math.degrees(record.placement_rotation),
        },
        "plan_on_critical_path_s": record.plan_on_critical_path_s,
        "move_suction_force_n": record.move_suction_force,
        "guarantee": record.guarantee,
        "total_s": record.plan_on_critical_path_s + sum(exec_s.values()),
    }


def cycle_report(records: tuple[ObjectRecord, ...], **extra: Any) -> dict[str, Any]:
    """The whole report: ``objects`` (one entry each), totals, ``extra``.

    ``total_s`` and ``plan_on_critical_path_s`` sum the objects';
    ``mean_cycle_s`` is ``total_s`` per object and ``picks_per_hour``
    ``objects / total_s * 3600``.
    """
    objects = [object_report(r) for r in records]
    total = math.fsum(o["total_s"] for o in objects)
    return {
        "objects": objects,
        "total_s": total,
        "plan_on_critical_path_s": math.fsum(
            o["plan_on_critical_path_s"] for o in objects
        ),
        "mean_cycle_s": total / len(objects) if objects else float("nan"),
        "picks_per_hour": 3600.0 * len(objects) / total if total > 0 else 0.0,
        **extra,
    }


def table_markdown(report: dict[str, Any]) -> str:
    """Table II of the paper for this run: one column per object."""
    objects = report["objects"]
    header = "| | " + " | ".join(o["name"] for o in objects) + " |"
    rule = "|---|" + "---:|" * len(objects)
    rows = [header, rule]

    def row(label: str, values: list[float], fmt: str = "{:.3f}") -> None:
        rows.append(f"| {label} | " + " | ".join(fmt.format(v) for v in values) + " |")

    for key, label in zip(
        PLAN_KEYS,
        ("APPROACH plan", "REACH plan", "MOVE plan", "MOVE retime"),
        strict=True,
    ):
        row(label, [o["plan_s"][key] for o in objects])
    row("**Total plan**", [sum(o["plan_s"].values()) for o in objects])
    row("plan on critical path", [o["plan_on_critical_path_s"] for o in objects])
    for key in EXEC_KEYS:
        label = (
            f"{key.upper()} exec."
            if key not in ("attach", "detach")
            else f"{key.upper()} delay"
        )
        row(label, [o["exec_s"][key] for o in objects])
    row("**Total exec.**", [sum(o["exec_s"].values()) for o in objects])
    row("**Total (critical plan + exec.)**", [o["total_s"] for o in objects])
    row("slip (mm)", [o["slip"]["max_translation_mm"] for o in objects], "{:.2f}")
    row("slip (deg)", [o["slip"]["max_rotation_deg"] for o in objects], "{:.2f}")
    row(
        "placement error (mm)",
        [o["placement_error"]["translation_mm"] for o in objects],
        "{:.1f}",
    )
    row(
        "placement error (deg)",
        [o["placement_error"]["rotation_deg"] for o in objects],
        "{:.1f}",
    )
    return "\n".join(rows) + "\n"


def summary_line(report: dict[str, Any]) -> str:
    """``4 objects in 17.2 s: 4.30 s per object, 837 picks per hour ...``."""
    n = len(report["objects"])
    return (
        f"{n} objects in {report['total_s']:.3f} s: {report['mean_cycle_s']:.3f} s "
        f"per object, {report['picks_per_hour']:.0f} picks per hour; plan on the "
        f"critical path {report['plan_on_critical_path_s']:.3f} s"
    )


def write_report(report: dict[str, Any], out_dir: Path) -> tuple[Path, Path]:
    """Write ``report.json`` and ``report.md`` into ``out_dir``; return both paths.

    Each file is written atomically (:mod:`rt_drake.atomic_file`).
    """
    json_path = out_dir / REPORT_FILES[0]
    md_path = out_dir / REPORT_FILES[1]
    write_text_atomically(json_path, json.dumps(report, indent=2) + "\n")
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
        *(f"- {o['name']}: {o.get('guarantee') or '-'}" for o in report["objects"]),
    ]
    write_text_atomically(md_path, "\n".join(lines) + "\n")
    return json_path, md_path


__all__ = [
    "EXEC_KEYS",
    "EXEC_PHASES",
    "REPORT_FILES",
    "PLAN_KEYS",
    "cycle_report",
    "object_report",
    "summary_line",
    "table_markdown",
    "write_report",
]
