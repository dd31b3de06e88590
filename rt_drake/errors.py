"""The one exception hierarchy of rt_drake.

Every error rt_drake raises on purpose derives from :class:`RtDrakeError`:

- :class:`InputError` (also a ``ValueError``): an argument, file or value
  is malformed or out of range; :class:`ScenarioError` for scenario files;
  :class:`TooLargeError` when the work an input asks for is estimated, up
  front, to need more memory than the limit (the message gives the estimate,
  the limit and the largest accepted value).
- ``RetimeError`` (:mod:`rt_drake.retiming`), ``PlanningError``
  (:mod:`rt_drake.planning`), ``CycleTimeout`` (:mod:`rt_drake.simulation`):
  the input is well formed but the task cannot be done (the object slips
  even at rest, no collision-free path, ...).

The CLI catches :class:`RtDrakeError` alone and exits with code 2 and one
line; any other exception is a bug and shows its traceback. Messages name
the problem (file, key, value, where on the path) and never a CLI flag.
This module imports nothing, so the Drake-free layers can use it.
"""


class RtDrakeError(Exception):
    """Base class of the errors rt_drake raises on purpose."""


class InputError(RtDrakeError, ValueError):
    """An argument, file or value given to rt_drake is malformed."""


class ScenarioError(InputError):
    """A scenario file is missing, malformed, or names something unknown.

    The message names the file, the key and the offending value.
    """


class TooLargeError(InputError):
    """The input asks for more memory (or time) than the limit allows.

    Raised before the work starts, from an estimate; the message gives the
    estimate, the limit and the largest accepted value.
    """


__all__ = ["InputError", "RtDrakeError", "ScenarioError", "TooLargeError"]
