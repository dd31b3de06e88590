"""The grasp constraint family: one class per source of its rows.

Each constructor builds the member of its source, with the rows of that
source (compared with the contact layer's own functions), and no member
carries a field it does not use (no optional field, no dispatch on one).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from rt_drake.contact import (
    CupMount,
    CupParameters,
    SharedLoadSet,
    ToolParameters,
    cached_wrench_polytope,
    worst_cup_polytope,
)
from rt_drake.model.held import held_object_of
from rt_drake.retiming import (
    CupGrasp,
    GraspConstraint,
    ObjectSetGrasp,
    ToolGrasp,
)
from rt_drake.types.object_uncertainty import ObjectUncertainty

SMALL = CupParameters(points=4, sides=3)
TWO_CUPS = ToolParameters(
    cups=[
        CupMount(SMALL, np.eye(3), [0.06, 0.0, 0.0]),
        CupMount(SMALL, np.eye(3), [-0.06, 0.0, 0.0]),
    ]
)
#: Friction and suction known down to these.
UNCERTAIN_CUP = CupParameters(friction_min=0.25, suction_force_min=18.0)
SET = ObjectUncertainty(mass=0.05, com=[0.01, 0.01, 0.0])
FAMILY = (GraspConstraint, CupGrasp, ToolGrasp, ObjectSetGrasp)


@pytest.fixture(scope="module")
def held(scenario):
    return held_object_of(scenario.object("notebook"))


def _same_rows(grasp, F, g):
    np.testing.assert_array_equal(grasp.F, F)
    np.testing.assert_array_equal(grasp.g, g)


def test_no_member_has_an_optional_field():
    for cls in FAMILY:
        assert issubclass(cls, GraspConstraint)
        for field in dataclasses.fields(cls):
            assert field.default is dataclasses.MISSING, (cls.__name__, field.name)
            assert "None" not in str(field.type), (cls.__name__, field.name)


def test_one_object_on_one_cup(held, scenario):
    grasp = GraspConstraint.for_cup(held, scenario.cup)
    assert type(grasp) is CupGrasp and grasp.cup is scenario.cup
    polytope = cached_wrench_polytope(scenario.cup)
    _same_rows(grasp, polytope.F, polytope.g)
    assert not grasp.is_robust
    suction = scenario.cup.suction_force
    assert grasp.describe() == f"object {held.mass:.3g} kg, suction {suction:.3g} N"
    assert grasp.guarantee() == f"the nominal object ({held.mass:.3g} kg)"
    by_hand = GraspConstraint(held, polytope.F, polytope.g)
    assert type(by_hand) is GraspConstraint and not by_hand.is_robust
    assert by_hand.describe() == f"object {held.mass:.3g} kg"
    assert GraspConstraint.for_polytope(held, polytope).cup is scenario.cup


def test_one_object_on_a_tool(held):
    elastic = GraspConstraint.for_tool(held, TWO_CUPS)
    shared = SharedLoadSet.of(TWO_CUPS)
    assert type(elastic) is ToolGrasp and elastic.tool is TWO_CUPS
    _same_rows(elastic, shared.F, shared.g)
    assert elastic.describe().endswith(", 2 cups, suction 20 + 20 N")
    assert not elastic.is_robust
    routed = GraspConstraint.for_polytope(held, shared)
    assert type(routed) is ToolGrasp and routed.tool is TWO_CUPS
    _same_rows(routed, shared.F, shared.g)


def test_every_object_of_a_set_with_every_cup_of_a_range(held, scenario):
    obj = dataclasses.replace(scenario.object("notebook"), uncertainty=SET)
    grasp = GraspConstraint.for_scenario_object(obj, UNCERTAIN_CUP)
    assert type(grasp) is ObjectSetGrasp and grasp.is_robust and grasp.worst_cup
    _same_rows(grasp, *worst_cup_polytope(UNCERTAIN_CUP))
    assert grasp.describe().startswith("every object of the set around object")
    assert grasp.describe().endswith("suction 20 N (at least 18 N)")
    assert grasp.guarantee().startswith("every object of the set (mass +-5 %")
    assert grasp.guarantee().endswith("friction down to 0.25 and suction down to 18 N")
    # Without the set (or asked not to be robust), the nominal object.
    nominal = GraspConstraint.for_scenario_object(obj, scenario.cup, robust=False)
    assert type(nominal) is CupGrasp
    # A set of zero width is one object: not robust, still the worst cup.
    zero = GraspConstraint.robust(held, ObjectUncertainty(), UNCERTAIN_CUP)
    assert type(zero) is ObjectSetGrasp and not zero.is_robust and zero.worst_cup
    assert zero.guarantee().startswith(f"the nominal object ({held.mass:.3g} kg), ")
    listed = GraspConstraint.for_objects([held, held], scenario.cup)
    assert type(listed) is ObjectSetGrasp and listed.held is held
    assert listed.guarantee() == "every object of the set (2 objects)"
    assert not listed.worst_cup
