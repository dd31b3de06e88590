"""A MOVE's grasp margin from the bellows' ring, against an independent integration.

Reference: the held body on the bellows, ``M d'' + C d' + K d = w(t)``, all
six degrees of freedom integrated at once by ``scipy.integrate.solve_ivp``
(RK45, tight tolerances) from rest in equilibrium, with the object's wrench
``w`` sampled every 1 ms (the bound samples every 2 ms and integrates each
mode exactly); ``C`` proportional (diagonal in the modes, with the modal
damping ratios of the catalogue's dampers), as the bound states. The ring is
the largest grasp row of ``K d(t)``, measured on the unshrunk set.
"""

from __future__ import annotations

import numpy as np
import pytest
from grasp_paths import BACK
from pydrake.math import RigidTransform
from scipy.integrate import solve_ivp
from scipy.linalg import eigh

from rt_drake import load_scenario
from rt_drake.contact import CupParameters
from rt_drake.dynamics.bellows_modes import BellowsTool
from rt_drake.dynamics.wrench import object_wrench
from rt_drake.errors import ScenarioError
from rt_drake.model.cup_physics import load_bellows_cup
from rt_drake.model.held import held_object_of
from rt_drake.model.resources import scenarios_dir
from rt_drake.retiming import (
    GraspConstraint,
    JointLimits,
    RetimeInputError,
    RingNotHeldError,
    retime,
    retime_for_ring,
    ring_load,
)
from rt_drake.retiming._ring_margin import TOLERANCE
from rt_drake.types.object_uncertainty import ObjectUncertainty

CUP = CupParameters(points=4)


@pytest.fixture(scope="module")
def grasp(scenario):
    return GraspConstraint.for_cup(held_object_of(scenario.object("notebook")), CUP)


@pytest.fixture(scope="module")
def tool():
    return BellowsTool(load_bellows_cup("vs060_bellows"), (RigidTransform(),))


@pytest.fixture(scope="module")
def limits(plant, scenario):
    return JointLimits.from_plant(plant, scenario.robot)


def reference_rows(plant, trajectory, grasp, tool) -> tuple[float, float]:
    """``(r_static, r_ring)`` by solve_ivp on the full 6-DOF system (docstring)."""
    end = trajectory.end_time()
    t = np.linspace(0.0, end, int(np.ceil(end / 1e-3)) + 1)
    q, v, a = trajectory.sample(t, 2)
    w = object_wrench(plant, grasp.held, q, v, a)
    K, M = tool.stiffness, tool.inertia(grasp.held)
    omega2, V = eigh(K, M)  # V^T M V = 1
    omega = np.sqrt(omega2)
    zeta = np.einsum("ik,ij,jk->k", V, tool.damping, V) / (2.0 * omega)
    C = M @ V @ np.diag(2.0 * zeta * omega) @ V.T @ M
    M_inv = np.linalg.inv(M)

    step = t[1] - t[0]

    def rate(time: float, x: np.ndarray) -> np.ndarray:
        k = min(int(time / step), len(t) - 2)  # w linear between samples
        load = w[k] + (time - t[k]) / step * (w[k + 1] - w[k])
        d, d_dot = x[:6], x[6:]
        return np.concatenate([d_dot, M_inv @ (load - C @ d_dot - K @ d)])

    x0 = np.concatenate([np.linalg.solve(K, w[0]), np.zeros(6)])
    solution = solve_ivp(
        rate, (t[0], t[-1]), x0, t_eval=t, rtol=1e-9, atol=1e-12, max_step=1e-3
    )
    carried = (K @ solution.y[:6]).T

    def rows(x: np.ndarray) -> float:
        return float(((x @ grasp.F.T) / grasp.g).max())

    return rows(w), rows(carried)


def test_the_ring_matches_a_full_integration(plant, grasp, tool, limits):
    trajectory = retime(plant, BACK, limits, grasp).trajectory
    load = ring_load(plant, trajectory, grasp, tool)
    static, ring = reference_rows(plant, trajectory, grasp, tool)
    assert load.static == pytest.approx(static, rel=1e-3)
    assert load.ring == pytest.approx(ring, rel=5e-3)
    assert load.factor > 1.2  # acceleration steps ring the bellows


def test_the_margin_found_holds_the_ring_and_is_the_least(plant, grasp, tool, limits):
    def retime_with(shrunk: GraspConstraint):
        return retime(plant, BACK, limits, shrunk)

    found = retime_for_ring(retime_with, BACK, grasp, tool, plant)
    static, ring = reference_rows(plant, found.result.trajectory, grasp, tool)
    assert ring <= 1.0 + 2e-3
    assert static <= 1.0 - found.margin + 1e-3  # retimed under the shrunk set
    assert (1.0 - found.margin) * ring / static <= 1.0 + 2e-3  # (1 - m) D <= 1
    np.testing.assert_allclose(found.grasp.g, (1.0 - found.margin) * grasp.g)
    assert found.margin > 0.0 and found.retimes == len(found.tried) <= 8
    # a margin within the tolerance below it was tried and rang out of the set
    below = [m for m, r in found.tried if r is not None and r > 1.0]
    assert max(below) >= found.margin - TOLERANCE
    _, ring_below = reference_rows(
        plant, retime_with(grasp.with_margin(max(below))).trajectory, grasp, tool
    )
    assert ring_below > 1.0


def _weighed_down(plant, grasp: GraspConstraint, rest_rows: float) -> GraspConstraint:
    """``grasp`` with g scaled so that gravity alone takes ``rest_rows`` on BACK."""
    q = np.linspace(BACK[0], BACK[-1], 50)  # BACK's configurations, and between
    q = np.vstack([q, BACK])
    still = np.zeros_like(q)
    w = object_wrench(plant, grasp.held, q, still, still)
    rows = ((w @ grasp.F.T) / grasp.g).max()
    return GraspConstraint(grasp.held, grasp.F, grasp.g * rows / rest_rows)


def test_a_ring_not_held_within_the_retimes_is_refused(plant, grasp, tool, limits):
    def retime_with(shrunk: GraspConstraint):
        return retime(plant, BACK, limits, shrunk)

    # one retime: at m = 0 the acceleration steps ring the rows to 1.66
    with pytest.raises(RingNotHeldError) as info:
        retime_for_ring(retime_with, BACK, grasp, tool, plant, max_retimes=1)
    message = str(info.value)
    assert "ring exceeds the grasp set at every margin of 1 retimes" in message
    assert "(m, ring rows: 0.000 1.66" in message and "\n" not in message


def test_gravity_alone_outside_the_set_is_refused_before_any_retime(plant, grasp, tool):
    def retime_with(shrunk: GraspConstraint):
        raise AssertionError("no retime expected")

    heavy = _weighed_down(plant, grasp, 1.2)
    with pytest.raises(RingNotHeldError, match="gravity alone takes"):
        retime_for_ring(retime_with, BACK, heavy, tool, plant)


def test_a_set_of_objects_is_refused(plant, grasp, tool):
    robust = GraspConstraint.robust(grasp.held, ObjectUncertainty(mass=0.1), CUP)
    with pytest.raises(RetimeInputError, match="set of objects"):
        retime_for_ring(lambda g: None, BACK, robust, tool, plant)


def test_the_scenario_key_takes_ring(tmp_path):
    text = (scenarios_dir() / "random_transport_bellows.yaml").read_text()
    assert "grasp_margin: 0.18" in text
    path = tmp_path / "ring.yaml"
    path.write_text(text.replace("grasp_margin: 0.18", "grasp_margin: ring"))
    planning = load_scenario(path).planning
    assert planning.ring_margin and planning.fixed_margin == 0.0
    path.write_text(text.replace("grasp_margin: 0.18", "grasp_margin: rings"))
    with pytest.raises(
        ScenarioError, match=r"ring.yaml: key 'planning.grasp_margin'.*'rings'"
    ):
        load_scenario(path)
