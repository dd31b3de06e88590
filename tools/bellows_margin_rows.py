"""``tools/bellows_margin.py`` measuring D on the rows the scenario retimes under.

    python tools/bellows_margin_rows.py SCENARIO [bellows_margin.py's options]

``tools/bellows_margin.py`` takes the dynamic load factor ``D`` on the
elastic tool set (``SharedLoadSet.of``) whatever ``tool.load_sharing`` the
scenario states. For a scenario with ``load_sharing: stiffness`` the MOVEs
are retimed under the stiffness split's rows
(:func:`rt_drake.contact.stiffness_shared_set`), so ``D`` must be measured
on those: this runs that tool with the set ``tool.load_sharing`` names
(elastic for ``elastic``, the stiffness split for ``stiffness``). Everything
else (modes, integration, iteration ``m <- 1 - 1 / D_max``) is the tool's.
"""

from __future__ import annotations

import runpy
import sys
from pathlib import Path

import rt_drake.contact.load_sharing as load_sharing
from rt_drake.contact import LoadSharing, ToolParameters, stiffness_shared_set
from rt_drake.model.resources import resolve_scenario_path
from rt_drake.model.scenario import load_scenario

_ELASTIC = load_sharing.SharedLoadSet


class _ScenarioRows:
    """Stands in for ``SharedLoadSet`` in the tool: ``of`` the scenario's set."""

    sharing = LoadSharing.ELASTIC

    @classmethod
    def of(cls, tool: ToolParameters) -> load_sharing.SharedLoadSet:
        """The tool's set under the scenario's ``tool.load_sharing``."""
        if cls.sharing is LoadSharing.STIFFNESS:
            return stiffness_shared_set(tool)
        return _ELASTIC.of(tool)


if __name__ == "__main__":
    scenario = load_scenario(resolve_scenario_path(sys.argv[1]))
    if scenario.tool is not None:
        _ScenarioRows.sharing = LoadSharing(scenario.tool.load_sharing)
    print(f"D on the rows of load_sharing: {_ScenarioRows.sharing.value}", flush=True)
    load_sharing.SharedLoadSet = _ScenarioRows  # type: ignore[misc]
    sys.argv[0] = "bellows_margin.py"
    runpy.run_path(
        str(Path(__file__).with_name("bellows_margin.py")), run_name="__main__"
    )
