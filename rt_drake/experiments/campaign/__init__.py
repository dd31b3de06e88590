"""Validation campaigns: many objects, cups and transports, resumable, queryable.

``rt-drake experiment campaign CAMPAIGN.yaml --out DB`` runs every
(object, cup, trial, variant) row of a campaign file, locally or on a Ray
cluster, into one SQLite database; ``rt-drake experiment report DB`` writes
its summary tables and plots.

- :mod:`._spec`, :mod:`._catalogue`, :mod:`._definition`: the campaign file, its
  objects and cups, its rows and content hash (:func:`load_campaign`).
- :mod:`._row_types`: a row's key, :class:`Variant`, status and result.
- :mod:`._variants`: the registry of comparisons, one function per variant.
- :mod:`._worker`: a worker's shared inputs (built once) and one task.
- :mod:`._local_executor`, :mod:`._ray_executor`: where the tasks run.
- :mod:`._store`: the SQLite database; :mod:`._runner`: the driver;
  :mod:`._campaign_progress`: done / total, failures, ETA.
- :mod:`._report`, :mod:`._report_plots`: the report from the database.
"""

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
    "Variant",
    "load_campaign",
    "make_executor",
    "run_campaign",
    "summarize_rows",
    "write_campaign_report",
]
