"""The set of objects the robust grasp holds, as a set of inertial parameters.

Frames as in :mod:`rt_drake.dynamics.wrench`: C the cup frame (origin Co), O the
object frame, Scm the centre of mass; ``R_CO`` the object's axes in C.

**The wrench is linear in the inertial parameters.** About Co, in C, with
``alpha``, ``omega`` the angular acceleration and velocity of C, ``a`` the
acceleration of Co and ``g_C`` gravity, Newton-Euler reads::

    f   = m (a - g_C) + alpha x h + omega x (omega x h)
    tau = I_Co alpha + omega x (I_Co omega) + h x (a - g_C)

with ``h = m p`` (kg m, ``p = p_CoScm_C``) and ``I_Co = I_Scm + m S(p)``,
``S(p) = |p|^2 1 - p pᵀ`` (parallel axes). So for a given motion the wrench
``w = Y pi`` is linear in the ten parameters ``pi = (m, h, I_Co)``
(:data:`PARAMETER_NAMES`; :mod:`rt_drake.dynamics.regressor` builds Y along a path).
Along a path, ``a``, ``alpha`` are affine in (u, x) = (s'', s'^2) and
``omega = omega1 sqrt(x)``, so ``w = a(pi) u + b(pi) x + c(pi)`` with a, b, c
linear in pi.

**The uncertainty set is not a box in pi.** An object of the set
(:class:`~rt_drake.types.object_uncertainty.ObjectUncertainty`) has ``m`` in ``[m_lo,
m_hi]``, ``p = p0 + R_CO delta`` with ``|delta_j| <= d_j`` and principal
moments ``lambda_j`` in ``lambda0_j [1 - r, 1 + r]`` about the nominal's
principal axes ``e_j`` (in C). Its image in pi-space splits, exactly, as::

    pi = m pi1(p) + pi_I(lambda) + pi_E(m, delta)

    pi1(p)    = (1, p, S(p0) + S'(p0, p - p0))      affine in p
    pi_I      = (0, 0, sum_j lambda_j e_j e_jᵀ)      linear in lambda
    pi_E      = (0, 0, m S(R_CO delta))              second order in delta

with ``S'(p0, v) = 2 (p0 . v) 1 - p0 vᵀ - v p0ᵀ`` the derivative of S
(``m S(p) = m S(p0) + m S'(p0, delta_C) + m S(delta_C)``, exact). Which parts
are exact and which bounded:

- ``{m pi1(p)}`` over ``m`` in an interval and ``p`` in a box is the
  perspective of a box: **exact** and convex, the set ``{m (c1 + sum_j
  delta_j gamma_j)}`` with ``c1 = pi1(p0)`` and ``gamma_j = (0, R_CO e_j,
  S'(p0, R_CO e_j))``. So mass, first moment ``h = m p`` and the part of
  ``I_Co`` linear in them are taken exactly: the bilinear ``h = m p`` needs
  no bound.
- ``pi_I`` is linear in lambda: **exact**, a box (zonotope) in pi. It
  includes principal moments that break the triangle inequality (no real
  body): a superset, so sound.
- ``pi_E = m S(delta)`` (rotated by R_CO) is the only non-linear term: it is
  **bounded** by a box in the entries of ``S(delta)`` in O: each diagonal
  entry in ``[0, m_hi (d_k^2 + d_l^2)]`` and each off-diagonal one in
  ``[-m_hi d_k d_l, m_hi d_k d_l]`` (the exact range of each entry). It is
  second order in the CoM widths: below 1.4e-4 kg m^2 for the notebook's
  set, against its 3e-3 kg m^2.

The grasp is enforced on the Minkowski sum of the three parts, a set ``Q``
that CONTAINS every admissible object's pi (each of its three parts lies in
the corresponding part of Q; the sum only forgets that the m and delta of
the first and third parts are the same). Every piece is a "box" of one form::

    Q = { m (c1 + G1 sigma) + cz + Gz tau :  m in [m_lo, m_hi],
                                             |sigma|, |tau| <= 1 (entrywise) }

(:class:`ParameterBox`; the CoM widths folded into G1, the inertia and
``S(delta)`` widths into Gz, parallel generators merged). Since ``w`` is
linear in pi, ``F_k w(pi) <= g_k`` holds on Q iff it holds at Q's vertices,
and the worst vertex of row k at a motion point is known in closed form (no
enumeration; :mod:`rt_drake.retiming._robust_rows`)::

    max_Q n.w = max(m_lo B, m_hi B) + n.w(cz) + sum_j |n.w(Gz_j)|,
    B = n.w(c1) + sum_j |n.w(G1_j)|

For the notebook's set Q has 2 x 2^3 x 2^6 = 1024 vertices (mass, CoM
corner, three merged diagonal and three off-diagonal inertia generators); the
retimer only ever builds the few that bind. A finite list of objects (for
instance a dense sample, whose stacked constraint bounds the robust optimum
from below) is a union of degenerate boxes (:func:`object_list`).
"""

from __future__ import annotations

import dataclasses
import itertools
from typing import NamedTuple

import numpy as np

from rt_drake.errors import InputError
from rt_drake.types.held_object import HeldObject
from rt_drake.types.object_uncertainty import ObjectUncertainty

#: The ten inertial parameters about Co, in C: mass (kg), first moment h = m p
#: (kg m) and the entries of I_Co (kg m^2).
PARAMETER_NAMES = (
    "m",
    "h_x",
    "h_y",
    "h_z",
    "I_xx",
    "I_yy",
    "I_zz",
    "I_xy",
    "I_xz",
    "I_yz",
)
#: Generators whose directions agree to this (|cos| > 1 - tol) are merged.
_PARALLEL = 1e-12


def sym_entries(M: np.ndarray) -> np.ndarray:
    """``[M_xx, M_yy, M_zz, M_xy, M_xz, M_yz]`` of a symmetric 3x3 matrix."""
    return np.array([M[0, 0], M[1, 1], M[2, 2], M[0, 1], M[0, 2], M[1, 2]])


def parallel_axes(p: np.ndarray) -> np.ndarray:
    """``S(p) = |p|^2 1 - p pᵀ`` (m^2): I_Co = I_Scm + m S(p)."""
    p = np.asarray(p, dtype=float)
    return float(p @ p) * np.eye(3) - np.outer(p, p)


def inertial_parameters(held: HeldObject) -> np.ndarray:
    """Pi = (m, m p, I_Co) (10,) of an object (:data:`PARAMETER_NAMES`)."""
    m, p = held.mass, held.p_CoScm_C
    I_Co = held.I_Scm_C + m * parallel_axes(p)
    return np.concatenate([[m], m * p, sym_entries(I_Co)])


def held_object(pi: np.ndarray) -> HeldObject:
    """The object of parameters pi: ``p = h / m``, ``I_Scm = I_Co - m S(p)``."""
    pi = np.asarray(pi, dtype=float)
    m, p = float(pi[0]), pi[1:4] / pi[0]
    xx, yy, zz, xy, xz, yz = pi[4:]
    I_Co = np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])
    return HeldObject(mass=m, p_CoScm_C=p, I_Scm_C=I_Co - m * parallel_axes(p))


class SetVertex(NamedTuple):
    """A point of a parameter set: mass (kg) and centre of mass (m, in C).

    A vertex of the outer set Q need not be a body (its inertia may break
    the triangle inequality, or not be positive definite): the retimer's
    at-rest errors name it by its mass and centre of mass only.
    """

    mass: float
    p_CoScm_C: np.ndarray


def set_vertex(pi: np.ndarray) -> SetVertex:
    """The mass and centre of mass ``h / m`` of parameters pi."""
    pi = np.asarray(pi, dtype=float)
    return SetVertex(float(pi[0]), pi[1:4] / pi[0])


@dataclasses.dataclass(frozen=True, eq=False)
class ParameterBox:
    """``{m (c1 + G1 sigma) + cz + Gz tau}``, see the module docstring.

    Attributes:
        mass: (m_lo, m_hi), kg, 0 < m_lo <= m_hi.
        unit: (10,) c1, the parameters per kg at the nominal CoM.
        com: (k1, 10) G1, per kg, one row per CoM generator (widths folded).
        center: (10,) cz, the inertia part's centre (zero mass and h).
        inertia: (k2, 10) Gz, one row per inertia generator.
    """

    mass: tuple[float, float]
    unit: np.ndarray
    com: np.ndarray
    center: np.ndarray
    inertia: np.ndarray

    def vertex(self, heavy: bool, com_signs: np.ndarray, inertia_signs: np.ndarray):
        """Pi (10,) of the vertex with those choices (signs +-1)."""
        m = self.mass[1] if heavy else self.mass[0]
        return (
            m * (self.unit + com_signs @ self.com)
            + self.center
            + inertia_signs @ self.inertia
        )

    @property
    def vertex_count(self) -> int:
        """Vertices of the box (2 masses unless equal, 2 per generator)."""
        masses = 1 if self.mass[0] == self.mass[1] else 2
        return masses * 2 ** (len(self.com) + len(self.inertia))


@dataclasses.dataclass(frozen=True, eq=False)
class ObjectSet:
    """A union of parameter boxes: the objects a grasp constraint must hold.

    Attributes:
        nominal: The object the planner knows (for messages and the
            single-object route).
        boxes: The boxes; a single degenerate box is the nominal alone.
        label: What the set is, for reports.
    """

    nominal: HeldObject
    boxes: tuple[ParameterBox, ...]
    label: str = ""

    def is_single(self) -> bool:
        """Whether the set is one object (one box of zero width)."""
        if len(self.boxes) != 1:
            return False
        box = self.boxes[0]
        return box.mass[0] == box.mass[1] and not len(box.com) and not len(box.inertia)

    @property
    def vertex_count(self) -> int:
        """Vertices of all boxes."""
        return sum(box.vertex_count for box in self.boxes)


def uncertain_object(
    held: HeldObject,
    uncertainty: ObjectUncertainty,
    R_CO: np.ndarray | None = None,
) -> ObjectSet:
    """The outer set Q of every object ``uncertainty`` allows around ``held``.

    Args:
        held: The nominal object in C.
        uncertainty: Half-widths
            (:class:`~rt_drake.types.object_uncertainty.ObjectUncertainty`).
        R_CO: (3, 3) the object's axes in C (the CoM widths are along them);
            default identity.
    """
    uncertainty.validate()
    R = np.eye(3) if R_CO is None else np.asarray(R_CO, dtype=float)
    if R.shape != (3, 3) or not np.allclose(R @ R.T, np.eye(3), atol=1e-9):
        raise InputError(f"R_CO must be a 3x3 rotation matrix, got {R!r}")
    m0, p0 = held.mass, held.p_CoScm_C
    m_lo, m_hi = m0 * (1.0 - uncertainty.mass), m0 * (1.0 + uncertainty.mass)
    d = uncertainty.com_half_widths
    unit = np.concatenate([[1.0], p0, sym_entries(parallel_axes(p0))])
    com = []
    for j in np.flatnonzero(d > 0.0):
        v = R[:, j]
        derivative = 2.0 * float(p0 @ v) * np.eye(3) - np.outer(p0, v) - np.outer(v, p0)
        com.append(d[j] * np.concatenate([[0.0], v, sym_entries(derivative)]))
    # Inertia about Scm: the nominal's principal axes e_j and moments lambda0_j.
    moments, axes = np.linalg.eigh(held.I_Scm_C)
    center = np.concatenate([np.zeros(4), sym_entries(held.I_Scm_C)])
    inertia = [
        uncertainty.inertia * moments[j] * _matrix_direction(np.outer(e, e))
        for j, e in enumerate(axes.T)
        if uncertainty.inertia > 0.0 and moments[j] > 0.0
    ]
    # pi_E = R_CO (m S(delta)) R_COᵀ, each entry of S(delta) in O boxed.
    diagonal = (d[1] ** 2 + d[2] ** 2, d[0] ** 2 + d[2] ** 2, d[0] ** 2 + d[1] ** 2)
    for k in range(3):
        half = 0.5 * m_hi * diagonal[k]
        if half > 0.0:
            E = np.outer(R[:, k], R[:, k])
            center = center + half * _matrix_direction(E)
            inertia.append(half * _matrix_direction(E))
    for k, other in itertools.combinations(range(3), 2):
        half = m_hi * d[k] * d[other]
        if half > 0.0:
            E = np.outer(R[:, k], R[:, other]) + np.outer(R[:, other], R[:, k])
            inertia.append(half * _matrix_direction(E))
    box = ParameterBox(
        mass=(m_lo, m_hi),
        unit=unit,
        com=_rows(com),
        center=center,
        inertia=_rows(_merged(inertia)),
    )
    return ObjectSet(nominal=held, boxes=(box,), label=uncertainty.describe())


def object_list(objects: list[HeldObject]) -> ObjectSet:
    """A finite set of objects (one degenerate box each); the first is nominal."""
    if not objects:
        raise InputError("an object list needs at least one object")
    empty = np.zeros((0, 10))
    boxes = tuple(
        ParameterBox(
            mass=(1.0, 1.0),
            unit=inertial_parameters(held),
            com=empty,
            center=np.zeros(10),
            inertia=empty,
        )
        for held in objects
    )
    return ObjectSet(nominal=objects[0], boxes=boxes, label=f"{len(objects)} objects")


def _matrix_direction(M: np.ndarray) -> np.ndarray:
    """pi-vector (10,) of a symmetric matrix added to I_Co."""
    return np.concatenate([np.zeros(4), sym_entries(M)])


def _rows(vectors: list[np.ndarray]) -> np.ndarray:
    return np.array(vectors, dtype=float).reshape(-1, 10)


def _merged(generators: list[np.ndarray]) -> list[np.ndarray]:
    """Parallel generators summed (``[-1, 1] a + [-1, 1] b = [-1, 1] (a + b)``)."""
    merged: list[np.ndarray] = []
    for g in generators:
        for i, kept in enumerate(merged):
            cosine = float(g @ kept) / (np.linalg.norm(g) * np.linalg.norm(kept))
            if abs(cosine) > 1.0 - _PARALLEL:
                merged[i] = kept + np.sign(cosine) * g
                break
        else:
            merged.append(g)
    return merged


__all__ = [
    "PARAMETER_NAMES",
    "ObjectSet",
    "ParameterBox",
    "SetVertex",
    "held_object",
    "inertial_parameters",
    "object_list",
    "parallel_axes",
    "set_vertex",
    "sym_entries",
    "uncertain_object",
]
