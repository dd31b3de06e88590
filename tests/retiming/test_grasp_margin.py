"""``GraspConstraint.with_margin`` and ``planning.grasp_margin``: a subset, kept.

The shrunk set ``F w <= (1 - m) g`` is checked against the original by an
independent LP (HiGHS: the largest value of each original row over the
shrunk set) and by its vertices; a MOVE retimed under it keeps a share m of
every row of the original set at 1 kHz (``check_trajectory``).
"""

from __future__ import annotations

import numpy as np
import pytest
from grasp_paths import BACK
from scipy.optimize import linprog

from rt_drake import load_scenario
from rt_drake.contact import CupParameters, cached_wrench_polytope
from rt_drake.errors import ScenarioError
from rt_drake.model.held import held_object_of
from rt_drake.model.resources import scenarios_dir
from rt_drake.retiming import (
    GraspConstraint,
    JointLimits,
    Margin,
    RetimeInputError,
    check_trajectory,
    retime,
)

CUP = CupParameters(points=4)


@pytest.fixture(scope="module")
def grasp(scenario):
    return GraspConstraint.for_cup(held_object_of(scenario.object("notebook")), CUP)


@pytest.mark.parametrize("fraction", [0.05, 0.3])
def test_the_shrunk_set_is_a_strict_subset(grasp, fraction):
    shrunk = grasp.with_margin(fraction)
    assert type(shrunk) is type(grasp) and shrunk.cup == grasp.cup
    np.testing.assert_array_equal(shrunk.F, grasp.F)
    rng = np.random.default_rng(0)
    rows = rng.choice(len(grasp.g), size=12, replace=False)
    for row in rows:  # the LP: max F_i w over the shrunk set, at most g_i
        lp = linprog(-grasp.F[row], A_ub=shrunk.F, b_ub=shrunk.g, bounds=(None, None))
        assert lp.status == 0
        assert -lp.fun <= grasp.g[row] + 1e-9
        assert -lp.fun == pytest.approx((1 - fraction) * grasp.g[row], rel=1e-6)
    vertices = cached_wrench_polytope(CUP).vertices
    scaled = (1 - fraction) * vertices  # the shrunk set's vertices
    assert np.all(scaled @ grasp.F.T <= grasp.g + 1e-9)
    assert np.all(scaled @ shrunk.F.T <= shrunk.g + 1e-9)
    outside = np.any(vertices @ shrunk.F.T > shrunk.g + 1e-9, axis=1)
    assert outside.all()  # every vertex of the original is cut off


def test_no_margin_is_the_same_constraint(grasp):
    assert grasp.with_margin(0.0) is grasp


@pytest.mark.parametrize("fraction", [-0.1, 0.95, float("nan"), "5 %"])
def test_a_bad_margin_is_refused_in_one_line(grasp, fraction):
    with pytest.raises(RetimeInputError) as info:
        grasp.with_margin(fraction)
    message = str(info.value)
    assert "CupGrasp.with_margin: fraction must be a finite number" in message
    assert "\n" not in message


def test_a_move_retimed_with_a_margin_keeps_it_in_the_original_set(
    plant, scenario, grasp
):
    limits = JointLimits.from_plant(plant, scenario.robot)
    plain = retime(plant, BACK, limits, grasp)
    kept = retime(plant, BACK, limits, grasp.with_margin(0.1))
    assert kept.duration > plain.duration
    margin = [
        check_trajectory(plant, r.trajectory, limits, grasp).margins[Margin.GRASP]
        for r in (plain, kept)
    ]
    assert margin[0].value == pytest.approx(0.0, abs=1e-3)  # the grasp binds
    assert margin[1].value >= 0.1 - 1e-3  # 10 % of every row kept free


def test_the_scenario_key_is_checked(tmp_path):
    text = (scenarios_dir() / "random_transport.yaml").read_text()
    path = tmp_path / "margin.yaml"
    path.write_text(text + "\nplanning:\n  grasp_margin: 0.05\n")
    assert load_scenario(path).planning.grasp_margin == 0.05
    path.write_text(text + "\nplanning:\n  grasp_margin: 1.5\n")
    with pytest.raises(
        ScenarioError, match=r"margin.yaml: key 'planning.grasp_margin'.*1.5"
    ):
        load_scenario(path)
