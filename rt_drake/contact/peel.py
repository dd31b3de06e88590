"""The peel limit of a compliant lip: linear rows on the cup's tilting moment.

The rim model (:mod:`rt_drake.contact._cup`) lets the m rim points carry any
normal forces in ``[0, f_max]``, so a tilting moment is resisted until the
whole normal load sits on the far edge: the rigid rim tips at ``|M_t| = N
r`` (N the rim's total normal force). A rubber lip is a ring of compliant
points pressed onto the face; it cannot move its load to one edge without
lifting the other.

Model (derived here; Dex-Net 3.0, Mahler et al., ICRA 2018, also treats the
cup's perimeter as a quasi-static ring of springs, there for its seal test, not
for this limit). The lip is a ring of radius r of points of equal stiffness,
pressed onto a rigid face. Assumptions: the face stays plane (a rigid object);
the lip points are linear springs of equal stiffness along the cup axis and
deflect only along it; friction carries the shear without changing the normal
loads; quasi-static (the bellows' dynamics are the job of
``planning.grasp_ramp_s`` and ``planning.grasp_margin``). In the cup frame C
(origin at the centre of the face, +z into the object), w = ``[torque; force]``
on the object:

- The ring's total normal load is ``N0 = P A + f_z``: the suction pulls the
  object on by P A, the net force ``f_z`` on the object leaves the rest on
  the lip (``f_z < 0`` pulls the object onto the cup, e.g. its weight
  hanging below a cup pointing down: ``N0 = P A - m g``).
- A rigid face turned by a small angle about an axis of the face plane
  presses the point at angle phi by ``k (d + theta r cos(phi - psi))``: the
  load per unit angle is ``q(phi) = N0 / (2 pi) + q1 cos(phi - psi)``. The
  uniform part carries N0, the cosine part the moment: ``|M_t| = integral
  q1 cos^2 r dphi = pi r q1``. The farthest point lifts when its load reaches
  zero, ``q1 = N0 / (2 pi)``:

      |M_t| = N0 r / 2   (first lift; the rigid rim tips at N0 r).

  For n evenly spaced points (n >= 3) ``sum cos^2 = n / 2`` gives the same
  ``N0 r / 2`` when a point lies opposite the moment, and more otherwise.

The planner states ``cup.peel_fraction`` c (1/2: the lip lifts nowhere; a
lip that seals through a small lift leaks later, between 1/2 and 1, the
guide's ring model with a leak gap) and the rows keep
``|M_t| <= c r N0``. The disk is replaced by the regular
:data:`PEEL_SIDES`-gon inscribed in it (its corners on the x and y axes of
C), so the set stays a polytope and inside the disk:

    cos(b_j) M_x + sin(b_j) M_y <= c r cos(pi / K) (P A + f_z),
    b_j = 2 pi (j + 1/2) / K,   j = 0 .. K - 1.

Each row, as a unit row of ``F w <= g``: ``[cos b_j, sin b_j, 0, 0, 0,
-h] w <= h P A`` divided by ``sqrt(1 + h^2)``, ``h = c r cos(pi / K)`` (m).
The rows are intersected with the rim's W_c
(:func:`rt_drake.contact.contact_wrench_polytope`). Suction enters as
``P A + f_z``, so a changed suction translates them along ``f_z`` with the
rim's rows (:func:`rt_drake.contact.with_suction_force` stays exact).
"""

from __future__ import annotations

import numpy as np

from rt_drake import arguments
from rt_drake.contact._cup import CupParameters
from rt_drake.errors import InputError

#: Sides K of the polygon that replaces the peel disk (inscribed: its rows
#: allow ``cos(pi / K) = 0.924`` of the disk between its corners).
PEEL_SIDES = 8


def peel_rows(cup: CupParameters) -> tuple[np.ndarray, np.ndarray]:
    """``(F, g)``: the K unit rows of the lip's peel limit, ``F w <= g``.

    ``cos(b_j) M_x + sin(b_j) M_y <= c r cos(pi / K) (P A + f_z)`` (module
    docstring), w ``[torque; force]`` on the object about C's origin in C
    (N m, N), c the cup's ``peel_fraction``, r its radius (m), P A its
    suction force (N).

    Raises:
        InputError: not a CupParameters, or a cup without ``peel_fraction``.
    """
    arguments.instance(cup, "cup", CupParameters, where="peel_rows")
    if cup.peel_fraction is None:
        raise arguments.fail(
            "peel_rows", "cup.peel_fraction", "a number in (0, 1]", None, InputError
        )
    half = cup.peel_fraction * cup.radius * np.cos(np.pi / PEEL_SIDES)
    normals = 2.0 * np.pi * (np.arange(PEEL_SIDES) + 0.5) / PEEL_SIDES
    F = np.zeros((PEEL_SIDES, 6))
    F[:, 0], F[:, 1], F[:, 5] = np.cos(normals), np.sin(normals), -half
    g = np.full(PEEL_SIDES, half * cup.suction_force)
    norm = np.hypot(1.0, half)
    return F / norm, g / norm


__all__ = ["PEEL_SIDES", "peel_rows"]
