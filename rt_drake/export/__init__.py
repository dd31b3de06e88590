"""Trajectories for real controllers: samples at the controller's period.

A retimed trajectory leaves the simulator as a ROS 2 bag (MCAP) of one
``trajectory_msgs/msg/JointTrajectory`` or as a CSV, sampled on a fixed grid
of the controller's period and padded at the end with rest samples, with
the controller's joint names (the plant's, renamed by the scenario's
``robot.joint_names``).

- :func:`export_trajectory` writes the file (:class:`ExportFormat`);
- :mod:`.controller_names`: the plant's joint names and the map;
- private: ``_grid_samples`` (the grid and its rest padding),
  ``_ros2_bag``, ``_csv_table`` (the two formats), ``_export_file``.

The package needs only a trajectory (from :mod:`rt_drake.retiming`) and the
names; it sits beside :mod:`rt_drake.shaping`, above retiming.
"""

from rt_drake.export._csv_table import csv_header
from rt_drake.export._export_file import ExportFormat, export_format, export_trajectory
from rt_drake.export._grid_samples import MAX_SAMPLES, GridSamples, sample_on_grid
from rt_drake.export._ros2_bag import (
    DEFAULT_TOPIC,
    JOINT_TRAJECTORY_DEFINITION,
    SCHEMA_NAME,
)
from rt_drake.export.controller_names import (
    MAP_KEY,
    check_joint_names,
    controller_joint_names,
    plant_joint_names,
)

__all__ = [
    "DEFAULT_TOPIC",
    "JOINT_TRAJECTORY_DEFINITION",
    "MAP_KEY",
    "MAX_SAMPLES",
    "SCHEMA_NAME",
    "ExportFormat",
    "GridSamples",
    "check_joint_names",
    "controller_joint_names",
    "csv_header",
    "export_format",
    "export_trajectory",
    "plant_joint_names",
    "sample_on_grid",
]
