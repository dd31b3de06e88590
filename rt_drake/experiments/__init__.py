"""The paper's experiments in simulation, and their reports.

- :mod:`._rollout`: play one MOVE in the cycle's physics and measure slip.
- :mod:`._transport_experiment`: Table I, random transports with and without the grasp
  constraint; :mod:`._optimized_transport`: the optimised MOVE of each
  (issue 13); :mod:`._transport_report` and :mod:`._plots` write its report.
- :mod:`._robust_transport`: Table I with objects known only to an
  uncertainty set, nominal and robust plans played with a true object;
  :mod:`.robust_report` writes its report.
- :mod:`._stop_experiment`: protective stops of Table I's MOVEs in physics,
  grasp-aware and joint-brake.
- :mod:`._cycle_report`: Table II, the cycle's timing breakdown
  (:class:`CycleReport`); :mod:`.cycle_floor`: the floor it is measured
  against (:func:`cycle_floors`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from rt_drake._lazy import lazy_attributes

if TYPE_CHECKING:  # the lazy names below, for type checkers and IDEs
    from rt_drake.experiments._cycle_report import (
        REPORT_FILES,
        CycleReport,
        RunSettings,
        cycle_report,
        summary_line,
        table_markdown,
        write_report,
    )
    from rt_drake.experiments._robust_transport import (
        robust_trial,
        run_robust_transport_experiment,
    )
    from rt_drake.experiments._rollout import (
        SLIP_ROTATION,
        SLIP_TRANSLATION,
        SPEED_FACTORS,
        Rollout,
        critical_speed,
        simulate_move,
    )
    from rt_drake.experiments._stop_experiment import (
        STOP_FILES,
        run_stop_experiment,
        stop_table,
        stop_trial,
        summarize_stops,
    )
    from rt_drake.experiments._transport_experiment import (
        run_transport_experiment,
        summarize,
        transport_trial,
    )
    from rt_drake.experiments._transport_report import (
        TRANSPORT_FILES,
        optimized_summary,
        transport_table,
        write_transport_report,
    )
    from rt_drake.experiments.cycle_floor import (
        ObjectFloor,
        cycle_floors,
    )
    from rt_drake.experiments.robust_report import (
        ROBUST_FILES,
        robust_table,
        write_robust_report,
    )

__all__ = [
    "REPORT_FILES",
    "ROBUST_FILES",
    "SLIP_ROTATION",
    "SLIP_TRANSLATION",
    "SPEED_FACTORS",
    "STOP_FILES",
    "TRANSPORT_FILES",
    "CycleReport",
    "ObjectFloor",
    "Rollout",
    "RunSettings",
    "critical_speed",
    "cycle_floors",
    "cycle_report",
    "optimized_summary",
    "robust_table",
    "robust_trial",
    "run_robust_transport_experiment",
    "run_stop_experiment",
    "run_transport_experiment",
    "simulate_move",
    "stop_table",
    "stop_trial",
    "summarize",
    "summarize_stops",
    "summary_line",
    "table_markdown",
    "transport_table",
    "transport_trial",
    "write_report",
    "write_robust_report",
    "write_transport_report",
]

#: Public name -> module defining it, imported on first access (PEP 562).
_WHERE: dict[str, str] = {
    "robust_trial": "rt_drake.experiments._robust_transport",
    "run_robust_transport_experiment": "rt_drake.experiments._robust_transport",
    "SLIP_ROTATION": "rt_drake.experiments._rollout",
    "SLIP_TRANSLATION": "rt_drake.experiments._rollout",
    "SPEED_FACTORS": "rt_drake.experiments._rollout",
    "Rollout": "rt_drake.experiments._rollout",
    "critical_speed": "rt_drake.experiments._rollout",
    "simulate_move": "rt_drake.experiments._rollout",
    "STOP_FILES": "rt_drake.experiments._stop_experiment",
    "run_stop_experiment": "rt_drake.experiments._stop_experiment",
    "stop_table": "rt_drake.experiments._stop_experiment",
    "stop_trial": "rt_drake.experiments._stop_experiment",
    "summarize_stops": "rt_drake.experiments._stop_experiment",
    "run_transport_experiment": "rt_drake.experiments._transport_experiment",
    "summarize": "rt_drake.experiments._transport_experiment",
    "transport_trial": "rt_drake.experiments._transport_experiment",
    "TRANSPORT_FILES": "rt_drake.experiments._transport_report",
    "optimized_summary": "rt_drake.experiments._transport_report",
    "transport_table": "rt_drake.experiments._transport_report",
    "write_transport_report": "rt_drake.experiments._transport_report",
    "ObjectFloor": "rt_drake.experiments.cycle_floor",
    "cycle_floors": "rt_drake.experiments.cycle_floor",
    "REPORT_FILES": "rt_drake.experiments._cycle_report",
    "CycleReport": "rt_drake.experiments._cycle_report",
    "RunSettings": "rt_drake.experiments._cycle_report",
    "cycle_report": "rt_drake.experiments._cycle_report",
    "summary_line": "rt_drake.experiments._cycle_report",
    "table_markdown": "rt_drake.experiments._cycle_report",
    "write_report": "rt_drake.experiments._cycle_report",
    "ROBUST_FILES": "rt_drake.experiments.robust_report",
    "robust_table": "rt_drake.experiments.robust_report",
    "write_robust_report": "rt_drake.experiments.robust_report",
}

__getattr__, __dir__ = lazy_attributes(__name__, _WHERE, __all__)
