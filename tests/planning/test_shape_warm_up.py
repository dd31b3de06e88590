"""The optimiser's warm-up leaves nothing for the first timed MOVE to load.

The cycle's first MOVE is planned on the wall clock while the arm waits
(:mod:`rt_drake.simulation.motion`). ``cmaes`` is imported lazily by the
search (it loads ``scipy.stats``, about 1.5 s), so the warm-up that
``OnlineMotions`` runs before the cycle must import it: in session 8 a
missing import put 0.61 s of plan on the vacuum-sensor cycle's critical path.
"""

from __future__ import annotations

import sys

import pytest

from rt_drake.shaping import warm_up


def test_warm_up_imports_the_search_package(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delitem(sys.modules, "cmaes", raising=False)
    warm_up.__wrapped__()  # the cached warm-up, run again
    assert "cmaes" in sys.modules
