"""Plots of a campaign report (matplotlib, Agg backend, imported lazily).

- ``success_rates.png``: per object and cup, the share of rollouts that
  held, with and without the grasp constraint, and on the optimised path;
- ``time_extension.png``: each trial's time extension (%);
- ``critical_speed.png``: each speed sweep's critical factor (a hollow
  marker at the fastest factor for a sweep that never slipped).
"""

from __future__ import annotations

from pathlib import Path

from rt_drake.experiments._rollout import SPEED_FACTORS
from rt_drake.experiments.campaign._group_summary import GroupSummary
from rt_drake.experiments.campaign._row_types import Variant


def _pyplot():  # noqa: ANN202
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _save(fig, path: Path) -> Path:  # noqa: ANN001
    plt = _pyplot()
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def _labels(groups: list[GroupSummary]) -> list[str]:
    return [f"{g.object}\n{g.cup}" for g in groups]


def plot_success_rates(groups: list[GroupSummary], path: Path) -> Path:
    """Grouped bars: held / ran per object and cup, per speed-1 variant."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(max(6.0, 1.4 * len(groups)), 4))
    variants = (
        (Variant.CONSTRAINED, "tab:green", "with grasp constraint"),
        (Variant.UNCONSTRAINED, "tab:red", "joint limits only"),
        (Variant.OPTIMIZED, "tab:purple", "optimised path, with constraint"),
    )
    width = 0.27
    for offset, (variant, colour, label) in zip((-1, 0, 1), variants, strict=True):
        rates = []
        for group in groups:
            counts = group.variants.get(variant.value)
            rate = None if counts is None else counts.success_rate
            rates.append(0.0 if rate is None else 100.0 * rate)
        positions = [i + offset * width for i in range(len(groups))]
        ax.bar(positions, rates, width, color=colour, label=label)
    ax.set_xticks(range(len(groups)), _labels(groups), fontsize=8)
    ax.set_ylim(0, 105)
    ax.set_ylabel("rollouts that held (%)")
    ax.set_title("success rate per object and cup")
    ax.legend(fontsize=8)
    return _save(fig, path)


def plot_time_extension(groups: list[GroupSummary], path: Path) -> Path:
    """Each trial's time extension (%) per object and cup."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(max(6.0, 1.4 * len(groups)), 4))
    for i, group in enumerate(groups):
        values = group.time_extension_pct
        ax.plot([i] * len(values), values, "o", color="tab:blue", alpha=0.6)
    ax.set_xticks(range(len(groups)), _labels(groups), fontsize=8)
    ax.set_xlim(-0.5, len(groups) - 0.5)
    ax.set_ylabel("time extension (d_c - d_u) / d_c (%)")
    ax.set_title("cost of the grasp constraint per trial")
    return _save(fig, path)


def plot_critical_speed(groups: list[GroupSummary], path: Path) -> Path:
    """Each sweep's critical speed factor per object and cup."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(max(6.0, 1.4 * len(groups)), 4))
    for i, group in enumerate(groups):
        values = group.critical_speeds
        ax.plot([i] * len(values), values, "o", color="tab:orange", alpha=0.7)
        held = group.held_through_sweep
        if held:
            ax.plot(
                [i] * held, [SPEED_FACTORS[-1]] * held, "o", mfc="none", color="0.4"
            )
    ax.axhline(1.0, color="0.6", lw=0.8)
    ax.set_xticks(range(len(groups)), _labels(groups), fontsize=8)
    ax.set_xlim(-0.5, len(groups) - 0.5)
    ax.set_ylabel("critical speed factor")
    ax.set_title("first speed factor at which the object slips")
    return _save(fig, path)


def write_plots(groups: list[GroupSummary], out: Path) -> list[Path]:
    """The three plots in ``out``."""
    return [
        plot_success_rates(groups, out / "success_rates.png"),
        plot_time_extension(groups, out / "time_extension.png"),
        plot_critical_speed(groups, out / "critical_speed.png"),
    ]


__all__ = [
    "plot_critical_speed",
    "plot_success_rates",
    "plot_time_extension",
    "write_plots",
]
