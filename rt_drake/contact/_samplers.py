"""Generic guiding samples for the guided approximation (Drake-free).

:func:`object_wrench_sampler` draws wrenches a cup must exert to hold and
move an object: with ``R_WC`` the cup's orientation in the world W, a_W the
object's linear acceleration, ``g_W = (0, 0, -9.81)`` m/s^2 and
``p_CoOcm_C`` the object's centre of mass in C, the wrench on the object,
about C's origin, in C, is

    f_C = m R_CW (a_W - g_W),    tau_C = p_CoOcm_C x f_C.

Rotational inertia is neglected (no angular acceleration). The cup axis +z_C
points down (the object hangs below) tilted by an angle drawn uniformly in
``[0, max_tilt]``, at a uniform azimuth and a uniform spin about the axis;
a_W is uniform in the ball of radius ``max_acceleration``. Samples from the
real planner (``rt_drake.dynamics.wrench``) are better guides; this one needs none.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from rt_drake import arguments
from rt_drake.errors import InputError

#: Gravity in the world frame, m/s^2.
GRAVITY_W = np.array([0.0, 0.0, -9.81])


def _rotation_z(angle: np.ndarray) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    R = np.zeros((len(angle), 3, 3))
    R[:, 0, 0], R[:, 0, 1], R[:, 1, 0], R[:, 1, 1], R[:, 2, 2] = c, -s, s, c, 1.0
    return R


def _rotation_y(angle: np.ndarray) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    R = np.zeros((len(angle), 3, 3))
    R[:, 0, 0], R[:, 0, 2], R[:, 2, 0], R[:, 2, 2], R[:, 1, 1] = c, s, -s, c, 1.0
    return R


def object_wrench_sampler(
    mass: float = 0.5,
    p_CoOcm_C: tuple[float, float, float] = (0.0, 0.0, 0.03),
    max_acceleration: float = 5.0,
    max_tilt: float = np.pi / 2,
    seed: int = 0,
) -> Callable[[int], np.ndarray]:
    """Return ``sample(count) -> (count, 6)`` wrenches ``[tau_C; f_C]`` (N*m, N).

    Args:
        mass: Object mass, kg (> 0).
        p_CoOcm_C: Centre of mass of the object in the cup frame, m.
        max_acceleration: Radius of the ball of linear accelerations, m/s^2.
        max_tilt: Largest angle between +z_C and straight down, rad.
        seed: Seed of the sampler's random generator.
    """
    where = "object_wrench_sampler"
    for name, value in (
        ("mass", mass),
        ("max_acceleration", max_acceleration),
        ("max_tilt", max_tilt),
    ):
        arguments.number(value, name, where=where)
    if not (np.isfinite(mass) and mass > 0.0):
        raise InputError(f"sampler mass must be > 0 kg, got {mass!r}")
    if not (np.isfinite(max_acceleration) and max_acceleration >= 0.0):
        raise InputError(f"max_acceleration must be >= 0, got {max_acceleration!r}")
    p = np.asarray(p_CoOcm_C, dtype=float)
    if p.shape != (3,) or not np.all(np.isfinite(p)):
        raise InputError(f"p_CoOcm_C must be 3 finite numbers, got {p_CoOcm_C!r}")
    if not (np.isfinite(max_tilt) and 0.0 <= max_tilt <= np.pi):
        raise InputError(f"max_tilt must be in [0, pi] rad, got {max_tilt!r}")
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise InputError(f"seed must be an integer >= 0, got {seed!r}")
    rng = np.random.default_rng(seed)
    down = np.diag([1.0, -1.0, -1.0])  # R_WC of a cup facing straight down

    def sample(count: int) -> np.ndarray:
        tilt = rng.uniform(0.0, max_tilt, count)
        R_WC = (
            _rotation_z(rng.uniform(0.0, 2 * np.pi, count))
            @ _rotation_y(tilt)
            @ down
            @ _rotation_z(rng.uniform(0.0, 2 * np.pi, count))
        )
        direction = rng.normal(size=(count, 3))
        direction /= np.linalg.norm(direction, axis=1, keepdims=True)
        radius = max_acceleration * rng.uniform(0.0, 1.0, count) ** (1.0 / 3.0)
        a_W = direction * radius[:, None]
        f_C = mass * np.einsum("nji,nj->ni", R_WC, a_W - GRAVITY_W)
        return np.hstack([np.cross(p, f_C), f_C])

    return sample
