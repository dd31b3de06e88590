"""The lip's peel fractions of a catalogue bellows cup: first lift and leak.

    python tools/peel_leak_fraction.py [CUP] [--pull F ...]

For the ring of ``lip_points`` equal springs ``k = lip_stiffness / n`` at
the cup's radius r on a rigid face (the bellows guide's ring model, the
planner's own derivation in :mod:`rt_drake.contact.peel`), with an axial
pull F on the object (its weight below a cup pointing down) and the vacuum's
gap law ``P A max(0, min(1, 1 + d / range))`` (d: the lip centre pressed in),
prints for each pull the normal load ``N0 = P A - F``, and the tilting
moment, as a fraction c of ``N0 r``, at which

- the first lip point lifts (its spring force reaches zero): the
  ``peel_fraction`` 1/2 of a continuous ring;
- the farthest point lifts by ``leak_gap`` (the seal leaks).

The moment turns the face about the x axis of C, with a lip point opposite
(the ring's weakest direction). Reads the catalogue only; no simulation.

``--at-rest MASS DX DY`` (kg, m, m: an object hanging below the cup pointing
down, its centre of mass DX, DY off the axis) also prints, for each
``--fractions`` c, the share ``max_k F_k w / g_k`` of the planner's set
(the cup's P A, radius and friction, ``peel_fraction`` c; none: the rigid
rim) that holding it at rest takes; ``1 - grasp_margin`` is the most a
margin leaves.
"""

from __future__ import annotations

import argparse

import numpy as np
from scipy.optimize import brentq

from rt_drake.contact import CupParameters, contact_wrench_polytope
from rt_drake.model.cup_physics import BellowsCup, load_bellows_cup


def ring_moment(cup: BellowsCup, pull: float, lift: float) -> float:
    """N m: the moment at which the farthest lip point is ``lift`` (m) up.

    Points at ``y_j = r sin(2 pi j / n)``; a face turned by theta about x
    with the centre pressed in by d lifts point j by ``theta y_j - d``; at the
    moment sought ``theta y_max - d = lift``, and theta balances the springs
    against the vacuum's pull less ``pull``. Lift 0 is the first lift.
    """
    n, r = cup.lip_points, cup.radius
    k = cup.lip_stiffness / n
    y = r * np.sin(2 * np.pi * np.arange(n) / n)

    def forces(theta: float) -> np.ndarray:
        return k * np.clip(theta * y.max() - lift - theta * y, 0.0, None)

    def balance(theta: float) -> float:
        d = theta * y.max() - lift
        vacuum = cup.suction_force * np.clip(1.0 + d / cup.vacuum_range, 0.0, 1.0)
        return forces(theta).sum() - (vacuum - pull)

    theta = brentq(balance, lift / (2 * r) + 1e-12, 1.0)
    return float(-(forces(theta) * y).sum())


def main() -> None:
    """Print the fractions for each pull."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cup", nargs="?", default="vs060_bellows_20n")
    parser.add_argument("--pull", type=float, nargs="+", default=[0.0, 5.41, 6.48])
    parser.add_argument("--at-rest", type=float, nargs=3, metavar=("MASS", "DX", "DY"))
    parser.add_argument(
        "--fractions", type=float, nargs="+", default=[0.5, 0.697, 0.72, 0.74]
    )
    args = parser.parse_args()
    cup = load_bellows_cup(args.cup)
    print(f"{cup.name}: P A {cup.suction_force:.2f} N, r {1e3 * cup.radius:g} mm,")
    print(
        f"  {cup.lip_points} points, K {cup.lip_stiffness:g} N/m, "
        f"leak gap {1e3 * cup.leak_gap:g} mm"
    )
    for pull in args.pull:
        N0 = cup.suction_force - pull
        first = ring_moment(cup, pull, 0.0)
        leak = ring_moment(cup, pull, cup.leak_gap)
        print(
            f"pull {pull:5.2f} N: N0 {N0:6.2f} N, first lift {first:.4f} N m "
            f"(c = {first / (N0 * cup.radius):.3f}), leak {leak:.4f} N m "
            f"(c = {leak / (N0 * cup.radius):.3f})"
        )
    if args.at_rest is not None:
        at_rest(cup, *args.at_rest, args.fractions)


def at_rest(
    cup: BellowsCup, mass: float, dx: float, dy: float, fractions: list[float]
) -> None:
    """Print the share of the planner's set an object at rest takes, per c.

    Cup pointing down: gravity along +z_C; the cup's wrench on the object
    about C's origin is ``[-p x (m g e_z); -m g e_z]``, p = (dx, dy, 0).
    """
    weight = np.array([0.0, 0.0, mass * 9.81])
    p = np.array([dx, dy, 0.0])
    wrench = np.concatenate([-np.cross(p, weight), -weight])
    for fraction in [None, *fractions]:
        planner = CupParameters(
            radius=cup.radius,
            friction=cup.friction,
            suction_force=cup.suction_force,
            peel_fraction=fraction,
        )
        polytope = contact_wrench_polytope(planner)
        share = float(np.max(polytope.F @ wrench / polytope.g))
        print(f"at rest, peel_fraction {fraction}: max F w / g = {share:.4f}")


if __name__ == "__main__":
    main()
