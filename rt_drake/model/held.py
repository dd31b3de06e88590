"""A scenario object as a :class:`~rt_drake.types.held_object.HeldObject`.

The object's spatial inertia comes from the plant (or its model file), moved
from the object frame O to the cup frame C through the grasp ``X_OC``.
"""

from __future__ import annotations

from pydrake.math import RigidTransform
from pydrake.multibody.plant import MultibodyPlant

from rt_drake import arguments
from rt_drake.errors import InputError
from rt_drake.model.object_model import OBJECT_BODY, model_file, read_model_inertia
from rt_drake.model.parser import make_parser
from rt_drake.model.scenario import ObjectConfig
from rt_drake.types.held_object import HeldObject


def held_object_of(
    obj: ObjectConfig, plant: MultibodyPlant | None = None
) -> HeldObject:
    """Inertia of a scenario object held with its grasp ``X_OC``.

    Takes the spatial inertia of body ``body`` of model instance
    ``obj.name`` from ``plant`` if it has one, else parses ``obj.model``
    (after checking the inertia written in the file: the parser would
    take a missing or invalid mass as 1 kg), and moves it from the object
    frame O to C through ``obj.grasp``.

    Raises:
        InputError: the model file is not a valid object model (see
            :func:`rt_drake.model.object_model.read_model_inertia`), or the
            inertia is not physically valid.
    """
    arguments.instance(obj, "obj", ObjectConfig, where="held_object_of")
    if plant is not None:
        arguments.instance(plant, "plant", MultibodyPlant, where="held_object_of")
    if plant is not None and plant.HasModelInstanceNamed(obj.name):
        instance = plant.GetModelInstanceByName(obj.name)
        body = plant.GetBodyByName(OBJECT_BODY, instance)
    else:
        read_model_inertia(model_file(obj.model))  # Drake's defaults hide errors
        scratch = MultibodyPlant(0.0)
        try:
            (instance,) = make_parser(scratch).AddModels(url=_as_url(obj.model))
            body = scratch.GetBodyByName(OBJECT_BODY, instance)
        except RuntimeError as error:
            message = " ".join(str(error).split())[:300]
            raise InputError(
                f"object model '{obj.model}' cannot be loaded: {message}"
            ) from None
    M_OOo_O = body.default_spatial_inertia()
    mass = M_OOo_O.get_mass()
    p_OoScm_O = M_OOo_O.get_com()
    I_Scm_O = M_OOo_O.CalcRotationalInertia().ShiftToCenterOfMass(mass, p_OoScm_O)
    X_CO: RigidTransform = obj.grasp.GetDeterministicValue().inverse()
    R_CO = X_CO.rotation().matrix()
    return HeldObject(
        mass=mass,
        p_CoScm_C=X_CO.multiply(p_OoScm_O),
        I_Scm_C=R_CO @ I_Scm_O.CopyToFullMatrix3() @ R_CO.T,
    )


def _as_url(model: str) -> str:
    return model if "://" in model else f"file://{model}"


__all__ = ["held_object_of"]
