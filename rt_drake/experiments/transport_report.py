"""The Table I report of the transport experiment: Markdown table and files.

:func:`write_transport_report` writes ``results.json``, ``report.md`` and the
plots of :mod:`.plots` into a directory.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from rt_drake.atomic_file import write_text_atomically
from rt_drake.experiments.plots import plot_durations, plot_margins, plot_profiles

#: The files :func:`write_transport_report` writes into its directory.
TRANSPORT_FILES = (
    "results.json",
    "sd_profiles.png",
    "grasp_margin.png",
    "durations.png",
    "report.md",
)


def transport_table(results: dict[str, Any]) -> str:
    """The paper's Table I for this run (Markdown)."""
    mark = {True: "ok", False: "SLIP"}
    lines = [
        "| # | without constraint (s) | | with constraint (s) | | time ext. (%) "
        "| critical speed |",
        "|---:|---:|:---|---:|:---|---:|---:|",
    ]
    for t in results["trials"]:
        critical = t["critical_speed_factor"]
        cells = [
            str(t["index"]),
            f"{t['duration_unconstrained_s']:.3f}",
            mark[t["success_unconstrained"]],
            f"{t['duration_constrained_s']:.3f}",
            mark[t["success_constrained"]],
            f"{t['time_extension_pct']:.2f}",
            "-" if critical is None else f"{critical:.1f}x",
        ]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


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
        "",
        "![s'(s)](sd_profiles.png) ![margin](grasp_margin.png)",
        "![durations](durations.png)",
    ]
    written.append(out_dir / "report.md")
    write_text_atomically(written[-1], "\n".join(text) + "\n")
    return written


__all__ = ["TRANSPORT_FILES", "transport_table", "write_transport_report"]
