"""The Table I report of the transport experiment: Markdown table and files.

:func:`write_transport_report` writes ``results.json``, ``report.md`` and the
plots of :mod:`._plots` into a directory.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from rt_drake.atomic_file import write_text_atomically
from rt_drake.experiments._optimized_transport import REPLAY_FILE
from rt_drake.experiments._plots import (
    plot_durations,
    plot_margins,
    plot_optimized,
    plot_profiles,
)

#: The files :func:`write_transport_report` writes into its directory (the
#: last two only for an ``optimize`` run; the replay is written by the trial).
TRANSPORT_FILES = (
    "results.json",
    "sd_profiles.png",
    "grasp_margin.png",
    "durations.png",
    "report.md",
    "optimized.png",
    REPLAY_FILE,
)


def _speed(critical: float | None) -> str:
    return "-" if critical is None else f"{critical:.1f}x"


def transport_table(results: dict[str, Any]) -> str:
    """The paper's Table I for this run (Markdown), optimised MOVEs if run."""
    mark = {True: "ok", False: "SLIP"}
    optimized = bool(results.get("optimize"))
    header = (
        "| # | without constraint (s) | | with constraint (s) | | time ext. (%) "
        "| critical speed |"
    )
    rule = "|---:|---:|:---|---:|:---|---:|---:|"
    if optimized:
        header += " optimized (s) | | ratio | critical speed |"
        rule += "---:|:---|---:|---:|"
    lines = [header, rule]
    for t in results["trials"]:
        cells = [
            str(t["index"]),
            f"{t['duration_unconstrained_s']:.3f}",
            mark[t["success_unconstrained"]],
            f"{t['duration_constrained_s']:.3f}",
            mark[t["success_constrained"]],
            f"{t['time_extension_pct']:.2f}",
            _speed(t["critical_speed_factor"]),
        ]
        if optimized:
            cells += [
                f"{t['duration_optimized_s']:.3f}",
                mark[t["success_optimized"]],
                f"{t['duration_optimized_s'] / t['duration_constrained_s']:.3f}",
                _speed(t["critical_speed_factor_optimized"]),
            ]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def optimized_summary(summary: dict[str, Any]) -> str:
    """One line on the optimised MOVEs (the summary of an ``optimize`` run)."""
    critical = summary["critical_speed_factor_optimized_min"]
    return (
        f"optimized MOVE: {summary['success_optimized']}/{summary['n']} hold, "
        f"{summary['improved']}/{summary['n']} shorter than the spline path; "
        f"median duration ratio {summary['ratio_median']:.3f} against the spline "
        f"path (Table I's retime), {summary['ratio_same_grid_median']:.3f} against "
        f"the spline path on the optimiser's grid; critical speed factor min "
        f"{_speed(critical)}; optimisation median "
        f"{summary['optimize_wall_s_median']:.3f} s wall, "
        f"{summary['optimize_cpu_s_median']:.3f} s CPU"
    )


def write_transport_report(results: dict[str, Any], out_dir: Path) -> list[Path]:
    """Write results.json, report.md and the PNG plots; return the paths.

    The files are :data:`TRANSPORT_FILES`, each written atomically.
    """
    s = results["summary"]
    written = [out_dir / "results.json"]
    write_text_atomically(written[0], json.dumps(results, indent=1) + "\n")
    first = results["trials"][0]
    written += [
        plot_profiles(first, out_dir / "sd_profiles.png"),
        plot_margins(first, out_dir / "grasp_margin.png"),
        plot_durations(results["trials"], out_dir / "durations.png"),
    ]
    if results.get("optimize"):
        written.append(plot_optimized(first, out_dir / "optimized.png"))
        if (out_dir / REPLAY_FILE).exists():
            written.append(out_dir / REPLAY_FILE)
    if s["critical_speed_factor_median"] is not None:
        critical = (
            f"median {s['critical_speed_factor_median']:.2f}x, "
            f"min {s['critical_speed_factor_min']:.2f}x"
        )
    else:
        critical = f"some paths never slipped up to {s['never_slipped_up_to']}x"
    extension, duration = s["time_extension_pct"], s["duration_constrained_s"]
    text = [
        f"# Random transports of the {results['object']} "
        f"(seed {results['seed']}, n = {s['n']})",
        "",
        "Each path is retimed with joint limits only and with the grasp constraint,",
        "and both are played in the cycle's physics. ok: the object moved less than",
        "5 mm and",
        "3 deg on the cup; SLIP: more. Time extension = (with - without) / with, as in",
        "the paper. Critical speed: the first factor of the sweep",
        "1.0, 1.1, 1.2, 1.3, 1.4, 1.6, 1.8, 2.0, 2.5, 3.0 at which the constrained",
        "trajectory, played that much faster, slips.",
        "",
        transport_table(results),
        f"- with the constraint: {s['success_constrained']} of {s['n']} succeed; "
        f"without: {s['success_unconstrained']} of {s['n']}",
        f"- time extension: mean {extension['mean']:.1f} %, "
        f"range {extension['min']:.1f}-{extension['max']:.1f} %",
        f"- constrained durations {duration['min']:.3f}-{duration['max']:.3f} s",
        f"- critical speed factor: {critical}",
    ]
    for t in results.get("not_retimed", []):
        text.append(f"- path {t['index']} not retimed, not played: {t['not_retimed']}")
    if results.get("optimize"):
        text += [
            f"- {optimized_summary(s)}",
            "- optimized: the MOVE shaped for speed (issue 13) from the same grasp "
            "to the same goal, retimed under the exact constraint on the "
            "optimiser's adaptive grid; ratio = optimized / with constraint",
        ]
    text += [
        "",
        "![s'(s)](sd_profiles.png) ![margin](grasp_margin.png)",
        "![durations](durations.png)",
    ]
    if results.get("optimize"):
        text += [
            "",
            f"![spline and optimized MOVE of path {first['index']}](optimized.png) "
            f"(replay: [{REPLAY_FILE}]({REPLAY_FILE}))",
        ]
    written.append(out_dir / "report.md")
    write_text_atomically(written[-1], "\n".join(text) + "\n")
    return written


__all__ = [
    "TRANSPORT_FILES",
    "optimized_summary",
    "transport_table",
    "write_transport_report",
]
