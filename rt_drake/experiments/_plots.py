"""Plots of the transport experiment (matplotlib, Agg backend).

matplotlib is imported inside the functions, so importing rt_drake stays light.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from rt_drake.atomic_file import write_atomically


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _save(fig, path: Path) -> Path:
    """Write ``fig`` as a PNG at ``path`` (atomically) and release it."""
    plt = _pyplot()
    fig.tight_layout()
    try:
        write_atomically(
            path, lambda stream: fig.savefig(stream, format="png", dpi=120)
        )
    finally:
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
    ax.plot(
        p.get("s_unconstrained", p["s"]),  # results.json before 0.2.0: one grid
        p["sd_unconstrained"],
        color="tab:red",
        label="joint limits only",
    )
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


def plot_robustness(trials: list[dict[str, Any]], path: Path) -> Path:
    """The price of robustness (durations) against its gain (slip, success).

    Top: each path's MOVE duration, nominal and robust plan (x: the true
    object slipped). Bottom: how far the true object slipped on the cup.
    """
    import numpy as np

    plt = _pyplot()
    index = np.arange(len(trials))
    fig, (top, bottom) = plt.subplots(
        2, 1, figsize=(max(6, 0.45 * len(trials) + 2), 6), sharex=True
    )
    width = 0.4
    for offset, key, color, label in (
        (-width / 2, "nominal", "tab:red", "nominal object's plan"),
        (width / 2, "robust", "tab:green", "robust plan (every object of the set)"),
    ):
        durations = [t[f"duration_{key}_s"] for t in trials]
        top.bar(index + offset, durations, width, color=color, label=label)
        slips = [t[f"slip_{key}"]["max_translation_mm"] for t in trials]
        bottom.bar(index + offset, slips, width, color=color, label=label)
        for i, t in enumerate(trials):
            if not t[f"success_{key}"]:
                top.plot(i + offset, durations[i] + 0.03, "kx")
    bottom.axhline(5.0, color="k", linewidth=0.8, linestyle="--")
    bottom.set_yscale("log")
    longest = max(max(t["duration_nominal_s"], t["duration_robust_s"]) for t in trials)
    top.set_ylim(0, 1.4 * longest)
    top.set_ylabel("MOVE duration (s)")
    top.set_title("price of robustness (duration) and its gain (x: slipped)")
    top.legend(loc="upper left", ncol=2)
    bottom.set_ylabel("true object's slip (mm; - - 5 mm)")
    bottom.set_xlabel("path")
    bottom.set_xticks(index)
    return _save(fig, path)


def plot_optimized(trial: dict[str, Any], path: Path) -> Path:
    """The spline MOVE and the optimised MOVE of a trial, side by side.

    Rows, against time: the cup position (m, world x, y, z), its tilt (deg,
    the angle between the cup axis and gravity) and the grasp margin
    ``min (g - F w) / g`` (0: the constraint binds).
    """
    plt = _pyplot()
    profiles = trial["cup_profiles"]
    fig, axes = plt.subplots(3, 2, figsize=(10, 7), sharex=True, sharey="row")
    titles = {
        "spline": f"spline path: {trial['duration_constrained_s']:.3f} s (Table I)",
        "optimized": (
            f"optimised path: {trial['duration_optimized_s']:.3f} s"
            if trial["improved"]
            else f"no faster path: {trial['duration_optimized_s']:.3f} s "
            "(adaptive grid)"
        ),
    }
    for column, key in enumerate(("spline", "optimized")):
        p = profiles[key]
        top, middle, bottom = axes[:, column]
        for axis, color in (("x", "tab:red"), ("y", "tab:green"), ("z", "tab:blue")):
            top.plot(p["t"], p[axis], color=color, label=axis)
        top.set_title(titles[key])
        middle.plot(p["t"], p["tilt_deg"], color="tab:purple")
        bottom.axhline(0.0, color="k", linewidth=0.8)
        bottom.plot(p["t_grid"], p["grasp_margin"], color="tab:orange")
        bottom.set_xlabel("time (s)")
    axes[0, 0].set_ylabel("cup position (m)")
    axes[0, 0].legend(loc="best")
    axes[1, 0].set_ylabel("cup tilt (deg)")
    axes[2, 0].set_ylabel("grasp margin")
    return _save(fig, path)


__all__ = [
    "plot_durations",
    "plot_margins",
    "plot_optimized",
    "plot_profiles",
    "plot_robustness",
]
