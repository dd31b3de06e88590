"""Object models: the inertia written in the file is read and must be physical."""

from __future__ import annotations

import numpy as np
import pytest

from rt_drake.errors import InputError
from rt_drake.model.object_model import (
    model_file,
    read_model_inertia,
)
from rt_drake.model.resources import models_dir
from rt_drake.types.held_object import check_inertia

SDF = (models_dir() / "objects" / "notebook.sdf").read_text()
INERTIA = "<ixx>0.000928</ixx><iyy>0.00211</iyy><izz>0.00298</izz>"


def test_the_shipped_objects_are_read_as_written():
    mass, inertia = read_model_inertia(models_dir() / "objects" / "notebook.sdf")
    assert mass == 0.551
    np.testing.assert_array_equal(np.diag(inertia), [0.000928, 0.00211, 0.00298])
    for path in (models_dir() / "objects").glob("*.sdf"):
        read_model_inertia(path)
    assert model_file("package://rt_drake/objects/notebook.sdf").is_file()


@pytest.mark.parametrize(
    "old,new,words",
    [
        ("<mass>0.551</mass>", "<mass>0</mass>", ["mass must be > 0 kg", "0.0"]),
        ("<mass>0.551</mass>", "<mass>-1</mass>", ["mass", "-1.0"]),
        ("<mass>0.551</mass>", "<mass>nan</mass>", ["mass", "nan"]),
        ("<mass>0.551</mass>", "<mass>heavy</mass>", ["<mass>", "'heavy'"]),
        ("<mass>0.551</mass>", "", ["no <inertial><mass>", "1 kg"]),
        ("<ixx>0.000928</ixx>", "", ["no <inertia><ixx>"]),
        (INERTIA, "<ixx>-1</ixx><iyy>-1</iyy><izz>-1</izz>", ["positive definite"]),
        (INERTIA, "<ixx>1e-3</ixx><iyy>1e-3</iyy><izz>1e-2</izz>", ["triangle"]),
        ('<link name="body">', '<link name="box">', ["no link named 'body'"]),
    ],
)
def test_an_unphysical_or_defaulted_inertia_is_refused(tmp_path, old, new, words):
    assert old in SDF
    path = tmp_path / "obj.sdf"
    path.write_text(SDF.replace(old, new, 1))
    with pytest.raises(InputError) as info:
        read_model_inertia(path)
    message = str(info.value)
    assert "obj.sdf" in message and "\n" not in message
    for word in words:
        assert word in message, (word, message)


def test_a_urdf_object_and_files_that_are_not_models(tmp_path):
    urdf = tmp_path / "o.urdf"
    urdf.write_text(
        '<robot name="o"><link name="body"><inertial><mass value="2"/>'
        '<inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/>'
        "</inertial></link></robot>"
    )
    assert read_model_inertia(urdf)[0] == 2.0
    (tmp_path / "x.sdf").write_text("not xml")
    with pytest.raises(InputError, match="x.sdf' is not an SDF or URDF"):
        read_model_inertia(tmp_path / "x.sdf")
    (tmp_path / "y.sdf").write_text("<html/>")
    with pytest.raises(InputError, match="root element <html>"):
        read_model_inertia(tmp_path / "y.sdf")
    with pytest.raises(InputError, match="does not exist"):
        read_model_inertia(tmp_path / "none.sdf")


@pytest.mark.parametrize(
    "mass,inertia,words",
    [
        (np.nan, np.eye(3), ["mass", "nan"]),
        (True, np.eye(3), ["mass must be a number"]),
        (1.0, -np.eye(3), ["positive definite"]),
        (1.0, np.diag([1.0, 1.0, 2.5]), ["triangle inequality"]),
        (1.0, [[1, 0.5, 0], [0, 1, 0], [0, 0, 1]], ["symmetric"]),
        (1.0, np.full((3, 3), np.inf), ["finite 3x3"]),
        (1.0, np.eye(2), ["finite 3x3"]),
    ],
)
def test_check_inertia(mass, inertia, words):
    with pytest.raises(InputError) as info:
        check_inertia(mass, inertia)
    for word in words:
        assert word in str(info.value)


def test_a_physical_inertia_passes_at_the_triangle_limit():
    check_inertia(1.0, np.diag([1.0, 1.0, 2.0]))  # a thin disc: I_z = I_x + I_y
    rotation = np.linalg.qr(np.arange(9.0).reshape(3, 3) + np.eye(3))[0]
    check_inertia(0.5, rotation @ np.diag([1.0, 2.0, 2.5]) @ rotation.T)
