"""The paper's experiments in simulation, and their reports.

- :mod:`.rollout`: play one MOVE in the cycle's physics and measure slip.
- :mod:`.transport`: Table I, random transports with and without the grasp
  constraint; :mod:`.optimized_transport`: the optimised MOVE of each
  (issue 13); :mod:`.transport_report` and :mod:`.plots` write its report.
- :mod:`.robust_transport`: Table I with objects known only to an
  uncertainty set, nominal and robust plans played with a true object;
  :mod:`.robust_report` writes its report.
- :mod:`.cycle_report`: Table II, the cycle's timing breakdown
  (:class:`CycleReport`).
"""

from rt_drake.experiments.cycle_report import (
    REPORT_FILES,
    CycleReport,
    RunSettings,
    cycle_report,
    summary_line,
    table_markdown,
    write_report,
)
from rt_drake.experiments.robust_report import (
    ROBUST_FILES,
    robust_table,
    write_robust_report,
)
from rt_drake.experiments.robust_transport import (
    robust_trial,
    run_robust_transport_experiment,
)
from rt_drake.experiments.rollout import (
    SLIP_ROTATION,
    SLIP_TRANSLATION,
    SPEED_FACTORS,
    Rollout,
    critical_speed,
    simulate_move,
)
from rt_drake.experiments.transport_experiment import (
    run_transport_experiment,
    summarize,
    transport_trial,
)
from rt_drake.experiments.transport_report import (
    TRANSPORT_FILES,
    optimized_summary,
    transport_table,
    write_transport_report,
)

__all__ = [
    "REPORT_FILES",
    "ROBUST_FILES",
    "SLIP_ROTATION",
    "SLIP_TRANSLATION",
    "SPEED_FACTORS",
    "TRANSPORT_FILES",
    "CycleReport",
    "Rollout",
    "RunSettings",
    "critical_speed",
    "cycle_report",
    "optimized_summary",
    "robust_table",
    "robust_trial",
    "run_robust_transport_experiment",
    "run_transport_experiment",
    "simulate_move",
    "summarize",
    "summary_line",
    "table_markdown",
    "transport_table",
    "transport_trial",
    "write_report",
    "write_robust_report",
    "write_transport_report",
]
