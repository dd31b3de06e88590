"""The wrenches every cup of a friction and suction range exerts, against LPs."""

import dataclasses

import numpy as np

from rt_drake.contact import CupParameters, is_realizable, is_realizable_lp
from rt_drake.contact.worst_cup import FORCE_Z, worst_cup_polytope

#: A small cup (4 rim points), so that the exact sets are fast to compute.
CUP = CupParameters(
    points=4,
    friction=0.4,
    friction_min=0.25,
    suction_force=20.0,
    suction_force_min=10.0,
    max_normal_force=10.0,
)


def _near_boundary(F, g, count, rng, delta=1e-4):
    """Wrenches just inside and just outside ``F w <= g``, in random directions."""
    directions = rng.normal(size=(count, 6)) * [0.05, 0.05, 0.05, 1.0, 1.0, 1.0]
    rates = directions @ F.T
    with np.errstate(divide="ignore"):
        t = np.min(np.where(rates > 0, g / rates, np.inf), axis=1)
    scale = np.where(np.arange(count) % 2, 1.0 + delta, 1.0 - delta)
    return (t * scale)[:, None] * directions


def test_worst_cup_set_is_every_cups_set():
    """Inside (F, g) iff realizable by the cups at both ends of the range."""
    F, g = worst_cup_polytope(CUP, use_cache=False)
    rng = np.random.default_rng(0)
    wrenches = _near_boundary(F, g, 60, rng)
    inside = is_realizable(wrenches, F, g)
    ends = [
        dataclasses.replace(
            CUP.worst_case(), suction_force=force
        )  # friction_min, either suction
        for force in (CUP.suction_force_min, CUP.suction_force)
    ]
    by_lp = np.all([is_realizable_lp(wrenches, cup) for cup in ends], axis=0)
    np.testing.assert_array_equal(inside, by_lp)
    # The nominal cup (more friction) holds them too.
    assert np.all(is_realizable_lp(wrenches[inside], dataclasses.replace(CUP)))


def test_suction_is_not_monotone_pushing_tightens():
    """Less suction is not the smaller set: the rim must overcome the suction.

    A force along +z (the cup pushing the object away from it, e.g. moving
    it down faster than it falls) is rim force minus suction; the rim's
    normal forces are bounded (4 x 10 N here).
    """
    F, g = worst_cup_polytope(CUP, use_cache=False)
    weakest = CUP.worst_case()
    push = np.array([0, 0, 0, 0, 0, 25.0])
    assert is_realizable_lp(push, weakest)  # 25 + 10 <= 40
    strongest = dataclasses.replace(weakest, suction_force=CUP.suction_force)
    assert not is_realizable_lp(push, strongest)  # 25 + 20 > 40
    assert not is_realizable(push, F, g)
    # Rows pulling away keep the weakest suction's offset, pushing rows tighten.
    from rt_drake.contact import cached_wrench_polytope

    plain = cached_wrench_polytope(weakest, use_cache=False)
    pull = F[:, FORCE_Z] <= 0
    np.testing.assert_array_equal(g[pull], plain.g[pull])
    push = F[:, FORCE_Z] > 1e-6
    assert push.any() and np.all(g[push] < plain.g[push])
    assert np.all(g <= plain.g)


def test_a_known_cup_is_its_own_set():
    cup = CupParameters(points=4, max_normal_force=10.0)
    F, g = worst_cup_polytope(cup, use_cache=False)
    from rt_drake.contact import contact_wrench_polytope

    exact = contact_wrench_polytope(cup)
    np.testing.assert_array_equal(F, exact.F)
    np.testing.assert_array_equal(g, exact.g)
