"""Validation campaigns: many objects, cups and transports, resumable, queryable.

``rt-drake experiment campaign CAMPAIGN.yaml --out DB`` runs every
(object, cup, trial, variant) row of a campaign file, locally or on a Ray
cluster, into one SQLite database; ``rt-drake experiment report DB`` writes
its summary tables and plots.

- :mod:`.spec`, :mod:`.catalogue`, :mod:`.campaign`: the campaign file, its
  objects and cups, its rows and content hash (:func:`load_campaign`).
- :mod:`.rows`: a row's key, :class:`Variant`, status and result.
- :mod:`.variants`: the registry of comparisons, one function per variant.
- :mod:`.worker`: a worker's shared inputs (built once) and one task.
- :mod:`.local_executor`, :mod:`.ray_executor`: where the tasks run.
- :mod:`.store`: the SQLite database; :mod:`.runner`: the driver;
  :mod:`.progress`: done / total, failures, ETA.
- :mod:`.report`, :mod:`.report_plots`: the report from the database.
"""

from rt_drake.experiments.campaign.campaign_errors import (
    CampaignError,
    CampaignMismatchError,
    ExecutorUnavailableError,
)
from rt_drake.experiments.campaign.definition import (
    Campaign,
    Combination,
    load_campaign,
)
from rt_drake.experiments.campaign.report import summarize_rows, write_campaign_report
from rt_drake.experiments.campaign.row_types import (
    Outcome,
    RowKey,
    RowResult,
    Status,
    Variant,
)
from rt_drake.experiments.campaign.runner import (
    CampaignRun,
    ExecutorKind,
    make_executor,
    run_campaign,
)
from rt_drake.experiments.campaign.variants import VARIANTS

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
