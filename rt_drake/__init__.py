"""rt_drake: critically fast suction-cup pick-and-place on Drake.

The public API: import what you need from here, e.g.
``from rt_drake import retime, JointLimits, GraspConstraint, HeldObject``.
Names load on first use (PEP 562), so ``import rt_drake`` and the Drake-free
:mod:`rt_drake.contact` stay light. Data flows one way through the layers:
scenario -> plant -> (IK, planner) -> path -> (dynamics + grasp constraint)
-> retimer -> trajectory -> diagram simulation -> report. The packages import
downward only (checked by import-linter in CI): cli > experiments >
simulation > shaping > planning | retiming > uncertainty > dynamics > model >
contact > types > errors.

- grasp stability (numpy, scipy, cdd; no Drake): ``CupParameters``,
  ``WrenchPolytope``, ``contact_wrench_polytope``, ``cached_wrench_polytope``,
  ``is_realizable``, ``is_realizable_lp``; multi-cup tools:
  ``ToolParameters`` of ``CupMount`` (cup and pose in the tool frame),
  ``SharedLoadSet`` (the set when the cups share the load as equal springs,
  as a rigid tool does; ``LoadSharing``), ``stiffness_shared_set`` (the
  set when compliant cups, each with its ``CupStiffness``, split the whole
  wrench by stiffness), ``tool_wrench_polytope`` (exact
  W_T of any split), ``ToolWrenchSet`` (support function and LP, for inner
  approximations); retime under them with
  ``GraspConstraint.for_tool`` or ``GraspConstraint.inner_for_tool``;
- dynamics: ``HeldObject`` (``held_object_of`` a scenario object),
  ``CupFrame`` (the cup frame of a plant), ``object_wrench``,
  ``make_arm_plant``;
- what the robot does not know: ``ObjectUncertainty`` (an object's set),
  ``GraspConstraint.robust`` (hold every object of it, with the worst
  friction and suction: ``worst_cup_polytope``), ``ObjectInertia`` (objects
  of a set, for checks and physics);
- retiming: ``retime``, ``RetimeResult``, ``JointLimits``,
  ``GraspConstraint``, ``check_trajectory``, ``TrajectoryCheck``,
  ``save_trajectory``, ``load_trajectory``, ``sample_trajectory``;
  protective stops along the path: ``protective_stop`` (keeps the grasp),
  ``joint_brake_stop`` (joints brake at their limits), ``StopResult``,
  ``stop_table`` (stops computed ahead, ``StopTable.at(t)``);
- planning: ``CyclePlanner``, ``PlannedPath``, ``GeometricPath``; MOVE
  path optimisation: ``MoveOptimizer``, ``MoveOptimizerOptions``,
  ``OptimizedMove``;
- simulation: ``MakeStation``, ``run_cycle``, ``OnlineMotions``;
- export for controllers: ``export_trajectory`` (a ROS 2 bag or a CSV at the
  controller's period, ``ExportFormat``);
- scenarios: ``load_scenario``, ``Scenario``, the shipped files'
  ``scenarios_dir`` and ``models_dir``; phases: ``Phase``;
- errors: ``RtDrakeError`` (the base of every error rt_drake raises on
  purpose), ``InputError``, ``ScenarioError``, ``TooLargeError``,
  ``RetimeError``, ``PlanningError``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from rt_drake._lazy import lazy_attributes
from rt_drake._version import __version__

if TYPE_CHECKING:  # the lazy names below, for type checkers and IDEs
    from rt_drake.contact import (
        CupMount,
        CupParameters,
        CupStiffness,
        LoadSharing,
        SharedLoadSet,
        ToolParameters,
        ToolWrenchSet,
        WrenchPolytope,
        cached_wrench_polytope,
        contact_wrench_polytope,
        is_realizable,
        is_realizable_lp,
        stiffness_shared_set,
        tool_wrench_polytope,
    )
    from rt_drake.contact.worst_cup import worst_cup_polytope
    from rt_drake.dynamics.cup_frame import CupFrame
    from rt_drake.dynamics.wrench import object_wrench
    from rt_drake.errors import InputError, RtDrakeError, ScenarioError, TooLargeError
    from rt_drake.export import ExportFormat, export_trajectory
    from rt_drake.model.held import held_object_of
    from rt_drake.model.plant import make_arm_plant
    from rt_drake.model.resources import models_dir, scenarios_dir
    from rt_drake.model.scenario import (
        Scenario,
        load_scenario,
    )
    from rt_drake.planning import (
        CyclePlanner,
        GeometricPath,
        PlannedPath,
        PlanningError,
    )
    from rt_drake.retiming import (
        GraspConstraint,
        JointLimits,
        RetimeError,
        RetimeResult,
        SavedTrajectory,
        StopNotFoundError,
        StopResult,
        StopTable,
        TrajectoryCheck,
        check_trajectory,
        joint_brake_stop,
        load_trajectory,
        path_waypoints_and_knots,
        protective_stop,
        retime,
        sample_trajectory,
        save_trajectory,
        stop_table,
    )
    from rt_drake.shaping import (
        MoveOptimizer,
        MoveOptimizerOptions,
        OptimizedMove,
    )
    from rt_drake.simulation import MakeStation, OnlineMotions, run_cycle
    from rt_drake.types.held_object import HeldObject
    from rt_drake.types.object_uncertainty import ObjectUncertainty
    from rt_drake.types.phase import Phase
    from rt_drake.uncertainty.object_samples import ObjectInertia

#: Public name -> module defining it, imported on first access.
_LAZY: dict[str, str] = {
    "CupMount": "rt_drake.contact",
    "CupParameters": "rt_drake.contact",
    "CupStiffness": "rt_drake.contact",
    "stiffness_shared_set": "rt_drake.contact",
    "ToolParameters": "rt_drake.contact",
    "LoadSharing": "rt_drake.contact",
    "SharedLoadSet": "rt_drake.contact",
    "ToolWrenchSet": "rt_drake.contact",
    "tool_wrench_polytope": "rt_drake.contact",
    "WrenchPolytope": "rt_drake.contact",
    "cached_wrench_polytope": "rt_drake.contact",
    "contact_wrench_polytope": "rt_drake.contact",
    "is_realizable": "rt_drake.contact",
    "is_realizable_lp": "rt_drake.contact",
    "worst_cup_polytope": "rt_drake.contact",
    "CupFrame": "rt_drake.dynamics.cup_frame",
    "HeldObject": "rt_drake.types.held_object",
    "held_object_of": "rt_drake.model.held",
    "object_wrench": "rt_drake.dynamics.wrench",
    "ObjectInertia": "rt_drake.uncertainty.object_samples",
    "ObjectUncertainty": "rt_drake.types.object_uncertainty",
    "InputError": "rt_drake.errors",
    "RtDrakeError": "rt_drake.errors",
    "ScenarioError": "rt_drake.errors",
    "TooLargeError": "rt_drake.errors",
    "ExportFormat": "rt_drake.export",
    "export_trajectory": "rt_drake.export",
    "Phase": "rt_drake.types.phase",
    "CyclePlanner": "rt_drake.planning",
    "GeometricPath": "rt_drake.types.path",
    "PlannedPath": "rt_drake.planning",
    "PlanningError": "rt_drake.planning",
    "MoveOptimizer": "rt_drake.shaping",
    "MoveOptimizerOptions": "rt_drake.shaping",
    "OptimizedMove": "rt_drake.shaping",
    "make_arm_plant": "rt_drake.model.plant",
    "GraspConstraint": "rt_drake.retiming",
    "JointLimits": "rt_drake.retiming",
    "RetimeError": "rt_drake.retiming",
    "RetimeResult": "rt_drake.retiming",
    "StopNotFoundError": "rt_drake.retiming",
    "StopResult": "rt_drake.retiming",
    "StopTable": "rt_drake.retiming",
    "joint_brake_stop": "rt_drake.retiming",
    "protective_stop": "rt_drake.retiming",
    "stop_table": "rt_drake.retiming",
    "SavedTrajectory": "rt_drake.retiming",
    "TrajectoryCheck": "rt_drake.retiming",
    "check_trajectory": "rt_drake.retiming",
    "load_trajectory": "rt_drake.retiming",
    "path_waypoints_and_knots": "rt_drake.types.path",
    "retime": "rt_drake.retiming",
    "sample_trajectory": "rt_drake.retiming",
    "save_trajectory": "rt_drake.retiming",
    "Scenario": "rt_drake.model.scenario",
    "load_scenario": "rt_drake.model.scenario",
    "models_dir": "rt_drake.model.resources",
    "scenarios_dir": "rt_drake.model.resources",
    "MakeStation": "rt_drake.simulation",
    "OnlineMotions": "rt_drake.simulation",
    "run_cycle": "rt_drake.simulation",
}

__all__ = [
    "__version__",
    "CupFrame",
    "CupMount",
    "CupParameters",
    "CupStiffness",
    "CyclePlanner",
    "ExportFormat",
    "GeometricPath",
    "GraspConstraint",
    "HeldObject",
    "InputError",
    "JointLimits",
    "LoadSharing",
    "MakeStation",
    "MoveOptimizer",
    "MoveOptimizerOptions",
    "ObjectInertia",
    "ObjectUncertainty",
    "OnlineMotions",
    "OptimizedMove",
    "Phase",
    "PlannedPath",
    "PlanningError",
    "RetimeError",
    "RetimeResult",
    "RtDrakeError",
    "SavedTrajectory",
    "Scenario",
    "ScenarioError",
    "SharedLoadSet",
    "StopNotFoundError",
    "StopResult",
    "StopTable",
    "TooLargeError",
    "ToolParameters",
    "ToolWrenchSet",
    "TrajectoryCheck",
    "WrenchPolytope",
    "cached_wrench_polytope",
    "check_trajectory",
    "contact_wrench_polytope",
    "export_trajectory",
    "is_realizable",
    "is_realizable_lp",
    "joint_brake_stop",
    "load_scenario",
    "held_object_of",
    "load_trajectory",
    "make_arm_plant",
    "models_dir",
    "object_wrench",
    "path_waypoints_and_knots",
    "protective_stop",
    "stop_table",
    "retime",
    "run_cycle",
    "sample_trajectory",
    "save_trajectory",
    "scenarios_dir",
    "stiffness_shared_set",
    "tool_wrench_polytope",
    "worst_cup_polytope",
]


__getattr__, __dir__ = lazy_attributes(__name__, _LAZY, __all__)
