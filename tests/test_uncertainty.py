"""ObjectUncertainty and the scenario's uncertainty keys: one-line typed errors."""

import textwrap

import numpy as np
import pytest

from rt_drake.contact import CupParameters
from rt_drake.errors import InputError, ScenarioError
from rt_drake.model.resources import scenarios_dir
from rt_drake.model.scenario import load_scenario
from rt_drake.types.object_uncertainty import ObjectUncertainty


@pytest.mark.parametrize(
    ("fields", "names"),
    [
        ({"mass": -0.1}, ("uncertainty.mass", "-0.1")),
        ({"mass": 1.0}, ("uncertainty.mass", "1.0")),
        ({"inertia": 1.5}, ("uncertainty.inertia", "1.5")),
        ({"inertia": float("nan")}, ("uncertainty.inertia", "nan")),
        ({"com": [0.01, -0.01, 0.0]}, ("uncertainty.com", "-0.01")),
        ({"com": [0.01, 0.01]}, ("uncertainty.com", "0.01")),
    ],
)
def test_bad_widths_are_one_line_errors_naming_key_and_value(fields, names):
    with pytest.raises(InputError) as error:
        ObjectUncertainty(**fields)
    message = str(error.value)
    assert "\n" not in message
    for name in names:
        assert name in message


def test_com_box_must_stay_inside_the_object():
    uncertainty = ObjectUncertainty(com=[0.01, 0.08, 0.0])
    uncertainty.check_inside(np.zeros(3), np.array([0.1, 0.1, 0.01]))
    with pytest.raises(InputError, match=r"com\[1\] = 0.08 .*outside the object"):
        uncertainty.check_inside(np.array([0.0, 0.03, 0.0]), np.array([0.1, 0.1, 0.01]))


def test_cup_minimum_above_nominal_is_refused():
    with pytest.raises(InputError, match="friction_min = 0.5 exceeds friction = 0.3"):
        CupParameters(friction_min=0.5)
    with pytest.raises(InputError, match="suction_force_min"):
        CupParameters(suction_force_min=-1.0)
    cup = CupParameters(friction_min=0.2, suction_force_min=15.0)
    assert cup.is_uncertain()
    assert cup.as_dict() == CupParameters().as_dict()  # the model, not its range
    worst = cup.worst_case()
    assert (worst.friction, worst.suction_force) == (0.2, 15.0)
    assert not worst.is_uncertain()


def _scenario(tmp_path, replace: dict[str, str]):
    text = (scenarios_dir() / "random_transport_uncertain.yaml").read_text()
    for old, new in replace.items():
        assert old in text
        text = text.replace(old, new)
    path = tmp_path / "s.yaml"
    path.write_text(text)
    return path


def test_scenario_loads_its_uncertainty_set():
    scenario = load_scenario(scenarios_dir() / "random_transport_uncertain.yaml")
    uncertainty = scenario.object("notebook").uncertainty
    assert uncertainty == ObjectUncertainty(0.2, [0.01, 0.01, 0.005], 0.2)


@pytest.mark.parametrize(
    ("old", "new", "expected"),
    [
        ("mass: 0.2", "mass: 1.2", "objects[0].uncertainty': uncertainty.mass"),
        (
            "com: [0.01, 0.01, 0.005]",
            "com: [0.01, 0.01, 0.02]",
            "com[2] = 0.02 m puts the centre of mass",
        ),
        ("com: [0.01, 0.01, 0.005]", "com: [0.01, -0.01, 0.0]", "-0.01"),
        ("inertia: 0.2", "inertia: -0.2", "uncertainty.inertia"),
        ("friction: 0.3", "friction: 0.3\n  friction_min: 0.4", "friction_min = 0.4"),
        ("mass: 0.2", "mass: 0.2, density: 3", "unknown key"),
    ],
)
def test_bad_scenario_uncertainty_is_a_one_line_scenario_error(
    tmp_path, old, new, expected
):
    path = _scenario(tmp_path, {old: textwrap.dedent(new)})
    with pytest.raises(ScenarioError) as error:
        load_scenario(path)
    message = str(error.value)
    assert "\n" not in message and str(path) in message
    assert expected in message
