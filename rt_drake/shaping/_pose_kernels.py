"""Compiled (numba) kernel of :mod:`rt_drake.shaping.cup_chain`.

Newton's method for cup poses, on the chain kernels of
:mod:`rt_drake.dynamics.chain_kernels`.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from rt_drake.dynamics.chain_kernels import frames


@njit(cache=True)
def solve_poses(  # noqa: D417
    q, R_target, p_target, pre, post, index, axis, X_BC, order, iterations,
    tolerance, error,
):  # fmt: skip
    """Newton's method for each row of q in place (see CupChain.solve_pose).

    Each row stops once its pose error ``|theta_err| + |p_err|`` is below
    ``tolerance``; ``error`` gets the last error computed.
    """
    n = order.shape[0]
    row = np.empty((1, q.shape[1]))
    z, o = np.empty((1, n, 3)), np.empty((1, n, 3))
    R, p = np.empty((1, 3, 3)), np.empty((1, 3))
    J = np.empty((6, n))
    A = np.empty((6, 6))
    L = np.zeros((6, 6))
    r = np.empty(6)
    y = np.empty(6)
    for i in range(q.shape[0]):
        error[i] = np.inf
        for _ in range(iterations):
            row[0] = q[i]
            frames(row, pre, post, index, axis, X_BC, z, o, R, p)
            # rotation vector of E = R_target R^T, and the position error
            E = np.empty((3, 3))
            for a in range(3):
                for b in range(3):
                    E[a, b] = (
                        R_target[i, a, 0] * R[0, b, 0]
                        + R_target[i, a, 1] * R[0, b, 1]
                        + R_target[i, a, 2] * R[0, b, 2]
                    )
            cos = min(max((E[0, 0] + E[1, 1] + E[2, 2] - 1.0) / 2.0, -1.0), 1.0)
            angle = np.arccos(cos)
            sin = np.sin(angle)
            scale = angle / (2.0 * sin) if sin > 1e-9 else 0.5
            r[0] = (E[2, 1] - E[1, 2]) * scale
            r[1] = (E[0, 2] - E[2, 0]) * scale
            r[2] = (E[1, 0] - E[0, 1]) * scale
            for a in range(3):
                r[3 + a] = p_target[i, a] - p[0, a]
            error[i] = np.sqrt(r[0] ** 2 + r[1] ** 2 + r[2] ** 2) + np.sqrt(
                r[3] ** 2 + r[4] ** 2 + r[5] ** 2
            )
            if error[i] < tolerance:
                break
            # J = [z_j; z_j x (p - o_j)], dq = J^T (J J^T + 1e-12 I)^-1 r
            for j in range(n):
                z0, z1, z2 = z[0, j, 0], z[0, j, 1], z[0, j, 2]
                d0 = p[0, 0] - o[0, j, 0]
                d1 = p[0, 1] - o[0, j, 1]
                d2 = p[0, 2] - o[0, j, 2]
                J[0, j], J[1, j], J[2, j] = z0, z1, z2
                J[3, j] = z1 * d2 - z2 * d1
                J[4, j] = z2 * d0 - z0 * d2
                J[5, j] = z0 * d1 - z1 * d0
            for a in range(6):
                for b in range(6):
                    total = 1e-12 if a == b else 0.0
                    for j in range(n):
                        total += J[a, j] * J[b, j]
                    A[a, b] = total
            # Cholesky A = L L^T, then L L^T y = r
            for a in range(6):
                for b in range(a + 1):
                    total = A[a, b]
                    for k in range(b):
                        total -= L[a, k] * L[b, k]
                    if a == b:
                        L[a, a] = np.sqrt(max(total, 1e-300))
                    else:
                        L[a, b] = total / L[b, b]
            for a in range(6):
                total = r[a]
                for k in range(a):
                    total -= L[a, k] * y[k]
                y[a] = total / L[a, a]
            for a in range(5, -1, -1):
                total = y[a]
                for k in range(a + 1, 6):
                    total -= L[k, a] * y[k]
                y[a] = total / L[a, a]
            for j in range(n):
                step = 0.0
                for a in range(6):
                    step += J[a, j] * y[a]
                q[i, order[j]] += step


__all__ = ["solve_poses"]
