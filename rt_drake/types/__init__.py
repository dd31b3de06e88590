"""Value types every layer shares: the held object, the geometric path, the phase.

The bottom layer of rt_drake (above only :mod:`rt_drake.errors`): numpy,
scipy and Drake value types, no other rt_drake package.

- :class:`~rt_drake.types.held_object.HeldObject`: the object's mass and
  inertia in the cup frame C.
- :class:`~rt_drake.types.path.GeometricPath`: the clamped cubic spline
  ``q(s)`` through joint waypoints at chord-length knots, the one path type.
- :class:`~rt_drake.types.phase.Phase`: the phases of a pick-and-place cycle.
- :class:`~rt_drake.types.object_uncertainty.ObjectUncertainty`: what the
  robot does not know about the object (mass, centre of mass, inertia).
"""

from rt_drake.types.held_object import HeldObject
from rt_drake.types.object_uncertainty import ObjectUncertainty
from rt_drake.types.path import GeometricPath
from rt_drake.types.phase import Phase

__all__ = ["GeometricPath", "HeldObject", "ObjectUncertainty", "Phase"]
