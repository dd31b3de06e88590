"""Typed errors of rt_drake.

Every error a user can cause by bad input derives from :class:`RtDrakeError`
(or is a plain ``ValueError`` raised by the Drake-free maths). The CLI turns
either into one line on stderr and exit code 2.
"""


class RtDrakeError(Exception):
    """Base class of the errors rt_drake raises on purpose."""


class ScenarioError(RtDrakeError, ValueError):
    """A scenario file is missing, malformed, or names something unknown.

    The message names the file, the key and the offending value.
    """
