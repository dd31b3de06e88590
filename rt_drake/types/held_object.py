"""The held object: its mass and inertia in the cup frame C, checked once.

Physically valid (:func:`check_inertia`): the mass is finite and > 0; the
rotational inertia about the centre of mass is finite, symmetric and positive
definite, and its principal moments satisfy the triangle inequality
``I_a + I_b >= I_c`` (a real mass distribution's do). Units: kg, kg m^2.
Numpy only: a scenario object becomes one with
:func:`rt_drake.model.held.held_object_of`.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from rt_drake.errors import InputError

#: Relative tolerance of the symmetry and triangle-inequality checks.
INERTIA_RTOL = 1e-9


def check_inertia(mass: float, inertia: np.ndarray, what: str = "object") -> None:
    """Raise InputError unless ``mass`` and ``inertia`` are physically valid.

    Args:
        mass: kg.
        inertia: (3, 3) rotational inertia about the centre of mass, kg m^2,
            in any frame.
        what: Names the object in messages (``"object 'notebook'"``).
    """
    if isinstance(mass, bool) or not isinstance(mass, (int, float, np.number)):
        raise InputError(f"{what} mass must be a number, got {mass!r}")
    if not (math.isfinite(mass) and mass > 0.0):
        raise InputError(f"{what} mass must be > 0 kg, got {mass!r}")
    I = np.asarray(inertia, dtype=float)  # noqa: E741 (the usual symbol)
    if I.shape != (3, 3) or not np.all(np.isfinite(I)):
        raise InputError(
            f"{what} inertia must be a finite 3x3 matrix, got {I.tolist()}"
        )
    scale = float(np.abs(I).max())
    if not np.allclose(I, I.T, rtol=0.0, atol=INERTIA_RTOL * scale):
        raise InputError(f"{what} inertia must be symmetric, got {I.tolist()}")
    moments = np.linalg.eigvalsh(0.5 * (I + I.T))
    if moments[0] <= 0.0:
        raise InputError(
            f"{what} inertia must be positive definite, got principal moments "
            f"{_moments(moments)} kg m^2"
        )
    if moments[2] > (moments[0] + moments[1]) * (1.0 + INERTIA_RTOL):
        raise InputError(
            f"{what} inertia violates the triangle inequality of its principal "
            f"moments ({_moments(moments)} kg m^2: {moments[2]:.4g} > "
            f"{moments[0]:.4g} + {moments[1]:.4g}); no mass distribution has it"
        )


def _moments(moments: np.ndarray) -> str:
    return "[" + ", ".join(f"{m:.4g}" for m in moments) + "]"


@dataclasses.dataclass(frozen=True, eq=False)
class HeldObject:
    """Inertia of an object held rigidly by the cup, in the cup frame C.

    Attributes:
        mass: m, kg (> 0).
        p_CoScm_C: (3,) centre of mass Scm from the cup origin Co, in C, m.
        I_Scm_C: (3, 3) rotational inertia about Scm, expressed in C, kg m^2.
    """

    mass: float
    p_CoScm_C: np.ndarray
    I_Scm_C: np.ndarray

    def __post_init__(self) -> None:
        p = np.asarray(self.p_CoScm_C, dtype=float).reshape(-1)
        if p.shape != (3,) or not np.all(np.isfinite(p)):
            raise InputError(f"p_CoScm_C must be 3 finite numbers, got {p!r}")
        check_inertia(self.mass, self.I_Scm_C, "object")
        object.__setattr__(self, "mass", float(self.mass))
        object.__setattr__(self, "p_CoScm_C", p)
        object.__setattr__(self, "I_Scm_C", np.asarray(self.I_Scm_C, dtype=float))


__all__ = ["INERTIA_RTOL", "HeldObject", "check_inertia"]
