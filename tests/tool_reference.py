"""An LP reference for multi-cup tools, written apart from rt_drake.contact.

Every rim force of every cup is a convex combination of its friction
pyramid's vertices (not the H-form of ``rt_drake.contact._lp``): the tests
of the tool's exact set and of retiming under it compare against this.
A tool is given as ``[(CupParameters, p_TC), ...]`` (cups with the tool
frame's axes).
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import linprog

from rt_drake.contact import CupParameters


def rim_forces(tool_cups: list[tuple[CupParameters, np.ndarray]]):
    """Columns mapping pyramid-vertex weights to wrenches about T, in T.

    Each rim point's force is ``sum_j lam_j v_j`` with v_j the pyramid's
    base vertices ``f_max (mu cos a_j, mu sin a_j, 1)`` in the point's frame
    (radial x), ``lam >= 0`` and ``sum_j lam_j <= 1`` (the apex is 0).
    """
    columns, groups, suction = [], [], np.zeros(6)
    for cup, p_TC in tool_cups:
        for i in range(cup.points):
            angle = 2.0 * np.pi * i / cup.points
            c, s = np.cos(angle), np.sin(angle)
            R = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
            p = p_TC + cup.radius * np.array([c, s, 0.0])
            group = []
            for j in range(cup.sides):
                a = 2.0 * np.pi * j / cup.sides
                local = cup.max_normal_force * np.array(
                    [cup.friction * np.cos(a), cup.friction * np.sin(a), 1.0]
                )
                force = R @ local
                group.append(len(columns))
                columns.append(np.concatenate([np.cross(p, force), force]))
            groups.append(group)
        pull = np.array([0.0, 0.0, -cup.suction_force])
        suction += np.concatenate([np.cross(p_TC, pull), pull])
    return np.array(columns).T, groups, suction


def residual(wrenches: np.ndarray, tool_cups) -> np.ndarray:
    """``min ||sum of rim-force wrenches + suction - w||_inf`` per wrench."""
    G, groups, suction = rim_forces(tool_cups)
    n = G.shape[1]
    sums = np.zeros((len(groups), n + 1))
    for row, group in enumerate(groups):
        sums[row, group] = 1.0
    ones = np.ones((6, 1))
    A_ub = np.vstack([sums, np.hstack([G, -ones]), np.hstack([-G, -ones])])
    cost = np.zeros(n + 1)
    cost[-1] = 1.0
    out = []
    for w in wrenches:
        target = w - suction
        b_ub = np.concatenate([np.ones(len(groups)), target, -target])
        result = linprog(cost, A_ub=A_ub, b_ub=b_ub, bounds=(0.0, None))
        assert result.status == 0, result.message
        out.append(result.fun)
    return np.array(out)
