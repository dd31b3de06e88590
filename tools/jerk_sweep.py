"""Every case of the retime fingerprint, retimed with jerk limits and checked.

Run: ``PYTHONPATH=. nice python tools/jerk_sweep.py``.

Each case of ``tools/retime_fingerprint.py`` (Table II's MOVE-like paths,
three objects, torque and tight limits, coarse and explicit grids, Drake
trajectories of three kinds, 60 random paths) is retimed with jerk limits
of 20 x its acceleration limits (per second), and every result is checked
by ``check_trajectory`` at 1 kHz. Prints each refusal and each check beyond
the 1e-3 contract, then the counts, the worst margin and the CPU time.
"""

from __future__ import annotations

import collections
import importlib.util
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

from rt_drake.retiming import JointLimits, RetimeError, check_trajectory

ROOT = Path(__file__).resolve().parents[1]
#: Jerk limits of the sweep, as multiples of the acceleration limits (1/s).
PER_SECOND = 20.0


def fingerprint_tool() -> Any:
    """tools/retime_fingerprint.py as a module (it imports benchmarks/)."""
    sys.path.insert(0, str(ROOT / "benchmarks"))
    spec = importlib.util.spec_from_file_location(
        "retime_fingerprint", ROOT / "tools" / "retime_fingerprint.py"
    )
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules["retime_fingerprint"] = module
    spec.loader.exec_module(module)
    return module


def main() -> None:
    """Retime every case with jerk limits; print refusals, failures, counts."""
    tool = fingerprint_tool()
    plain_retime = tool.retime
    last: list[tuple[Any, JointLimits, Any]] = []

    def jerk_retime(plant, path, limits, grasp, grid=100, **kwargs):  # noqa: ANN001, ANN202
        jerk = JointLimits(
            limits.velocity, limits.acceleration, limits.torque,
            PER_SECOND * limits.acceleration,
        )  # fmt: skip
        last.append((plant, jerk, grasp))
        return plain_retime(plant, path, jerk, grasp, grid, **kwargs)

    tool.retime = jerk_retime
    counts: collections.Counter[str] = collections.Counter()
    worst, cpu = np.inf, []
    for name, thunk in tool.cases():
        start = time.process_time()
        try:
            result = thunk()
        except RetimeError as error:
            counts[type(error).__name__] += 1
            print(f"{name}: {type(error).__name__}: {error}")
            continue
        cpu.append(time.process_time() - start)
        plant, limits, grasp = last[-1]
        check = check_trajectory(plant, result.trajectory, limits, grasp)
        worst = min(worst, check.min_margin())
        counts["held" if check.passed() else "over the contract"] += 1
        if not check.passed():
            print(f"{name}: over the contract\n{check.summary()}")
    print(
        f"{dict(counts)}; worst margin {worst:+.5f}; CPU s per retime median "
        f"{np.median(cpu):.3f}, max {max(cpu):.3f}"
    )


if __name__ == "__main__":
    main()
