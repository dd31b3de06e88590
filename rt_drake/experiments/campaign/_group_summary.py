"""One object with one cup in a campaign report: its counts and statistics.

Plain data shared by the report's tables (:mod:`._report`) and its plots
(:mod:`._report_plots`); the module docstring of :mod:`._report` says what each
number means.
"""

from __future__ import annotations

import dataclasses
import statistics
from typing import Any

from rt_drake.experiments.campaign._row_types import Variant


@dataclasses.dataclass(frozen=True)
class VariantCounts:
    """Rows of one variant of one object and cup."""

    rows: int
    ran: int
    held: int
    infeasible: int
    failed: int

    @property
    def success_rate(self) -> float | None:
        """The share of the rollouts that held: held / ran (None if none ran)."""
        return self.held / self.ran if self.ran else None


@dataclasses.dataclass(frozen=True)
class GroupSummary:
    """The summary of one object with one cup (see the module docstring)."""

    object: str
    cup: str
    variants: dict[str, VariantCounts]
    time_extension_pct: list[float]
    critical_speeds: list[float]
    held_through_sweep: int
    optimized_ratios: list[float] = dataclasses.field(default_factory=list)
    optimize_cpu_s: list[float] = dataclasses.field(default_factory=list)
    robust_prices: list[float] = dataclasses.field(default_factory=list)
    nominal_held_on_true: int = 0

    def as_dict(self) -> dict[str, Any]:
        """JSON-ready numbers, with the derived statistics."""
        ext, critical = self.time_extension_pct, self.critical_speeds
        return {
            "object": self.object,
            "cup": self.cup,
            "variants": {
                name: {**dataclasses.asdict(c), "success_rate": c.success_rate}
                for name, c in self.variants.items()
            },
            "time_extension_pct": {
                "n": len(ext),
                "mean": statistics.fmean(ext) if ext else None,
                "min": min(ext, default=None),
                "max": max(ext, default=None),
            },
            "critical_speed": {
                "n": len(critical),
                "median": statistics.median(critical) if critical else None,
                "min": min(critical, default=None),
                "held_through_sweep": self.held_through_sweep,
            },
            "optimized": optimized_summary(
                self.variants.get(Variant.OPTIMIZED.value),
                self.optimized_ratios,
                self.optimize_cpu_s,
            ),
            "robust": robust_summary(
                self.variants.get(Variant.ROBUST.value),
                self.robust_prices,
                self.nominal_held_on_true,
            ),
        }


def robust_summary(
    counts: VariantCounts | None, prices: list[float], nominal_held: int
) -> dict[str, Any]:
    """The ``robust`` rows: ran, held, nominal MOVEs held, robust / nominal."""
    return {
        "ran": 0 if counts is None else counts.ran,
        "held": 0 if counts is None else counts.held,
        "nominal_held": nominal_held,
        "price_median": statistics.median(prices) if prices else None,
        "price_min": min(prices, default=None),
        "price_max": max(prices, default=None),
    }


def optimized_summary(
    counts: VariantCounts | None, ratios: list[float], cpu_s: list[float]
) -> dict[str, Any]:
    """The ``optimized`` rows: ran, held, optimised / spline duration, CPU time."""
    return {
        "ran": 0 if counts is None else counts.ran,
        "held": 0 if counts is None else counts.held,
        "ratio_median": statistics.median(ratios) if ratios else None,
        "ratio_min": min(ratios, default=None),
        "ratio_max": max(ratios, default=None),
        "optimize_cpu_s_median": statistics.median(cpu_s) if cpu_s else None,
    }


__all__ = ["GroupSummary", "VariantCounts", "optimized_summary", "robust_summary"]
