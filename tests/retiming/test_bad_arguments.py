"""retime, its limits, grasp and trajectory file refuse bad values up front."""

from __future__ import annotations

import types

import numpy as np
import pytest

from rt_drake.contact import CupMount, CupParameters, ToolParameters
from rt_drake.errors import InputError, TooLargeError
from rt_drake.model.held import held_object_of
from rt_drake.retiming import (
    GraspConstraint,
    JointLimits,
    RetimeInputError,
    retime,
    sample_trajectory,
)
from rt_drake.types.held_object import HeldObject
from rt_drake.types.object_uncertainty import ObjectUncertainty
from rt_drake.types.path import MAX_ABS_POSITION

HOME = np.array([0.0, 0.35, 1.75, 0.0, 1.04, 0.0])
PATH = np.array([HOME, HOME + [-0.4, 0.1, -0.2, 0.0, 0.1, -0.5]])
CUP = CupParameters()


@pytest.fixture(scope="module")
def limits(plant, scenario):
    return JointLimits.from_plant(plant, scenario.robot)


def test_retime_input_errors_are_input_errors():
    assert issubclass(RetimeInputError, InputError)


@pytest.mark.parametrize(
    "kwargs,words",
    [
        ({"sd_start": np.nan}, ["sd_start", "nan"]),
        ({"sd_start": -1.0}, ["sd_start must be >= 0", "-1.0"]),
        ({"sd_end": np.inf}, ["sd_end", "inf"]),
        ({"sd_end": "fast"}, ["sd_end", "'fast'"]),
        ({"start_time": np.nan}, ["start_time", "nan"]),
        ({"gridpoints": 10**9}, ["gridpoints", "1000000000"]),
        ({"gridpoints": 2.5}, ["gridpoints must be an integer", "2.5"]),
        ({"gridpoints": np.linspace(0, 1, 200_001)}, ["200001 values"]),
    ],
)
def test_retime_refuses_bad_arguments_before_any_work(plant, limits, kwargs, words):
    with pytest.raises(RetimeInputError) as info:
        retime(plant, PATH, limits, **kwargs)
    for word in words:
        assert word in str(info.value), (word, str(info.value))


@pytest.mark.parametrize("value", [1e6, -1e3, 2 * MAX_ABS_POSITION])
def test_a_waypoint_beyond_any_joint_range_is_refused(plant, limits, value):
    path = PATH.copy()
    path[1, 2] = value
    with pytest.raises(RetimeInputError) as info:
        retime(plant, path, limits)
    assert f"waypoint 1, joint 2: {value:g} is beyond" in str(info.value)


def test_limits_of_the_wrong_length_name_the_key(plant, scenario):
    robot = scenario.robot
    short = type(robot)(
        model_instance=robot.model_instance, home=robot.home, velocity_limits=[1, 2]
    )
    with pytest.raises(RetimeInputError, match="robot.velocity_limits': 2 values"):
        JointLimits.from_plant(plant, short)


def test_a_grasp_constraint_with_a_zero_row_is_refused():
    held = HeldObject(mass=1.0, p_CoScm_C=np.zeros(3), I_Scm_C=np.eye(3) * 1e-3)
    F = np.vstack([np.eye(6), -np.eye(6), np.zeros((1, 6))])
    with pytest.raises(RetimeInputError, match="GraspConstraint: F row 12 is zero"):
        GraspConstraint(held, F, np.ones(13))


@pytest.mark.parametrize(
    "mass,inertia,words",
    [
        (0.0, np.eye(3), ["object mass must be > 0 kg", "0.0"]),
        (np.nan, np.eye(3), ["mass", "nan"]),
        (1.0, -np.eye(3), ["object inertia must be positive definite"]),
        (1.0, np.diag([1e-3, 1e-3, 1e-2]), ["triangle inequality"]),
    ],
)
def test_a_held_object_must_be_physical(mass, inertia, words):
    with pytest.raises(InputError) as info:
        HeldObject(mass=mass, p_CoScm_C=np.zeros(3), I_Scm_C=inertia)
    for word in words:
        assert word in str(info.value)


def test_a_held_object_from_a_model_with_a_defaulted_mass_is_refused(
    tmp_path, scenario
):
    from rt_drake.model.resources import models_dir

    sdf = (models_dir() / "objects" / "notebook.sdf").read_text()
    (tmp_path / "o.sdf").write_text(sdf.replace("<mass>0.551</mass>", ""))
    obj = type(scenario.objects[0])(name="o", model=str(tmp_path / "o.sdf"))
    with pytest.raises(InputError, match="o.sdf.*no <inertial><mass>.*1 kg"):
        held_object_of(obj)


def test_sampling_a_trajectory_too_long_for_memory_is_refused(plant):
    held = HeldObject(mass=1.0, p_CoScm_C=np.zeros(3), I_Scm_C=np.eye(3) * 1e-3)
    result = types.SimpleNamespace(
        duration=1e6, trajectory=types.SimpleNamespace(rows=lambda: 6)
    )
    with pytest.raises(TooLargeError, match="1e\\+06 s trajectory.*at most 1000000"):
        sample_trajectory(plant, result, held, None, CUP, "x", PATH, [0.0, 1.0])
    with pytest.raises(InputError, match="period"):
        sample_trajectory(plant, result, held, None, CUP, "x", PATH, [0, 1], np.nan)


HELD = HeldObject(mass=1.0, p_CoScm_C=np.zeros(3), I_Scm_C=np.eye(3) * 1e-3)


def test_a_grasp_constraint_with_no_rows_is_refused():
    with pytest.raises(RetimeInputError, match=r"F must be a \(rows, 6\).*\(0, 6\)"):
        GraspConstraint(HELD, np.zeros((0, 6)), np.zeros(0))


@pytest.mark.parametrize(
    "build,key",
    [
        (lambda: GraspConstraint.for_cup(HELD, CupParameters(friction=0.0)),
         "for_cup: cup.friction"),
        (lambda: GraspConstraint.robust(
            HELD, ObjectUncertainty(), CupParameters(friction_min=0.0)),
         "robust: cup.friction_min"),
        (lambda: GraspConstraint.for_objects(
            [HELD], CupParameters(friction_min=0.0)),
         "for_objects: cup.friction_min"),
        (lambda: GraspConstraint.for_tool(
            HELD, ToolParameters((CupMount(CupParameters(friction=0.0)),))),
         "for_tool: cups[0].friction"),
    ],
)  # fmt: skip
def test_a_frictionless_cup_is_refused_naming_friction_and_value(build, key):
    with pytest.raises(RetimeInputError) as info:
        build()
    message = str(info.value)
    assert f"GraspConstraint.{key} must be > 0" in message
    assert message.endswith("got 0.0") and "g > 0" not in message
