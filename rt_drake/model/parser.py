"""A Drake ``Parser`` that resolves ``package://rt_drake/...`` (the shipped models)."""

from __future__ import annotations

from pydrake.multibody.parsing import Parser
from pydrake.multibody.plant import MultibodyPlant

from rt_drake.model.resources import models_dir


def make_parser(plant: MultibodyPlant) -> Parser:
    """Return a Parser that resolves ``package://rt_drake/...``."""
    return with_rt_drake_package(Parser(plant))


def with_rt_drake_package(parser: Parser) -> Parser:
    """Register ``package://rt_drake`` (the shipped models) with ``parser``."""
    package_map = parser.package_map()
    if not package_map.Contains("rt_drake"):
        package_map.Add("rt_drake", str(models_dir()))
    return parser


__all__ = ["make_parser", "with_rt_drake_package"]
