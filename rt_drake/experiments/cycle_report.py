"""The cycle report: ``report.json`` and a Markdown table like the paper's Table II.

Per object: planning wall times (s) of APPROACH, REACH, MOVE and the MOVE
retime; execution times (s, simulated) of APPROACH, REACH, ATTACH, MOVE and
DETACH; the object's slip on the cup while attached (max translation mm,
max rotation deg) and its placement error at the goal; the MOVE's guarantee
(what its retiming holds: the nominal object, every object of its
uncertainty set, or none); and the cycle total (plan + execution, as in the
paper, where planning runs while the arm waits).
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

from rt_drake.phase import Phase
from rt_drake.simulation.motion import PlanTimes
from rt_drake.simulation.sequencer import ObjectRecord

#: Keys of ``plan_s``: APPROACH and REACH (plan + retime), MOVE (plan), and
#: the MOVE's retime, as the paper's Table II.
PLAN_KEYS = ("approach", "reach", "move", "retime")
#: The phases of ``exec_s``, in order (keys: their values).
EXEC_PHASES = (Phase.APPROACH, Phase.REACH, Phase.ATTACH, Phase.MOVE, Phase.DETACH)
EXEC_KEYS = tuple(phase.value for phase in EXEC_PHASES)


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
        "guarantee": record.guarantee,
        "total_s": sum(plan_s.values()) + sum(exec_s.values()),
    }


def cycle_report(records: tuple[ObjectRecord, ...], **extra: Any) -> dict[str, Any]:
    """The whole report: ``objects`` (one entry each), ``total_s``, ``extra``."""
    objects = [object_report(r) for r in records]
    return {"objects": objects, "total_s": sum(o["total_s"] for o in objects), **extra}


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
    for key in EXEC_KEYS:
        label = (
            f"{key.upper()} exec."
            if key not in ("attach", "detach")
            else f"{key.upper()} delay"
        )
        row(label, [o["exec_s"][key] for o in objects])
    row("**Total exec.**", [sum(o["exec_s"].values()) for o in objects])
    row("**Total (plan + exec.)**", [o["total_s"] for o in objects])
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


def write_report(report: dict[str, Any], out_dir: Path) -> tuple[Path, Path]:
    """Write ``report.json`` and ``report.md`` into ``out_dir``; return both paths."""
    out_dir.mkdir(parents=True, exist_ok=True)
    json_path = out_dir / "report.json"
    md_path = out_dir / "report.md"
    json_path.write_text(json.dumps(report, indent=2) + "\n")
    lines = [
        "# Pick-and-place cycle",
        "",
        "Times in seconds: planning is wall time on this machine, execution is",
        "simulated time. Slip: the object's largest displacement relative to the",
        "cup while attached. Total = plan + exec., as in the paper's Table II.",
        "",
        table_markdown(report),
        f"Cycle total: {report['total_s']:.3f} s",
        "",
        "What each MOVE's retiming guarantees the cup holds:",
        "",
        *(f"- {o['name']}: {o.get('guarantee') or '-'}" for o in report["objects"]),
    ]
    md_path.write_text("\n".join(lines) + "\n")
    return json_path, md_path


__all__ = [
    "EXEC_KEYS",
    "EXEC_PHASES",
    "PLAN_KEYS",
    "cycle_report",
    "object_report",
    "table_markdown",
    "write_report",
]
