"""The report of the robust transport experiment: table, files and plot.

:func:`write_robust_report` writes ``results.json``, ``report.md`` (the
table: each trial's true object, both durations, whether each plan held it,
the price of robustness and the tightness ratio) and ``robustness.png``
(:func:`~._plots.plot_robustness`, when a trial was played). The trials
the retimer refused (``not_retimed``) are listed under the table.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from rt_drake.atomic_file import write_text_atomically
from rt_drake.experiments._plots import plot_robustness

#: The files :func:`write_robust_report` writes into its directory.
ROBUST_FILES = ("results.json", "robustness.png", "report.md")


def robust_table(results: dict[str, Any]) -> str:
    """One row per trial (Markdown)."""
    mark = {True: "ok", False: "SLIP"}
    lines = [
        "| # | true mass (kg) | true CoM (mm) | nominal (s) | | robust (s) | "
        "| price | tightness |",
        "|---:|---:|:---|---:|:---|---:|:---|---:|---:|",
    ]
    for t in results["trials"]:
        true = t["true_object"]
        com = ", ".join(f"{1e3 * v:+.1f}" for v in true["com"])
        cells = [
            str(t["index"]),
            f"{true['mass']:.3f}",
            f"({com})",
            f"{t['duration_nominal_s']:.3f}",
            mark[t["success_nominal"]],
            f"{t['duration_robust_s']:.3f}",
            mark[t["success_robust"]],
            f"{t['price']:.2f}x",
            f"{t['tightness']:.4f}",
        ]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def summary_lines(results: dict[str, Any]) -> list[str]:
    """The comparison in a few lines, and the trials the retimer refused."""
    s = results["summary"]
    refused = [
        f"- path {t['index']} not retimed, not played: {t['not_retimed']}"
        for t in results.get("not_retimed", [])
    ]
    if s.get("not_retimed"):
        refused.insert(
            0,
            f"- not retimed (not played): {s['not_retimed']} of the "
            f"{s['n_sampled']} sampled paths",
        )
    if not results["trials"]:
        return refused
    return _played_lines(results) + _speed_lines(s) + refused


def _speed_lines(s: dict[str, Any]) -> list[str]:
    """The robust plans' critical speed factors, if swept."""
    if "critical_speed_factors" not in s:
        return []
    factors = ", ".join(
        "never" if f is None else f"{f:g}" for f in s["critical_speed_factors"]
    )
    median, least = s["critical_speed_factor_median"], s["critical_speed_factor_min"]
    return [
        "- critical speed factor of the robust plans (true object): median "
        + ("-" if median is None else f"{median:g}")
        + ", min "
        + ("-" if least is None else f"{least:g}")
        + (
            f" (some never slipped up to {s['never_slipped_up_to']:g}x)"
            if s["never_slipped_up_to"] is not None
            else ""
        )
        + f"; each: {factors}"
    ]


def _played_lines(results: dict[str, Any]) -> list[str]:
    """Holds, price, tightness, soundness and retime time of the played trials."""
    s = results["summary"]
    price, tight = s["price"], s["tightness"]
    return [
        f"- true objects held: robust plans {s['success_robust']} of {s['n']}, "
        f"nominal plans {s['success_nominal']} of {s['n']}; largest slip of the "
        f"robust plans {s['slip_robust_max_mm']:.2f} mm, "
        f"{s['slip_robust_max_deg']:.2f} deg",
        f"- price of robustness (robust / nominal duration): median "
        f"{price['median']:.2f}x, range {price['min']:.2f}-{price['max']:.2f}x",
        f"- tightness (robust / dense-sample lower bound): median "
        f"{tight['median']:.4f}, max {tight['max']:.4f}",
        f"- soundness: the robust plans checked at 1 kHz for the "
        f"{results['trials'][0]['sample_objects']} objects of the sample by an "
        f"independent route: worst excess "
        f"{s['sound_excess_max']:+.2e} (contract: <= 1e-3)",
        f"- retime wall time: nominal median "
        f"{1e3 * s['retime_nominal_s']['median']:.1f} ms, robust median "
        f"{1e3 * s['retime_robust_s']['median']:.1f} ms",
    ]


def _cup_physics_words(results: dict[str, Any]) -> str:
    """The simulated cup and the grasp's ramp and margin, in words."""
    kind = results.get("cup_physics", "rim")
    words = [f"{kind} (cup_physics)"]
    if results.get("grasp_ramp_s") is not None:
        words.append(f"grasp ramp {results['grasp_ramp_s']:g} s")
    if results.get("grasp_margin"):
        words.append(f"grasp margin {results['grasp_margin']:g}")
    if results.get("jerk_limits"):
        words.append("the robot's jerk limits")
    return ", ".join(words)


def write_robust_report(results: dict[str, Any], out_dir: Path) -> list[Path]:
    """Write results.json, robustness.png and report.md; return the paths.

    The files are :data:`ROBUST_FILES`, each written atomically.
    """
    written = [out_dir / "results.json"]
    write_text_atomically(written[0], json.dumps(results, indent=1) + "\n")
    played = bool(results["trials"])
    if played:
        written.append(plot_robustness(results["trials"], out_dir / "robustness.png"))
    u, cup = results["uncertainty"], results["cup"]
    com = ", ".join(f"{1e3 * v:.3g}" for v in u["com"])
    ranges = [
        f"{name} down to {cup[key]:g}{unit}"
        for name, key, unit in (
            ("friction", "friction_min", ""),
            ("suction", "suction_force_min", " N"),
        )
        if cup[key] is not None
    ]
    text = [
        f"# Robust transports of the {results['object']} "
        f"(seed {results['seed']}, n = {results['n']})",
        "",
        f"Uncertainty set: mass +-{100 * u['mass']:.3g} %, CoM +-({com}) mm,",
        f"principal moments +-{100 * u['inertia']:.3g} %; cup: "
        + (", ".join(ranges) if ranges else "friction and suction known")
        + ".",
        f"Simulated cup: {_cup_physics_words(results)}.",
        "Each path is retimed for the nominal object and for every object of",
        "the set, and both are played in the cycle's physics with the same true",
        "object, drawn from the set's hardest corners (heaviest, largest",
        "moments, centre of mass at a random corner), on the worst cup of the",
        "range (the rim cup; a bellows cup is its catalogue's).",
        "ok: it moved less than 5 mm and 3 deg on the cup. Price: robust",
        "/ nominal duration. Tightness: robust duration / the duration that",
        "holds a dense sample of the set (its corners that are bodies and 200",
        "random bodies),",
        "a lower bound of the robust optimum. Soundness: each robust plan",
        "checked at 1 kHz for that sample's objects by another route than the",
        "retimer's (Drake's body accelerations, Newton-Euler).",
        "",
        robust_table(results) if played else "No trial was played.\n",
        *summary_lines(results),
        "",
        "![price and gain of robustness](robustness.png)" if played else "",
    ]
    written.append(out_dir / "report.md")
    write_text_atomically(written[-1], "\n".join(text) + "\n")
    return written


__all__ = ["ROBUST_FILES", "robust_table", "summary_lines", "write_robust_report"]
