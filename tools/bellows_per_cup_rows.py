"""``tools/bellows_trial.py`` with per-cup friction rows added to the tool's set.

    python tools/bellows_per_cup_rows.py SCENARIO [bellows_trial.py's options]

A study of a planner change, not the planner: the elastic W_shared of
:mod:`rt_drake.contact.load_sharing` splits the rims' normal forces as
springs but lets friction split the tangential load ``t = (tau_z, f_x,
f_y)`` between the cups freely. Here the rim points are equal springs
tangentially too: a shift d and turn r_z of the object on the tool load
point i with ``k (d + r_z z x p_i)``, so ``t = K [r_z; d]`` with (unit k)

    K = [[sum |p_i|^2, -sum y_i, sum x_i],
         [-sum y_i,    n,        0      ],
         [sum x_i,     0,        n      ]]

and cup c carries ``t_c = K_c K^-1 t`` (K_c: the sums over its points).
Added rows, per cup c and per facet direction d of its points' friction
polygons (:func:`~rt_drake.contact.load_sharing.facet_directions`): ``d .
t_c(w) <= sum_{i in c} h_i(d) n_i(w)``. The tool's own rows stay.
"""

from __future__ import annotations

import runpy
import sys
from pathlib import Path

import numpy as np

import rt_drake.contact.load_sharing as load_sharing
from rt_drake.contact.tool import ToolParameters

_tool_rows = load_sharing.shared_load_polytope


def _stiffness(p: np.ndarray) -> np.ndarray:
    """K of the module docstring for rim points ``p`` (m, 2 columns)."""
    n = len(p)
    sx, sy = p[:, 0].sum(), p[:, 1].sum()
    return np.array([[(p**2).sum(), -sy, sx], [-sy, n, 0.0], [sx, 0.0, n]])


def per_cup_polytope(tool: ToolParameters) -> tuple[np.ndarray, np.ndarray]:
    """The tool's elastic rows and each cup's friction rows, unit-norm."""
    F, g = _tool_rows(tool)
    springs = load_sharing.rim_springs(tool)
    n0 = -springs.split @ springs.suction
    normal_part = np.zeros((3, 6))
    normal_part[[0, 1, 2], [0, 1, 5]] = 1.0
    tangential_part = np.zeros((3, 6))
    tangential_part[[0, 1, 2], [2, 3, 4]] = 1.0
    dn_dw = springs.split @ normal_part
    xy = springs.positions
    per_cup = len(xy) // len(tool.cups)
    K_inv = np.linalg.inv(_stiffness(xy))
    rows, offsets = [F], [g]
    for c in range(len(tool.cups)):
        points = np.arange(c * per_cup, (c + 1) * per_cup)
        share = _stiffness(xy[points]) @ K_inv
        polygons = [springs.polygons[i] for i in points]
        D = load_sharing.facet_directions(polygons)
        support = np.column_stack([np.max(D @ v.T, axis=1) for v in polygons])
        R = D @ share @ tangential_part - support @ dn_dw[points]
        norms = np.linalg.norm(R, axis=1)
        rows.append(R / norms[:, None])
        offsets.append(support @ n0[points] / norms)
    return np.vstack(rows), np.concatenate(offsets)


if __name__ == "__main__":
    load_sharing.shared_load_polytope = per_cup_polytope
    sys.argv[0] = "bellows_trial.py"
    runpy.run_path(
        str(Path(__file__).with_name("bellows_trial.py")), run_name="__main__"
    )
