"""The wrenches every cup of a friction and suction range can exert.

A cup known only down to ``friction_min`` and ``suction_force_min``
(:class:`~rt_drake.contact.CupParameters`) is any cup with friction ``mu``
in ``[friction_min, friction]`` and suction ``P A`` in ``[suction_force_min,
suction_force]``. A wrench is safe when it lies in W_c of every one of them:
the intersection of their wrench sets. With R(mu) the set of rim wrenches
``sum_i G_i f_i`` (:mod:`rt_drake.contact._cup`),
``W_c(mu, P A) = R(mu) - P A e_fz``:

- R(mu) grows with mu (each friction polygon contains those of lower
  friction at the same normal force), so the intersection over mu is
  ``W_c(friction_min, .)``: the smaller set, exactly.
- Suction only translates W_c along the cup axis (force z). More suction
  helps when the object pulls away from the cup (f_z < 0) but hurts when the
  cup must push it away (f_z > 0, e.g. moving it down faster than it falls
  with the cup pointing down: the rim's normal forces, bounded by f_max,
  must overcome the suction): W_c is NOT monotone in the suction. The
  intersection over ``P A`` in ``[P_lo, P_hi]`` of ``{w : F (w + (P A -
  P_lo) e_fz) <= g}`` (F, g the exact set at ``P_lo``) has the same rows
  with the offsets ``g_k - (P_hi - P_lo) max(F_k,fz, 0)``: rows bounding
  +z force (``F_k,fz > 0``) tighten, the others keep the weakest suction's
  offset. Exact, and no new rows.
"""

from __future__ import annotations

import numpy as np

from rt_drake import arguments
from rt_drake.contact._cache import cached_wrench_polytope
from rt_drake.contact._cup import CupParameters

#: Index of the force along the cup axis in a wrench [torque; force].
FORCE_Z = 5


def worst_cup_polytope(
    cup: CupParameters, use_cache: bool = True
) -> tuple[np.ndarray, np.ndarray]:
    """``(F, g)`` of the wrenches every cup of ``cup``'s range can exert.

    Args:
        cup: The cup, with ``friction_min`` and ``suction_force_min`` (None:
            known exactly).
        use_cache: Read and write the on-disk cache of exact sets.

    Returns:
        F (R, 6) unit rows and g (R,) (module docstring); the cup's own exact
        set when nothing is uncertain.
    """
    arguments.instance(cup, "cup", CupParameters, where="worst_cup_polytope")
    polytope = cached_wrench_polytope(cup.worst_case(), use_cache=use_cache)
    F, g = polytope.F, polytope.g
    if cup.suction_force_min is None:
        return F, g
    spread = cup.suction_force - cup.suction_force_min
    return F, g - spread * np.maximum(F[:, FORCE_Z], 0.0)


__all__ = ["FORCE_Z", "worst_cup_polytope"]
