"""Validation campaigns: many objects, cups and transports, resumable, queryable.

``rt-drake experiment campaign CAMPAIGN.yaml --out DB`` runs every
(object, cup, trial, variant) row of a campaign file, locally or on a Ray
cluster, into one SQLite database; ``rt-drake experiment report DB`` writes
its summary tables and plots.

- :mod:`._spec`, :mod:`._catalogue`, :mod:`._definition`: the campaign file, its
  objects and cups, its rows and content hash (:func:`load_campaign`).
- :mod:`._row_types`: a row's key, :class:`Variant`, status and result, and
  the :class:`Task` a worker gets.
- :mod:`._variants`: the registry of comparisons, one function per variant.
- :mod:`._worker`: a worker's shared inputs (built once) and one task.
- :mod:`._local_executor`, :mod:`._ray_executor`: where the tasks run.
- :mod:`._store`: the SQLite database; :mod:`._runner`: the driver;
  :mod:`._campaign_progress`: done / total, failures, ETA.
- :mod:`._report`, :mod:`._report_plots`: the report from the database.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from rt_drake._lazy import lazy_attributes

if TYPE_CHECKING:  # the lazy names below, for type checkers and IDEs
    from rt_drake.experiments.campaign._campaign_errors import (
        CampaignError,
        CampaignMismatchError,
        ExecutorUnavailableError,
    )
    from rt_drake.experiments.campaign._definition import (
        Campaign,
        Combination,
        load_campaign,
    )
    from rt_drake.experiments.campaign._report import (
        summarize_rows,
        write_campaign_report,
    )
    from rt_drake.experiments.campaign._row_types import (
        Outcome,
        RowKey,
        RowResult,
        Status,
        Task,
        Variant,
    )
    from rt_drake.experiments.campaign._runner import (
        CampaignRun,
        ExecutorKind,
        make_executor,
        run_campaign,
    )
    from rt_drake.experiments.campaign._variants import VARIANTS

__all__ = [
    "VARIANTS",
    "Campaign",
    "CampaignError",
    "CampaignMismatchError",
    "CampaignRun",
    "Combination",
    "ExecutorKind",
    "ExecutorUnavailableError",
    "Outcome",
    "RowKey",
    "RowResult",
    "Status",
    "Task",
    "Variant",
    "load_campaign",
    "make_executor",
    "run_campaign",
    "summarize_rows",
    "write_campaign_report",
]

#: Public name -> module defining it, imported on first access (PEP 562).
_WHERE: dict[str, str] = {
    "CampaignError": "rt_drake.experiments.campaign._campaign_errors",
    "CampaignMismatchError": "rt_drake.experiments.campaign._campaign_errors",
    "ExecutorUnavailableError": "rt_drake.experiments.campaign._campaign_errors",
    "Campaign": "rt_drake.experiments.campaign._definition",
    "Combination": "rt_drake.experiments.campaign._definition",
    "load_campaign": "rt_drake.experiments.campaign._definition",
    "summarize_rows": "rt_drake.experiments.campaign._report",
    "write_campaign_report": "rt_drake.experiments.campaign._report",
    "Outcome": "rt_drake.experiments.campaign._row_types",
    "RowKey": "rt_drake.experiments.campaign._row_types",
    "RowResult": "rt_drake.experiments.campaign._row_types",
    "Status": "rt_drake.experiments.campaign._row_types",
    "Task": "rt_drake.experiments.campaign._row_types",
    "Variant": "rt_drake.experiments.campaign._row_types",
    "CampaignRun": "rt_drake.experiments.campaign._runner",
    "ExecutorKind": "rt_drake.experiments.campaign._runner",
    "make_executor": "rt_drake.experiments.campaign._runner",
    "run_campaign": "rt_drake.experiments.campaign._runner",
    "VARIANTS": "rt_drake.experiments.campaign._variants",
}

__getattr__, __dir__ = lazy_attributes(__name__, _WHERE, __all__)
