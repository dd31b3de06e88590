"""The retimer computes today what it computed on the stored reference.

``data/retime_fingerprint.npz`` was recorded with
``python tools/retime_fingerprint.py record`` on 60ab596 (before the package
was reorganised): 104 retimes (the benchmark's MOVEs, three paths with each
object, torque and tight limits, coarse and explicit grids, Drake
trajectories of three kinds, 60 random paths), each as its duration, grid,
s'(s), s''(s), margins and counts, or its error's type and message. A change
meant to keep the retimer's results must keep every array to ``RTOL``;
a change meant to alter them records a new reference and says why.
"""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
REFERENCE = Path(__file__).resolve().parent / "data" / "retime_fingerprint.npz"
RTOL = 1e-9


def _tool():
    """tools/retime_fingerprint.py as a module (it imports benchmarks/)."""
    spec = importlib.util.spec_from_file_location(
        "retime_fingerprint", ROOT / "tools" / "retime_fingerprint.py"
    )
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules.setdefault("retime_fingerprint", module)
    spec.loader.exec_module(module)
    return module


@pytest.mark.slow
def test_every_case_matches_the_stored_fingerprint():
    tool = _tool()
    results = {
        f"{name}/{key}": value
        for name, thunk in tool.cases()
        for key, value in tool.fingerprint(thunk).items()
    }
    recorded = dict(np.load(REFERENCE))
    assert set(results) == set(recorded)
    assert len({key.split("/")[0] for key in recorded}) == 104
    worst, differ = 0.0, []
    for key, old in recorded.items():
        new = results[key]
        if old.dtype.kind in "US":
            if str(old) != str(new):
                differ.append(f"{key}: {old} vs {new}")
            continue
        if old.shape != new.shape:
            differ.append(f"{key}: shape {old.shape} vs {new.shape}")
            continue
        field = key.split("/")[1]
        worst = max(worst, tool.relative_difference(field, old, new))
    assert not differ, differ[:5]
    assert worst <= RTOL, f"largest relative difference {worst:.3g} > {RTOL:g}"


def test_the_comparison_sees_a_change_of_one_part_in_a_million():
    tool = _tool()
    old = np.array([1.0, 2.0, 3.0])
    assert tool.relative_difference("duration", old, old) == 0.0
    assert tool.relative_difference("duration", old, old * (1 + 1e-6)) > RTOL
