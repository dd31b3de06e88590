"""The natural periods of an object held by a tool of bellows cups.

The tool T is held still; each cup i (frame C_i at ``X_TCi``) hangs its lip
L_i on a bushing (:mod:`._bellows`: torque ``-K_t q`` with ``K_t =
diag(k_tilt, k_tilt, k_tor)``, force ``-K_f p`` with ``K_f = diag(k_lat,
k_lat, k_ax)``, in C_i), and the object rides on the lips as one rigid body.
For a small displacement ``d = [theta; x]`` of that body at T's origin
(rotation theta, rad, and translation x, m, both in T), cup i's bushing
deflects by

    J_i d = [R_TCi^T theta; R_TCi^T (x - [p_TCi]x theta)]

(rotation and translation in C_i), so the bushings in parallel store
``1/2 d^T K d`` with the tool's stiffness (6 x 6, in T, about T's origin)

    K = sum_i J_i^T diag(K_t, K_f) J_i.

Two cups a distance ``d_i`` off the tool's axis thus stiffen torsion about
it by ``k_lat d_i^2`` each and tilt about an axis in their face plane by
``k_ax`` times their squared distance from it. The held body (object and
lips) has the spatial inertia at T's origin

    M = [[I_To, m [p]x], [-m [p]x, m 1]],   I_To = I_cm + m [p]x^T [p]x,

``p`` its centre of mass from T's origin, in T. The modes solve
``K v = omega^2 M v``; the periods are ``2 pi / omega`` (s).

The bellows' dampers in parallel give ``C = sum_i J_i^T diag(C_t, C_f) J_i``
in the same way. Driven by a load ``w(t)`` (the wrench the tool must put on
the held body, 6, in T about T's origin: its inertia and weight), the body
on the bellows deflects as ``M d'' + C d' + K d = w``. With the modes
M-normalised (``V^T M V = 1``, ``V^T K V = diag(omega^2)``) and C taken
diagonal in them (``zeta_k = v_k^T C v_k / (2 omega_k)``), each modal
coordinate ``q_k = v_k^T M d`` obeys

    q_k'' + 2 zeta_k omega_k q_k' + omega_k^2 q_k = v_k^T w(t),

started at rest in equilibrium (``q_k(0) = v_k^T w(0) / omega_k^2``). The
bellows carry ``K d = M V diag(omega^2) q``: the quasi-static wrench ``w``
plus the ring. A step in ``w`` peaks at ``1 + exp(-zeta pi / sqrt(1 -
zeta^2))`` of its size; a ramp of x periods (undamped) at ``1 + |sin(pi x)
/ (pi x)|``.
"""

from __future__ import annotations

import dataclasses

import numpy as np
from pydrake.math import RigidTransform
from scipy.linalg import eigh

from rt_drake.errors import InputError
from rt_drake.model.cup_physics import BellowsCup
from rt_drake.types.held_object import HeldObject


def _skew(p: np.ndarray) -> np.ndarray:
    """``[p]x``: ``[p]x v = p x v``."""
    return np.array([[0.0, -p[2], p[1]], [p[2], 0.0, -p[0]], [-p[1], p[0], 0.0]])


def tool_stiffness(cup: BellowsCup, X_TCs: list[RigidTransform]) -> np.ndarray:
    """``K`` (6, 6, in T about T's origin, ``[theta; x]``; N m/rad, N/m).

    The sum over the cups of ``J_i^T diag(K_t, K_f) J_i`` (module docstring).
    """
    axes = (
        cup.tilt_stiffness,
        cup.torsion_stiffness,
        cup.lateral_stiffness,
        cup.axial_stiffness,
    )
    return _in_parallel("tool_stiffness", axes, X_TCs)


def tool_damping(cup: BellowsCup, X_TCs: list[RigidTransform]) -> np.ndarray:
    """``C`` (6, 6, in T about T's origin, ``[theta; x]``; N m s/rad, N s/m).

    The sum over the cups of ``J_i^T diag(C_t, C_f) J_i`` (module docstring).
    """
    axes = (
        cup.tilt_damping,
        cup.torsion_damping,
        cup.lateral_damping,
        cup.axial_damping,
    )
    return _in_parallel("tool_damping", axes, X_TCs)


def _in_parallel(
    name: str, axes: tuple[float, float, float, float], X_TCs: list[RigidTransform]
) -> np.ndarray:
    """``sum_i J_i^T diag(a_t, a_t, a_tor, a_lat, a_lat, a_ax) J_i``, in T.

    The cups' bushings in parallel, each with the per-axis values ``axes =
    (a_t, a_tor, a_lat, a_ax)`` (tilt, torsion, lateral, axial) in its cup
    frame C_i: the stiffnesses give ``K``, the dampings ``C``. ``name`` is
    the public function's, for the error.
    """
    if not X_TCs:
        raise InputError(f"{name}: X_TCs must hold at least one cup pose")
    tilt, torsion, lateral, axial = axes
    K_local = np.diag([tilt, tilt, torsion, lateral, lateral, axial])
    K = np.zeros((6, 6))
    for X_TC in X_TCs:
        R = X_TC.rotation().matrix()
        J = np.zeros((6, 6))
        J[:3, :3] = R.T
        J[3:, :3] = -R.T @ _skew(X_TC.translation())
        J[3:, 3:] = R.T
        K += J.T @ K_local @ J
    return K


def held_inertia(
    held: HeldObject, cup: BellowsCup, X_TCs: list[RigidTransform]
) -> np.ndarray:
    """``M`` (6, 6, in T about T's origin, ``[theta; x]``; kg m^2, kg).

    The object (``held``, its inertia in the tool frame T) and the lips: a
    mass ``lip_mass`` at each cup origin with moment of inertia
    ``lip_inertia`` about each axis.
    """
    bodies = [(held.mass, np.asarray(held.p_CoScm_C), np.asarray(held.I_Scm_C))]
    bodies += [
        (cup.lip_mass, X_TC.translation(), cup.lip_inertia * np.eye(3))
        for X_TC in X_TCs
    ]
    M = np.zeros((6, 6))
    for mass, p, I_cm in bodies:
        S = _skew(p)
        M[:3, :3] += I_cm + mass * S.T @ S
        M[:3, 3:] += mass * S
        M[3:, :3] -= mass * S
        M[3:, 3:] += mass * np.eye(3)
    return M


def mode_periods(K: np.ndarray, M: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The periods (s, longest first) and mode shapes (columns) of ``K v = w^2 M v``."""
    omega2, modes = eigh(K, M)
    if omega2[0] <= 0.0:
        raise InputError(f"mode_periods: K is not positive definite ({omega2[0]=})")
    order = np.argsort(omega2)
    return 2.0 * np.pi / np.sqrt(omega2[order]), modes[:, order]


def modal_damping_ratios(
    K: np.ndarray, C: np.ndarray, M: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(omega, zeta, V)``: rad/s, damping ratios, M-normalised modes (columns).

    Slowest first; ``zeta_k = v_k^T C v_k / (2 omega_k)`` (C taken diagonal
    in the modes, module docstring).
    """
    omega2, V = eigh(K, M)
    if omega2[0] <= 0.0:
        raise InputError(
            f"modal_damping_ratios: K is not positive definite ({omega2[0]=})"
        )
    omega = np.sqrt(omega2)
    zeta = np.einsum("ik,ij,jk->k", V, C, V) / (2.0 * omega)
    return omega, zeta, V


def bellows_wrench(
    t: np.ndarray, w: np.ndarray, K: np.ndarray, C: np.ndarray, M: np.ndarray
) -> np.ndarray:
    """The wrench ``K d(t)`` (N, 6, in T) the bellows carry under the load ``w``.

    ``t`` (N,) s, equally spaced and increasing; ``w`` (N, 6) the
    quasi-static load ``[tau; f]`` (N m, N) in T about T's origin, linear
    between samples. Each mode's
    ``q_k'' + 2 zeta_k omega_k q_k' + omega_k^2 q_k = v_k^T w`` is integrated
    exactly for that piecewise-linear load (``scipy.signal.lsim``, matrix
    exponential), from rest in equilibrium with ``w[0]`` (module docstring);
    then ``K d = M V diag(omega^2) q``.
    """
    t = np.asarray(t, dtype=float)
    w = np.asarray(w, dtype=float)
    if t.ndim != 1 or w.shape != (t.size, 6) or t.size < 2:
        raise InputError(
            f"bellows_wrench: need t (N,) and w (N, 6), got {t.shape}, {w.shape}"
        )
    steps = np.diff(t)
    if steps.min() <= 0.0 or np.ptp(steps) > 1e-9 * steps.mean():
        raise InputError("bellows_wrench: t must be equally spaced and increasing")
    # Imported here: scipy.signal (with scipy.stats) is about a quarter of
    # the import time of every process that loads the retimer.
    from scipy.signal import lsim

    omega, zeta, V = modal_damping_ratios(K, C, M)
    loads = w @ V  # (N, modes): v_k^T w
    q = np.empty_like(loads)
    for k, (om, ze) in enumerate(zip(omega, zeta, strict=True)):
        A = np.array([[0.0, 1.0], [-(om**2), -2.0 * ze * om]])
        system = (A, np.array([[0.0], [1.0]]), np.array([[1.0, 0.0]]), np.zeros((1, 1)))
        x0 = np.array([loads[0, k] / om**2, 0.0])
        _, q[:, k], _ = lsim(system, loads[:, k], t - t[0], X0=x0, interp=True)
    return (q * omega**2) @ V.T @ M


@dataclasses.dataclass(frozen=True, eq=False)
class BellowsTool:
    """A tool of identical bellows cups: ``cup`` at each pose ``X_TCs[i]`` in T.

    What the ring of an object held by it needs (module docstring): the
    stiffness ``K`` and damping ``C`` (6, 6, in T about T's origin) and the
    held body's inertia ``M`` (:func:`held_inertia`).

    Attributes:
        cup: The catalogue cup (:func:`rt_drake.model.cup_physics.load_bellows_cup`).
        X_TCs: Each cup's pose in the tool frame T (at least one).
        stiffness: ``K``, :func:`tool_stiffness`.
        damping: ``C``, :func:`tool_damping`.
    """

    cup: BellowsCup
    X_TCs: tuple[RigidTransform, ...]
    stiffness: np.ndarray = dataclasses.field(init=False, repr=False)
    damping: np.ndarray = dataclasses.field(init=False, repr=False)

    def __post_init__(self) -> None:
        poses = list(self.X_TCs)
        object.__setattr__(self, "stiffness", tool_stiffness(self.cup, poses))
        object.__setattr__(self, "damping", tool_damping(self.cup, poses))

    def inertia(self, held: HeldObject) -> np.ndarray:
        """``M`` of ``held`` (its inertia in T) and the lips, :func:`held_inertia`."""
        return held_inertia(held, self.cup, list(self.X_TCs))

    def carried(self, t: np.ndarray, w: np.ndarray, held: HeldObject) -> np.ndarray:
        """``K d(t)`` (N, 6, in T) under the load ``w`` on ``held``.

        :func:`bellows_wrench` with this tool's ``K``, ``C`` and ``held``'s ``M``.
        """
        return bellows_wrench(t, w, self.stiffness, self.damping, self.inertia(held))


__all__ = [
    "BellowsTool",
    "bellows_wrench",
    "held_inertia",
    "modal_damping_ratios",
    "mode_periods",
    "tool_damping",
    "tool_stiffness",
]
