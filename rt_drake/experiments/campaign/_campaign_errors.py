"""Typed errors of validation campaigns, each a one-line message."""

from __future__ import annotations

from rt_drake.errors import InputError, RtDrakeError


class CampaignError(InputError):
    """A campaign file is missing, malformed, or names something unknown.

    The message names the file, the key and the offending value, as
    :class:`~rt_drake.errors.ScenarioError` does for scenarios.
    """


class CampaignMismatchError(RtDrakeError):
    """A results database holds another campaign (another content hash)."""


class ExecutorUnavailableError(RtDrakeError):
    """An executor's optional dependency (Ray) is not installed, or fails to start."""


__all__ = ["CampaignError", "CampaignMismatchError", "ExecutorUnavailableError"]
