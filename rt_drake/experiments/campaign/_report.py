"""The campaign report: summary tables and plots from the results database.

Per object and cup (:class:`GroupSummary`):

- per variant, the rows that ran (``ok``), those that held (success: slip
  under 5 mm and 3 deg), and the success rate = held / ran; infeasible rows
  (a typed error, e.g. the object slips off the cup at rest) and failed rows
  (``error``, ``crashed``) are counted apart, not as rollouts;
- the time extension of each trial whose constrained and unconstrained rows
  both ran, ``100 (d_c - d_u) / d_c`` % as in the paper's Table I (mean,
  min, max);
- the critical speed factors of the ``speed_sweep`` rows that slipped
  (median, min), and how many held up to the fastest factor;
- the ``optimized`` rows that ran: the ratio of the optimised MOVE's
  duration to the spline MOVE's (``detail.ratio_to_spline``; median, min,
  max), how many held, and the optimisation's CPU time (median, s).

- the ``robust`` rows that ran: how many held (robust MOVE, true object,
  worst cup), how many of the nominal MOVEs held in the same physics
  (``detail.nominal_on_true``), and the price robust / nominal duration
  (``detail.price``; median, min, max).

``summary.json`` also has these ``optimized`` and ``robust`` numbers over
the whole campaign.

:func:`write_campaign_report` writes ``summary.md``, ``summary.csv``,
``summary.json`` and the plots ``success_rates.png``,
``time_extension.png`` and ``critical_speed.png``.
"""

from __future__ import annotations

import csv
import dataclasses
import json
from collections import defaultdict
from pathlib import Path
from typing import Any

from rt_drake.experiments.campaign._group_summary import (
    GroupSummary,
    VariantCounts,
    optimized_summary,
    robust_summary,
)
from rt_drake.experiments.campaign._report_plots import write_plots
from rt_drake.experiments.campaign._row_types import (
    Status,
    Variant,
)
from rt_drake.experiments.campaign._store import (
    connect,
    read_meta,
)


def read_rows(database: Path) -> tuple[dict[str, str], list[dict[str, Any]]]:
    """The database's meta table and its rows (as dicts), read-only.

    A row's ``status`` is a :class:`~._row_types.Status` (the database stores its
    value); the other columns are as stored.
    """
    connection = connect(database, readonly=True)
    try:
        meta = read_meta(connection, database)
        rows = [
            {**r, "status": Status(r["status"])}
            for r in map(dict, connection.execute("SELECT * FROM rollouts"))
        ]
    finally:
        connection.close()
    return meta, rows


def summarize_rows(rows: list[dict[str, Any]]) -> list[GroupSummary]:
    """One :class:`GroupSummary` per (object, cup), sorted by name.

    ``rows`` as :func:`read_rows` gives them (``status`` a
    :class:`~._row_types.Status`).
    """
    groups: dict[tuple[str, str], list[dict[str, Any]]] = defaultdict(list)
    for row in rows:
        groups[(row["object"], row["cup"])].append(row)
    return [_summarize(obj, cup, groups[(obj, cup)]) for obj, cup in sorted(groups)]


def _summarize(obj: str, cup: str, rows: list[dict[str, Any]]) -> GroupSummary:
    by_variant: dict[str, list[dict[str, Any]]] = defaultdict(list)
    for row in rows:
        by_variant[row["variant"]].append(row)
    counts: dict[str, VariantCounts] = {
        variant.value: _counts(by_variant[variant.value])
        for variant in Variant
        if variant.value in by_variant
    }
    duration = {
        (row["variant"], row["seed"], row["trial"]): row["duration_s"]
        for row in rows
        if row["status"] is Status.OK
    }
    extension = []
    for (variant, seed, trial), d_c in sorted(duration.items()):
        d_u = duration.get((Variant.UNCONSTRAINED.value, seed, trial))
        if variant == Variant.CONSTRAINED.value and d_u is not None:
            extension.append(100.0 * (d_c - d_u) / d_c)
    sweeps = [
        row
        for row in by_variant[Variant.SPEED_SWEEP.value]
        if row["status"] is Status.OK
    ]
    optimized = [
        json.loads(row["detail"])
        for row in by_variant[Variant.OPTIMIZED.value]
        if row["status"] is Status.OK
    ]
    robust = [
        json.loads(row["detail"])
        for row in by_variant[Variant.ROBUST.value]
        if row["status"] is Status.OK
    ]
    return GroupSummary(
        object=obj,
        cup=cup,
        variants=counts,
        time_extension_pct=extension,
        critical_speeds=sorted(
            r["critical_speed"] for r in sweeps if r["critical_speed"] is not None
        ),
        held_through_sweep=sum(r["critical_speed"] is None for r in sweeps),
        optimized_ratios=[d["ratio_to_spline"] for d in optimized],
        optimize_cpu_s=[d["optimize_cpu_s"] for d in optimized],
        robust_prices=[d["price"] for d in robust],
        nominal_held_on_true=sum(bool(d["nominal_on_true"]["success"]) for d in robust),
    )


def _counts(rows: list[dict[str, Any]]) -> VariantCounts:
    ran = [row for row in rows if row["status"] is Status.OK]
    return VariantCounts(
        rows=len(rows),
        ran=len(ran),
        held=sum(bool(row["success"]) for row in ran),
        infeasible=sum(row["status"] is Status.INFEASIBLE for row in rows),
        failed=sum(row["status"] in _FAILED for row in rows),
    )


def _held_sweep(group: GroupSummary) -> str:
    sweeps = group.variants.get(Variant.SPEED_SWEEP.value)
    return "-" if sweeps is None else str(group.held_through_sweep)


def _held(group: GroupSummary, variant: Variant) -> str:
    counts = group.variants.get(variant.value)
    return "-" if counts is None else f"{counts.held}/{counts.ran}"


def summary_table(groups: list[GroupSummary]) -> str:
    """The Markdown table: one line per object and cup."""
    lines = [
        "| object | cup | held with constraint | held without | infeasible | "
        "failed | time ext. % mean (min to max) | critical speed median (min) | "
        "sweeps that never slipped | held optimized | optimized / spline median | "
        "held robust (nominal) | robust / nominal median |",
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for group in groups:
        d = group.as_dict()
        counts = list(group.variants.values())
        ext, crit = d["time_extension_pct"], d["critical_speed"]
        extension = "-"
        if ext["n"]:
            extension = f"{ext['mean']:.2f} ({ext['min']:.2f} to {ext['max']:.2f})"
        ratio = d["optimized"]["ratio_median"]
        robust, price = d["robust"], d["robust"]["price_median"]
        held_robust = "-"
        if Variant.ROBUST.value in group.variants:
            held_robust = f"{robust['held']}/{robust['ran']} ({robust['nominal_held']})"
        critical = "-"
        if crit["n"]:
            critical = f"{crit['median']:.1f}x ({crit['min']:.1f}x)"
        lines.append(
            f"| {group.object} | {group.cup} | {_held(group, Variant.CONSTRAINED)} | "
            f"{_held(group, Variant.UNCONSTRAINED)} | "
            f"{sum(c.infeasible for c in counts)} | {sum(c.failed for c in counts)} | "
            f"{extension} | {critical} | {_held_sweep(group)} | "
            f"{_held(group, Variant.OPTIMIZED)} | "
            f"{'-' if ratio is None else f'{ratio:.3f}'} | {held_robust} | "
            f"{'-' if price is None else f'{price:.3f}'} |"
        )
    return "\n".join(lines)


def write_campaign_report(database: str | Path, out: str | Path) -> list[Path]:
    """Write the summary tables and plots of ``database`` into ``out``.

    Raises:
        CampaignError: the file is missing or not a campaign database.
    """
    database, out = Path(database), Path(out)
    meta, rows = read_rows(database)
    groups = summarize_rows(rows)
    out.mkdir(parents=True, exist_ok=True)
    status = {s.value: sum(r["status"] is s for r in rows) for s in Status}
    summary: dict[str, Any] = {
        "content_hash": meta.get("content_hash"),
        "campaign_file": meta.get("campaign_file"),
        "total_rows": int(meta.get("total_rows", 0)),
        "rows": len(rows),
        "status": status,
        "groups": [group.as_dict() for group in groups],
        "optimized": optimized_summary(
            _total_counts(groups, Variant.OPTIMIZED),
            [r for group in groups for r in group.optimized_ratios],
            [c for group in groups for c in group.optimize_cpu_s],
        ),
        "robust": robust_summary(
            _total_counts(groups, Variant.ROBUST),
            [p for group in groups for p in group.robust_prices],
            sum(group.nominal_held_on_true for group in groups),
        ),
    }
    paths = [out / "summary.json", out / "summary.md", out / "summary.csv"]
    paths[0].write_text(json.dumps(summary, indent=2) + "\n")
    header = (
        f"Campaign {meta.get('campaign_file')} (content hash "
        f"{str(meta.get('content_hash'))[:12]}): {len(rows)} of "
        f"{summary['total_rows']} rows; "
        + ", ".join(f"{n} {s}" for s, n in status.items())
    )
    paths[1].write_text(f"{header}\n\n{summary_table(groups)}\n")
    _write_csv(paths[2], groups)
    return paths + write_plots(groups, out)


#: The statuses counted as failed rows (not infeasible, not rollouts).
_FAILED = (Status.ERROR, Status.CRASHED)


def _total_counts(groups: list[GroupSummary], variant: Variant) -> VariantCounts | None:
    counts = [g.variants[variant.value] for g in groups if variant.value in g.variants]
    if not counts:
        return None
    return VariantCounts(
        *(
            sum(getattr(c, f.name) for c in counts)
            for f in dataclasses.fields(counts[0])
        )
    )


def _write_csv(path: Path, groups: list[GroupSummary]) -> None:
    with path.open("w", newline="") as file:
        writer = csv.writer(file)
        writer.writerow(
            ["object", "cup", "variant", "rows", "ran", "held", "success_rate"]
            + ["infeasible", "failed", "time_extension_mean_pct"]
            + ["critical_speed_median", "critical_speed_min"]
            + ["optimized_ratio_median", "robust_price_median"]
        )
        for group in groups:
            d = group.as_dict()
            for name, c in group.variants.items():
                writer.writerow(
                    [group.object, group.cup, name, c.rows, c.ran, c.held]
                    + [c.success_rate, c.infeasible, c.failed]
                    + [d["time_extension_pct"]["mean"]]
                    + [d["critical_speed"]["median"], d["critical_speed"]["min"]]
                    + [d["optimized"]["ratio_median"], d["robust"]["price_median"]]
                )


__all__ = [
    "GroupSummary",
    "VariantCounts",
    "optimized_summary",
    "robust_summary",
    "read_rows",
    "summarize_rows",
    "summary_table",
    "write_campaign_report",
]
