"""Plots and the Table I report of the transport experiment (matplotlib, Agg).

matplotlib is imported inside the functions, so importing rt_drake stays light.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _save(fig, path: Path) -> Path:
    """Write ``fig`` as a PNG at ``path`` and release it."""
    plt = _pyplot()
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def plot_profiles(trial: dict[str, Any], path: Path) -> Path:
    """s'(s) with and without the grasp constraint, under the velocity bound."""
    plt = _pyplot()
    p = trial["profiles"]
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.fill_between(
        p["s"],
        0,
        p["sd_velocity_limit"],
        color="0.9",
        label="joint velocity limits allow",
    )
    ax.plot(p["s"], p["sd_unconstrained"], color="tab:red", label="joint limits only")
    ax.plot(
        p["s"], p["sd_constrained"], color="tab:green", label="with grasp constraint"
    )
    top = max(max(p["sd_unconstrained"]), max(p["sd_constrained"]))
    ax.set_ylim(0, 1.3 * top)
    ax.set_xlabel("path parameter s")
    ax.set_ylabel("path velocity s' (1/s)")
    ax.set_title(f"path {trial['index']}: time-optimal s'(s)")
    ax.legend(loc="upper right")
    return _save(fig, path)


def plot_margins(trial: dict[str, Any], path: Path) -> Path:
    """Grasp-constraint margin min (g - F w)/g over time, both retimings."""
    plt = _pyplot()
    p = trial["profiles"]
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.axhline(0.0, color="k", linewidth=0.8)
    ax.plot(
        p["t_unconstrained"],
        p["margin_unconstrained"],
        color="tab:red",
        label="joint limits only",
    )
    ax.plot(
        p["t_constrained"],
        p["margin_constrained"],
        color="tab:green",
        label="with grasp constraint",
    )
    ax.set_xlabel("time (s)")
    ax.set_ylabel("grasp margin  min (g - F w) / g")
    ax.set_title(f"path {trial['index']}: below 0 the cup cannot hold the object")
    ax.legend(loc="lower right")
    return _save(fig, path)


def plot_durations(trials: list[dict[str, Any]], path: Path) -> Path:
    """Duration of each path with and without the constraint; x marks a slip."""
    import numpy as np

    plt = _pyplot()
    index = np.arange(len(trials))
    fig, ax = plt.subplots(figsize=(max(6, 0.45 * len(trials) + 2), 4))
    width = 0.4
    for offset, key, color, label in (
        (-width / 2, "unconstrained", "tab:red", "joint limits only"),
        (width / 2, "constrained", "tab:green", "with grasp constraint"),
    ):
        durations = [t[f"duration_{key}_s"] for t in trials]
        ax.bar(index + offset, durations, width, color=color, label=label)
        for i, t in enumerate(trials):
            if not t[f"success_{key}"]:
                ax.plot(i + offset, durations[i] + 0.03, "kx")
    ax.set_xticks(index)
    ax.set_xlabel("path")
    ax.set_ylabel("MOVE duration (s)")
    ax.set_title("durations; x: the object slipped in simulation")
    ax.legend(loc="upper right")
    return _save(fig, path)


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
    """Write results.json, report.md and the PNG plots; return the paths."""
    import json

    out_dir.mkdir(parents=True, exist_ok=True)
    s = results["summary"]
    written = [out_dir / "results.json"]
    written[0].write_text(json.dumps(results, indent=1) + "\n")
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
    written[-1].write_text("\n".join(text) + "\n")
    return written
