"""Every public function and class refuses bad arguments in one named line.

One table of (public name, a call with a bad argument, words the message must
contain): the error is an ``RtDrakeError`` (never a ``TypeError`` or an
``AttributeError`` from deep inside numpy or Drake), its message is one line
and names the argument and what was given. Array-likes are accepted where
numpy would accept them, with the same answer as arrays.
"""

from __future__ import annotations

import inspect
import types

import numpy as np
import pytest

import rt_drake
from rt_drake import (
    CupFrame,
    CupMount,
    CupParameters,
    CyclePlanner,
    GeometricPath,
    GraspConstraint,
    HeldObject,
    JointLimits,
    MakeStation,
    MoveOptimizer,
    MoveOptimizerOptions,
    ObjectInertia,
    ObjectUncertainty,
    OnlineMotions,
    SharedLoadSet,
    ToolParameters,
    ToolWrenchSet,
    WrenchPolytope,
    cached_wrench_polytope,
    check_trajectory,
    contact,
    contact_wrench_polytope,
    export_trajectory,
    is_realizable,
    is_realizable_lp,
    joint_brake_stop,
    load_scenario,
    load_trajectory,
    make_arm_plant,
    object_wrench,
    path_waypoints_and_knots,
    protective_stop,
    retime,
    retiming,
    run_cycle,
    sample_trajectory,
    save_trajectory,
    stop_table,
    tool_wrench_polytope,
    worst_cup_polytope,
)
from rt_drake.errors import RtDrakeError

HOME = np.array([0.0, 0.35, 1.75, 0.0, 1.04, 0.0])
PATH = np.array([HOME, HOME + [-0.4, 0.1, -0.2, 0.0, 0.1, -0.5]])
CUP = CupParameters(points=4)
TOOL = ToolParameters((CupMount(CUP),))
HELD = HeldObject(mass=1.0, p_CoScm_C=np.zeros(3), I_Scm_C=np.eye(3) * 1e-3)
Q = np.zeros(6)


@pytest.fixture(scope="module")
def env(scenario, plant):
    """What the calls need: a scenario, its plant, limits, a polytope, a result."""
    limits = JointLimits.from_plant(plant, scenario.robot)
    return types.SimpleNamespace(
        scenario=scenario,
        plant=plant,
        limits=limits,
        W=cached_wrench_polytope(CUP),
        result=retime(plant, PATH, limits),
    )


#: (public name, call with a bad argument, words the message must contain).
CASES = [
    # contact: the two, then every argument kind
    ("is_realizable", lambda e: is_realizable(np.zeros(6), [1, 2, 3], e.W.g),
     ["is_realizable: F must be a (rows, 6) array", "got list of shape (3,)"]),
    ("is_realizable", lambda e: is_realizable("abc", e.W.F, e.W.g),
     ["wrenches must be a (..., 6) array", "got str 'abc'"]),
    ("is_realizable", lambda e: is_realizable(np.zeros(6), e.W.F, None),
     ["g must be a (rows,) array", "got None"]),
    ("is_realizable", lambda e: is_realizable(np.zeros(6), e.W.F, e.W.g[:-1]),
     ["g must have one offset per row of F"]),
    ("is_realizable", lambda e: is_realizable(np.zeros(6), e.W.F, e.W.g, tol=None),
     ["tol must be a finite number >= 0", "got None"]),
    ("contact_wrench_polytope", lambda e: contact_wrench_polytope(None),
     ["contact_wrench_polytope: cup must be a CupParameters", "got None"]),
    ("contact_wrench_polytope", lambda e: contact_wrench_polytope(CUP, "4 GB"),
     ["max_memory must be a finite number > 0", "got str '4 GB'"]),
    ("cached_wrench_polytope", lambda e: cached_wrench_polytope("paper cup"),
     ["cup must be a CupParameters or a ToolParameters", "got str 'paper cup'"]),
    ("cached_wrench_polytope", lambda e: cached_wrench_polytope(CUP, directory=3),
     ["directory must be a file path", "got int 3"]),
    ("cached_wrench_polytope", lambda e: cached_wrench_polytope(TOOL, max_facets=0),
     ["max_facets must be an integer >= 1", "got int 0"]),
    ("is_realizable_lp", lambda e: is_realizable_lp(np.zeros(6), None),
     ["is_realizable_lp: cup must be a CupParameters", "got None"]),
    ("is_realizable_lp", lambda e: is_realizable_lp([np.nan] * 6, CUP),
     ["wrenches must be a (..., 6) array of finite numbers", "nan at (0,)"]),
    ("is_realizable_lp", lambda e: is_realizable_lp(np.zeros(6), CUP, tol=-1.0),
     ["tol must be a finite number >= 0", "got float -1.0"]),
    ("tool_wrench_polytope", lambda e: tool_wrench_polytope(CUP),
     ["tool must be a ToolParameters", "got CupParameters"]),
    ("tool_wrench_polytope", lambda e: tool_wrench_polytope(TOOL, max_facets=2.5),
     ["max_facets must be an integer", "got float 2.5"]),
    ("worst_cup_polytope", lambda e: worst_cup_polytope(TOOL),
     ["worst_cup_polytope: cup must be a CupParameters", "got ToolParameters"]),
    ("SharedLoadSet", lambda e: SharedLoadSet.of(None),
     ["SharedLoadSet.of: tool must be a ToolParameters", "got None"]),
    ("SharedLoadSet", lambda e: SharedLoadSet(TOOL, e.W.F, None),
     ["SharedLoadSet: g must be a (rows,) array", "got None"]),
    ("ToolWrenchSet", lambda e: ToolWrenchSet(CUP),
     ["ToolWrenchSet: cup must be a ToolParameters", "got CupParameters"]),
    ("ToolWrenchSet", lambda e: ToolWrenchSet(TOOL).support([1, 2]),
     ["directions must be a (..., 6) array", "got list of shape (2,)"]),
    ("WrenchPolytope", lambda e: WrenchPolytope(CUP, e.W.F, e.W.g, None),
     ["WrenchPolytope: vertices must be a (count, 6) array", "got None"]),
    ("with_suction_force", lambda e: contact.with_suction_force(e.W, "20 N"),
     ["with_suction_force: suction_force must be a finite number", "'20 N'"]),
    ("with_suction_force", lambda e: contact.with_suction_force(None, 20.0),
     ["with_suction_force: polytope must be a WrenchPolytope", "got None"]),
    ("guided_approximation",
     lambda e: contact.guided_approximation(None, np.zeros((3, 6)), 12),
     ["guided_approximation: polytope must be a WrenchPolytope", "got None"]),
    ("guided_approximation", lambda e: contact.guided_approximation(e.W, None, 12),
     ["guided_approximation: guiding_samples must be a (N, 6) array", "None"]),
    ("guided_approximation",
     lambda e: contact.guided_approximation(e.W, np.zeros((3, 6)), 12, tol="x"),
     ["guided_approximation: tol must be a finite number", "got str 'x'"]),
    ("object_wrench_sampler", lambda e: contact.object_wrench_sampler(mass="x"),
     ["object_wrench_sampler: mass must be a finite number", "got str 'x'"]),
    ("cache_path", lambda e: contact.cache_path(None),
     ["cache_path: cup must be a CupParameters", "got None"]),
    ("load_polytope", lambda e: contact.load_polytope(None, CUP),
     ["load_polytope: path must be a file path", "got None"]),
    ("load_polytope", lambda e: contact.load_polytope("w.npz", None),
     ["load_polytope: cup must be a CupParameters", "got None"]),
    ("save_polytope", lambda e: contact.save_polytope(3, e.W),
     ["save_polytope: path must be a file path", "got int 3"]),
    ("save_polytope", lambda e: contact.save_polytope("w.npz", None),
     ["save_polytope: polytope must be a WrenchPolytope", "got None"]),
    ("lp_residual", lambda e: contact.lp_residual(np.zeros(5), CUP),
     ["wrenches must be a (..., 6) array", "shape (5,)"]),
    ("shared_load_residual", lambda e: contact.shared_load_residual(Q, CUP),
     ["shared_load_residual: tool must be a ToolParameters", "got CupParameters"]),
    ("shared_load_polytope", lambda e: contact.shared_load_polytope(CUP),
     ["shared_load_polytope: tool must be a ToolParameters", "got CupParameters"]),
    ("stiffness_split", lambda e: contact.stiffness_split(CUP),
     ["stiffness_split: tool must be a ToolParameters", "got CupParameters"]),
    ("stiffness_split", lambda e: contact.stiffness_split(TOOL),
     ["cup 0: load sharing 'stiffness' needs the cup's stiffness", "got none"]),
    ("stiffness_shared_polytope", lambda e: contact.stiffness_shared_polytope(None),
     ["stiffness_shared_polytope: tool must be a ToolParameters", "got None"]),
    ("stiffness_shared_set", lambda e: rt_drake.stiffness_shared_set(CUP),
     ["stiffness_shared_set: tool must be a ToolParameters", "got CupParameters"]),
    ("CupStiffness", lambda e: rt_drake.CupStiffness(700.0, 0.0, 2.0, 1.0),
     ["cup stiffness lateral must be finite and > 0 N/m", "got 0.0"]),
    ("CupStiffness", lambda e: rt_drake.CupStiffness(700.0, 1e3, None, 1.0),
     ["cup stiffness tilt must be a number", "got None"]),
    ("CupMount", lambda e: CupMount(CUP, stiffness=700.0),
     ["stiffness must be a CupStiffness or None", "got float"]),
    ("peel_rows", lambda e: contact.peel_rows(TOOL),
     ["peel_rows: cup must be a CupParameters", "got ToolParameters"]),
    ("peel_rows", lambda e: contact.peel_rows(CUP),
     ["peel_rows: cup.peel_fraction must be a number in (0, 1]", "got None"]),
    ("grasp_matrices", lambda e: contact.grasp_matrices(TOOL),
     ["grasp_matrices: cup must be a CupParameters", "got ToolParameters"]),
    ("suction_wrench", lambda e: contact.suction_wrench(None),
     ["suction_wrench: cup must be a CupParameters", "got None"]),
    ("tool_summands", lambda e: contact.tool_summands(CUP),
     ["tool_summands: tool must be a ToolParameters", "got CupParameters"]),
    ("tool_symmetry", lambda e: contact.tool_symmetry(None),
     ["tool_symmetry: tool must be a ToolParameters", "got None"]),
    ("CupParameters", lambda e: CupParameters(friction=None),
     ["friction must be a number", "None"]),
    ("CupMount", lambda e: CupMount(CUP, p_TC=[0.0, 0.0]),
     ["p_TC must be 3 finite numbers"]),
    ("ToolParameters", lambda e: ToolParameters(None),
     ["cups must be a list of CupMount", "NoneType"]),
    # dynamics and objects
    ("HeldObject", lambda e: HeldObject(1.0, [0.0, 0.0], np.eye(3)),
     ["p_CoScm_C must be 3 finite numbers"]),
    ("object_wrench", lambda e: object_wrench(e.plant, None, Q, Q, Q),
     ["object_wrench: held must be a HeldObject", "got None"]),
    ("object_wrench", lambda e: object_wrench(e.plant, HELD, [np.nan] * 6, Q, Q),
     ["object_wrench: q must be a (..., n) array of finite", "nan at (0,)"]),
    ("object_wrench", lambda e: object_wrench(None, HELD, Q, Q, Q),
     ["plant must be a MultibodyPlant", "got None"]),
    ("ObjectInertia", lambda e: ObjectInertia(1.0, None, np.eye(3)),
     ["ObjectInertia: p_OoScm_O must be a (3,) array", "got None"]),
    ("ObjectInertia", lambda e: ObjectInertia(0.0, Q[:3], np.eye(3)),
     ["ObjectInertia: mass must be a finite number > 0", "got float 0.0"]),
    ("ObjectUncertainty", lambda e: ObjectUncertainty(mass="x"),
     ["uncertainty.mass must be a finite number", "'x'"]),
    ("CupFrame", lambda e: CupFrame(None, ()),
     ["CupFrame: frame must be a Frame", "got None"]),
    # retiming
    ("JointLimits", lambda e: JointLimits(None, np.ones(6)),
     ["JointLimits: velocity must be a (joints,) array", "got None"]),
    ("JointLimits", lambda e: JointLimits(np.ones(6), np.ones((2, 3))),
     ["acceleration must be a (joints,) array", "got ndarray of shape (2, 3)"]),
    ("JointLimits", lambda e: JointLimits(np.ones(6), np.ones(6), [1.0] * 5 + [0]),
     ["JointLimits: torque limits must be > 0"]),
    ("JointLimits", lambda e: e.limits.with_acceleration_ramp(0.0),
     ["JointLimits.with_acceleration_ramp: ramp_s", "> 0, got float 0.0"]),
    ("JointLimits", lambda e: JointLimits(np.ones(6), np.ones(6), jerk=[np.nan] * 6),
     ["JointLimits: jerk must be a (joints,) array of finite numbers"]),
    ("JointLimits", lambda e: JointLimits(np.ones(6), np.ones(6), jerk=np.ones(5)),
     ["limits differ in length", "jerk 5"]),
    ("JointLimits", lambda e: JointLimits.from_plant(None),
     ["JointLimits.from_plant: plant must be a MultibodyPlant", "got None"]),
    ("GraspConstraint", lambda e: GraspConstraint(None, e.W.F, e.W.g),
     ["GraspConstraint: held must be a HeldObject", "got None"]),
    ("GraspConstraint", lambda e: GraspConstraint(HELD, np.zeros((0, 6)), []),
     ["GraspConstraint: F must be a (rows, 6) array", "shape (0, 6)"]),
    ("GraspConstraint", lambda e: GraspConstraint.for_cup(HELD, None),
     ["GraspConstraint.for_cup: cup must be a CupParameters", "got None"]),
    ("GraspConstraint",
     lambda e: GraspConstraint.for_cup(HELD, CupParameters(points=4, friction=0.0)),
     ["GraspConstraint.for_cup: cup.friction must be > 0", "got 0.0"]),
    ("GraspConstraint", lambda e: GraspConstraint.robust(HELD, None, CUP),
     ["GraspConstraint.robust: uncertainty must be an ObjectUncertainty", "None"]),
    ("GraspConstraint",
     lambda e: GraspConstraint.robust(HELD, ObjectUncertainty(), CUP, R_CO=np.eye(2)),
     ["R_CO must be a (3, 3) array", "got ndarray of shape (2, 2)"]),
    ("GraspConstraint", lambda e: GraspConstraint.for_objects([], CUP),
     ["for_objects: objects must be a non-empty list of HeldObject"]),
    ("GraspConstraint", lambda e: GraspConstraint.for_tool(HELD, CUP),
     ["for_tool needs a ToolParameters", "got CupParameters"]),
    ("GraspConstraint", lambda e: GraspConstraint.inner_for_tool(HELD, TOOL, None),
     ["inner_for_tool: guiding_samples must be a (count, 6) array", "got None"]),
    ("CupGrasp", lambda e: retiming.CupGrasp(HELD, e.W.F, e.W.g, cup=None),
     ["CupGrasp: cup must be a CupParameters", "got None"]),
    ("CupGrasp",
     lambda e: retiming.CupGrasp(HELD, e.W.F, e.W.g, CupParameters(friction=0.0)),
     ["CupGrasp: cup.friction must be > 0", "got 0.0"]),
    ("ToolGrasp", lambda e: retiming.ToolGrasp(HELD, e.W.F, e.W.g, tool=CUP),
     ["ToolGrasp: tool must be a ToolParameters", "got CupParameters"]),
    ("ObjectSetGrasp",
     lambda e: retiming.ObjectSetGrasp(HELD, e.W.F, e.W.g, CUP, objects=[HELD]),
     ["ObjectSetGrasp: objects must be an ObjectSet", "got list"]),
    ("export_trajectory",
     lambda e: export_trajectory(None, "m.mcap", period=0.008, plant=e.plant),
     ["export_trajectory: trajectory must be a Trajectory or a SavedTrajectory",
      "got None"]),
    ("export_trajectory",
     lambda e: export_trajectory(e.result.trajectory, 3, period=0.008),
     ["export_trajectory: out must be a file path", "got int 3"]),
    ("export_trajectory",
     lambda e: export_trajectory(e.result.trajectory, "m.mcap", period=None),
     ["export_trajectory: period must be a finite number > 0", "got None"]),
    ("export_trajectory",
     lambda e: export_trajectory(e.result.trajectory, "m.mcap", format="bag",
                                 period=0.008),
     ["export_trajectory: format must be one of mcap, csv", "'bag'"]),
    ("export_trajectory",
     lambda e: export_trajectory(e.result.trajectory, "m.mcap", period=0.008,
                                 plant="ur5e"),
     ["export_trajectory: plant must be a MultibodyPlant", "got str 'ur5e'"]),
    ("export_trajectory",
     lambda e: export_trajectory(e.result.trajectory, "m.mcap", period=0.008,
                                 joint_names=["a"] * 6),
     ["export_trajectory: joint_names", "'a' is given twice"]),
    ("retime_for_ring", lambda e: retiming.retime_for_ring(
        lambda g: None, PATH, CUP, None, e.plant),
     ["retime_for_ring: grasp must be a GraspConstraint", "got CupParameters"]),
    ("ring_load", lambda e: retiming.ring_load(e.plant, None, CUP, None),
     ["ring_load: grasp must be a GraspConstraint", "got CupParameters"]),
    ("retime", lambda e: retime(None, PATH, e.limits),
     ["retime: plant must be a MultibodyPlant", "got None"]),
    ("retime", lambda e: retime(e.plant, PATH, None),
     ["retime: limits must be a JointLimits", "got None"]),
    ("retime", lambda e: retime(e.plant, PATH, e.limits, grasp=CUP),
     ["retime: grasp must be a GraspConstraint", "got CupParameters"]),
    ("retime", lambda e: retime(e.plant, PATH, e.limits, cup="suction_cup"),
     ["retime: cup must be a CupFrame", "got str 'suction_cup'"]),
    ("retime", lambda e: retime(e.plant, "home to goal", e.limits),
     ["path", "str"]),
    ("retime", lambda e: retime(e.plant, PATH, e.limits, sd_end="fast"),
     ["sd_end", "'fast'"]),
    ("protective_stop",
     lambda e: protective_stop(e.plant, PATH, e.limits, None, 0.1),
     ["stop: result must be a RetimeResult", "got None"]),
    ("protective_stop",
     lambda e: protective_stop(e.plant, PATH, e.limits, e.result, float("inf")),
     ["stop: t must be a finite number", "inf"]),
    ("joint_brake_stop",
     lambda e: joint_brake_stop(e.plant, PATH, "fast", e.result, 0.1),
     ["stop: limits must be a JointLimits", "got str 'fast'"]),
    ("stop_table", lambda e: stop_table(e.plant, PATH, e.limits, e.result, 0.0),
     ["stop_table: period must be a finite number > 0", "got float 0.0"]),
    ("stop_table", lambda e: stop_table(e.plant, PATH, e.limits, None, 0.01),
     ["stop_table: result must be a RetimeResult", "got None"]),
    ("stop_table",
     lambda e: stop_table(e.plant, PATH, e.limits, e.result, 10.0).at(-1.0),
     ["stop table: t must be a finite number in [0", "got float -1.0"]),
    ("check_trajectory", lambda e: check_trajectory(e.plant, None, e.limits),
     ["check_trajectory: trajectory must be a Trajectory", "got None"]),
    ("check_trajectory",
     lambda e: check_trajectory(e.plant, e.result.trajectory, e.limits, rate_hz=0),
     ["rate_hz must be a finite number > 0", "got int 0"]),
    ("path_waypoints_and_knots", lambda e: path_waypoints_and_knots("abc"),
     ["waypoints must be a (K, n) array", "got str 'abc'"]),
    ("path_waypoints_and_knots", lambda e: path_waypoints_and_knots(None),
     ["waypoints must be a (K, n) array", "got None"]),
    ("joint_floor", lambda e: retiming.joint_floor(np.ones(6), None, 0.0, 0.0),
     ["joint_floor: limits must be a JointLimits", "got None"]),
    ("joint_floor",
     lambda e: retiming.joint_floor(np.ones(6), e.limits, -1.0, 0.0),
     ["joint_floor: end speeds must be >= 0"]),
    ("segment_floor",
     lambda e: retiming.segment_floor(np.zeros(5), np.ones(6), e.limits, 0.0, 0.0),
     ["segment_floor: q_from must be a (6,) array", "shape (5,)"]),
    ("junction_speeds",
     lambda e: retiming.junction_speeds([np.nan] * 6, np.ones(6), e.limits),
     ["junction_speeds: line_step must be", "nan"]),
    ("junction_accelerations",
     lambda e: retiming.junction_accelerations(np.zeros((2, 6)), e.limits),
     ["junction_accelerations: line_end must be a (3, 6) array", "shape (2, 6)"]),
    ("joint_floor",
     lambda e: retiming.joint_floor(np.ones(6), e.limits, 0.0, 0.0, np.ones(6), -1.0),
     ["joint_floor: end accelerations must be >= 0"]),
    ("rest_to_rest_jerk",
     lambda e: retiming.rest_to_rest_jerk(1.0, 1.0, 1.0, 0.0),
     ["rest_to_rest_jerk: j must be > 0", "0.0"]),
    ("chord_knots", lambda e: retiming.chord_knots("abc"),
     ["chord_knots: waypoints must be a (N, n) array", "got str 'abc'"]),
    ("TimeScaled", lambda e: retiming.TimeScaled(None, 2.0),
     ["TimeScaled: trajectory must be a Trajectory", "got None"]),
    ("TimeScaled", lambda e: retiming.TimeScaled(e.result.trajectory, np.inf),
     ["TimeScaled: factor must be a finite number > 0", "got float inf"]),
    ("sample_trajectory",
     lambda e: sample_trajectory(e.plant, None, HELD, None, CUP, "x", PATH, [0, 1]),
     ["sample_trajectory: result must be a RetimeResult", "got None"]),
    ("sample_trajectory",
     lambda e: sample_trajectory(e.plant, e.result, HELD, None, 0, "x", PATH, [0, 1]),
     ["sample_trajectory: cup must be a CupParameters", "got int 0"]),
    ("sample_trajectory",
     lambda e: sample_trajectory(e.plant, e.result, HELD, None, CUP, "x", PATH, [0]),
     ["knots must have one value per waypoint (2), got 1"]),
    ("save_trajectory", lambda e: save_trajectory(None, None),
     ["save_trajectory: path must be a file path", "got None"]),
    ("save_trajectory", lambda e: save_trajectory("t.npz", e.result),
     ["save_trajectory: saved must be a SavedTrajectory", "got RetimeResult"]),
    ("load_trajectory", lambda e: load_trajectory(3),
     ["load_trajectory: path must be a file path", "got int 3"]),
    # planning, scenario, simulation
    ("GeometricPath", lambda e: GeometricPath.from_waypoints([1.0, 2.0]),
     ["waypoints must be a (N, n) array", "got list of shape (2,)"]),
    ("held_object_of", lambda e: rt_drake.held_object_of(None),
     ["held_object_of: obj must be an ObjectConfig", "got None"]),
    ("held_object_of",
     lambda e: rt_drake.held_object_of(e.scenario.objects[0], plant="plant"),
     ["held_object_of: plant must be a MultibodyPlant", "got str 'plant'"]),
    ("load_scenario", lambda e: load_scenario(None),
     ["load_scenario: path must be a file path", "got None"]),
    ("make_arm_plant", lambda e: make_arm_plant("stack_four_objects"),
     ["make_arm_plant: scenario must be a Scenario", "got str"]),
    ("CyclePlanner", lambda e: CyclePlanner(None),
     ["CyclePlanner: scenario must be a Scenario", "got None"]),
    ("CyclePlanner", lambda e: CyclePlanner(e.scenario, budget_s=np.nan),
     ["budget", "nan"]),
    ("MoveOptimizer", lambda e: MoveOptimizer(e.plant, None),
     ["MoveOptimizer: limits must be a JointLimits", "got None"]),
    ("MoveOptimizerOptions", lambda e: MoveOptimizerOptions(max_evaluations="x"),
     ["MoveOptimizerOptions: max_evaluations must be a finite number",
      "got str 'x'"]),
    ("MakeStation", lambda e: MakeStation(None),
     ["MakeStation: scenario must be a Scenario", "got None"]),
    ("OnlineMotions", lambda e: OnlineMotions(None),
     ["OnlineMotions: scenario must be a Scenario", "got None"]),
    ("OnlineMotions", lambda e: OnlineMotions(e.scenario, move_speed=np.nan),
     ["OnlineMotions: move_speed must be a finite number > 0", "nan"]),
    ("run_cycle", lambda e: run_cycle(None, None),
     ["run_cycle: scenario must be a Scenario", "got None"]),
    ("run_cycle", lambda e: run_cycle(e.scenario, None),
     ["run_cycle: motions must be a MotionSource", "got None"]),
]  # fmt: skip


@pytest.mark.parametrize(
    "name,call,words", CASES, ids=[f"{c[0]}-{i}" for i, c in enumerate(CASES)]
)
def test_a_bad_argument_is_refused_in_one_line_naming_it(env, name, call, words):
    with pytest.raises(RtDrakeError) as info:
        call(env)
    message = str(info.value)
    assert isinstance(info.value, ValueError)  # every InputError is one
    assert "\n" not in message, message
    for word in words:
        assert word in message, (word, message)


#: Public names with no argument to check: enums (``Phase("x")`` is Python's
#: own ValueError), results the package builds rather than takes, and
#: functions of no argument.
NOT_CALLED = {
    "Engine",
    "ExportFormat",
    "LoadSharing",
    "Margin",
    "Phase",
    "RetimeStatus",
    "PathLike",  # type annotations (a union, a Protocol), not constructed
    "WaypointPath",
    "WorstMargin",
    "Excess",
    "GuidedApproximation",
    "OptimizedMove",
    "PlannedPath",
    "RetimeResult",
    "RingLoad",  # built by ring_load
    "RingRetime",  # built by retime_for_ring
    "SavedTrajectory",
    "StopResult",  # built by protective_stop and joint_brake_stop
    "StopTable",  # built by stop_table
    "Scenario",  # built by load_scenario, which checks every key
    "TimedPath",  # built by retime
    "JerkTimedPath",  # built by retime with jerk limits
    "PathTrajectory",  # the base of the two above (isinstance checks)
    "TrajectoryCheck",
    "default_cache_dir",
    "models_dir",
    "scenarios_dir",
    "warm_up",
}


@pytest.mark.parametrize(
    "face", [rt_drake, contact, retiming], ids=lambda m: m.__name__
)
def test_the_table_covers_every_public_function_and_class(face):
    covered = {name for name, _, _ in CASES}
    public = set()
    for name in face.__all__:
        value = getattr(face, name)
        is_error = inspect.isclass(value) and issubclass(value, BaseException)
        if callable(value) and not is_error and name not in NOT_CALLED:
            public.add(name)
    assert public - covered == set()


def test_array_likes_give_the_same_answers_as_arrays(env):
    F, g = env.W.F, env.W.g
    rng = np.random.default_rng(0)
    wrenches = rng.normal(scale=[0.2, 0.2, 0.05, 5.0, 5.0, 20.0], size=(50, 6))
    expected = np.all(wrenches @ F.T <= g + 1e-9, axis=1)  # the definition
    assert 0 < expected.sum() < len(expected)
    got = is_realizable(wrenches.tolist(), F.tolist(), g.tolist())
    assert np.array_equal(got, expected)
    assert bool(is_realizable([0.0] * 6, F.tolist(), tuple(g))) is True
    grasp = GraspConstraint(HELD, F.tolist(), g.tolist())
    assert np.array_equal(grasp.F, F) and np.array_equal(grasp.g, g)
    limits = JointLimits([2.0] * 6, [5.0] * 6)
    assert np.array_equal(limits.velocity, np.full(6, 2.0))


def test_a_zero_row_grasp_constraint_no_longer_retimes_unconstrained():
    with pytest.raises(RtDrakeError, match=r"F must be a \(rows, 6\).*shape \(0, 6\)"):
        GraspConstraint(HELD, np.zeros((0, 6)), np.zeros(0))


@pytest.mark.parametrize(
    "old,new,key,value",
    [
        ("  friction: 0.3", "  friction: 0.0", "cup.friction", "0.0"),
        ("  friction: 0.3", "  friction: 0.3\n  friction_min: 0.0",
         "cup.friction_min", "0.0"),
    ],
)  # fmt: skip
def test_a_frictionless_scenario_cup_is_refused_naming_the_key(
    tmp_path, scenario_paths, old, new, key, value
):
    from rt_drake.errors import ScenarioError

    text = scenario_paths["stack_four_objects"].read_text()
    assert old in text
    path = tmp_path / "frictionless.yaml"
    path.write_text(text.replace(old, new, 1))
    with pytest.raises(ScenarioError) as info:
        load_scenario(path)
    message = str(info.value)
    assert f"key '{key}'" in message and f"got {value}" in message, message
    assert "frictionless.yaml" in message and "\n" not in message
