"""Compiled (numba) kernels of :mod:`rt_drake.dynamics.chain`.

Scalar arithmetic in loops: small temporary arrays would dominate the cost.
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def frames(q, pre, post, index, axis, X_BC, z, o, R_out, p_out):  # noqa: D417
    """Forward kinematics of the chain at each row of q (see SerialChain.frames)."""
    steps = pre.shape[0]
    R = np.empty((3, 3))
    T = np.empty((3, 3))
    p = np.empty(3)
    rot = np.zeros((4, 4))
    for i in range(q.shape[0]):
        for r in range(3):
            p[r] = 0.0
            for c in range(3):
                R[r, c] = 1.0 if r == c else 0.0
        j = 0
        for s in range(steps):
            compose(R, p, pre[s], T)
            if index[s] < 0:
                continue
            k = axis[s]
            for r in range(3):
                z[i, j, r] = R[r, 0] * k[0] + R[r, 1] * k[1] + R[r, 2] * k[2]
                o[i, j, r] = p[r]
            angle = q[i, index[s]]
            sn, vs = np.sin(angle), 1.0 - np.cos(angle)
            # Rodrigues: Rot = I + sin K + (1 - cos) K^2, K = [k]x
            for r in range(3):
                for c in range(3):
                    rot[r, c] = (1.0 if r == c else 0.0) + vs * (
                        k[r] * k[c] - (1.0 if r == c else 0.0)
                    )
                rot[r, 3] = 0.0
            rot[0, 1] -= sn * k[2]
            rot[0, 2] += sn * k[1]
            rot[1, 0] += sn * k[2]
            rot[1, 2] -= sn * k[0]
            rot[2, 0] -= sn * k[1]
            rot[2, 1] += sn * k[0]
            compose(R, p, rot, T)
            compose(R, p, post[s], T)
            j += 1
        compose(R, p, X_BC, T)
        for r in range(3):
            p_out[i, r] = p[r]
            for c in range(3):
                R_out[i, r, c] = R[r, c]


@njit(cache=True)
def compose(R, p, X, T):
    """(R, p) <- (R, p) X for a 4x4 homogeneous X; T is scratch."""
    for r in range(3):
        p[r] += R[r, 0] * X[0, 3] + R[r, 1] * X[1, 3] + R[r, 2] * X[2, 3]
        for c in range(3):
            T[r, c] = R[r, 0] * X[0, c] + R[r, 1] * X[1, c] + R[r, 2] * X[2, c]
    for r in range(3):
        for c in range(3):
            R[r, c] = T[r, c]


@njit(cache=True)
def accelerations(z, o, R, p, dq, ddq, p_CS, out):  # noqa: D417
    """``out = (w, v, al, a)`` of point S per unit s (module docstring), in W.

    Scalar arithmetic only: small temporary arrays would dominate the cost.
    """
    n = z.shape[1]
    for i in range(z.shape[0]):
        k0, k1, k2 = p_CS[0], p_CS[1], p_CS[2]
        s0 = p[i, 0] + R[i, 0, 0] * k0 + R[i, 0, 1] * k1 + R[i, 0, 2] * k2
        s1 = p[i, 1] + R[i, 1, 0] * k0 + R[i, 1, 1] * k1 + R[i, 1, 2] * k2
        s2 = p[i, 2] + R[i, 2, 0] * k0 + R[i, 2, 1] * k1 + R[i, 2, 2] * k2
        v0 = v1 = v2 = 0.0
        for j in range(n):
            z0, z1, z2 = z[i, j, 0], z[i, j, 1], z[i, j, 2]
            r0, r1, r2 = s0 - o[i, j, 0], s1 - o[i, j, 1], s2 - o[i, j, 2]
            d = dq[i, j]
            v0 += (z1 * r2 - z2 * r1) * d
            v1 += (z2 * r0 - z0 * r2) * d
            v2 += (z0 * r1 - z1 * r0) * d
        w0 = w1 = w2 = 0.0  # sum_{k<j} z_k q'_k
        c0 = c1 = c2 = 0.0  # sum_{k<j} q'_k z_k x o_k
        l0 = l1 = l2 = 0.0
        a0 = a1 = a2 = 0.0
        for j in range(n):
            z0, z1, z2 = z[i, j, 0], z[i, j, 1], z[i, j, 2]
            o0, o1, o2 = o[i, j, 0], o[i, j, 1], o[i, j, 2]
            r0, r1, r2 = s0 - o0, s1 - o1, s2 - o2
            d, dd = dq[i, j], ddq[i, j]
            # z' = w- x z ;  o' = w- x o - c
            y0, y1, y2 = w1 * z2 - w2 * z1, w2 * z0 - w0 * z2, w0 * z1 - w1 * z0
            e0 = w1 * o2 - w2 * o1 - c0
            e1 = w2 * o0 - w0 * o2 - c1
            e2 = w0 * o1 - w1 * o0 - c2
            # (v - o')
            f0, f1, f2 = v0 - e0, v1 - e1, v2 - e2
            l0 += z0 * dd + y0 * d
            l1 += z1 * dd + y1 * d
            l2 += z2 * dd + y2 * d
            a0 += (z1 * r2 - z2 * r1) * dd + (y1 * r2 - y2 * r1 + z1 * f2 - z2 * f1) * d
            a1 += (z2 * r0 - z0 * r2) * dd + (y2 * r0 - y0 * r2 + z2 * f0 - z0 * f2) * d
            a2 += (z0 * r1 - z1 * r0) * dd + (y0 * r1 - y1 * r0 + z0 * f1 - z1 * f0) * d
            c0 += (z1 * o2 - z2 * o1) * d
            c1 += (z2 * o0 - z0 * o2) * d
            c2 += (z0 * o1 - z1 * o0) * d
            w0 += z0 * d
            w1 += z1 * d
            w2 += z2 * d
        out[0, i, 0], out[0, i, 1], out[0, i, 2] = w0, w1, w2
        out[1, i, 0], out[1, i, 1], out[1, i, 2] = v0, v1, v2
        out[2, i, 0], out[2, i, 1], out[2, i, 2] = l0, l1, l2
        out[3, i, 0], out[3, i, 1], out[3, i, 2] = a0, a1, a2


@njit(cache=True)
def wrench_terms(R, motion, mass, p, inertia, g_W, a_w, b_w, c_w):  # noqa: D417
    """Newton-Euler in C split into u, x and constant terms (rt_drake.dynamics.chain).

    ``motion = (w, v, al, a)`` of Scm in W from :func:`accelerations`; each
    row i is rotated into C by ``R[i]^T``, then::

        a_w = [I w + m p x v;  m v]
        b_w = [I al + w x (I w) + m p x a;  m a]
        c_w = [-m p x g;  -m g]
    """
    x = np.empty((5, 3))  # w, v, al, a, g in C
    Iw = np.empty(3)
    Ial = np.empty(3)
    for i in range(R.shape[0]):
        for k in range(5):
            for r in range(3):
                if k < 4:
                    y0, y1, y2 = motion[k, i, 0], motion[k, i, 1], motion[k, i, 2]
                else:
                    y0, y1, y2 = g_W[0], g_W[1], g_W[2]
                x[k, r] = R[i, 0, r] * y0 + R[i, 1, r] * y1 + R[i, 2, r] * y2
        for r in range(3):
            Iw[r] = inertia[r, 0] * x[0, 0] + inertia[r, 1] * x[0, 1]
            Iw[r] += inertia[r, 2] * x[0, 2]
            Ial[r] = inertia[r, 0] * x[2, 0] + inertia[r, 1] * x[2, 1]
            Ial[r] += inertia[r, 2] * x[2, 2]
        for r in range(3):
            r1, r2 = (r + 1) % 3, (r + 2) % 3
            p_v = p[r1] * x[1, r2] - p[r2] * x[1, r1]
            p_a = p[r1] * x[3, r2] - p[r2] * x[3, r1]
            p_g = p[r1] * x[4, r2] - p[r2] * x[4, r1]
            gyro = x[0, r1] * Iw[r2] - x[0, r2] * Iw[r1]
            a_w[i, r] = Iw[r] + mass * p_v
            a_w[i, 3 + r] = mass * x[1, r]
            b_w[i, r] = Ial[r] + gyro + mass * p_a
            b_w[i, 3 + r] = mass * x[3, r]
            c_w[i, r] = -mass * p_g
            c_w[i, 3 + r] = -mass * x[4, r]


__all__ = ["accelerations", "compose", "frames", "wrench_terms"]
