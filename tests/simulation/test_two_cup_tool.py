"""A two-cup tool in the simulated cell: it holds what one cup drops.

The heavy carton (2.2 kg, 21.6 N of weight) hangs under the tool. The MOVE
(lift off the destination zone, then swing joint 1) is retimed under the set
of a coarse two-cup tool (4 rim points, 3-sided friction polygons, 20 N
each, 0.12 m apart) whose rims share the load as equal springs (436 rows).
The physics is the independent check: the station applies one vacuum force
and one rim per cup, and the same commanded trajectory is played to the
two-cup tool and to one cup at the tool frame. Two cups carry the carton along;
one cup lets it fall.
"""

from __future__ import annotations

import numpy as np
import pytest
from motion_helpers import IkMotions
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import (
    ConstantVectorSource,
    Demultiplexer,
    TrajectorySource,
)
from pydrake.trajectories import PiecewisePolynomial

from rt_drake import CupFrame, GraspConstraint, JointLimits, retime
from rt_drake.model.object_model import OBJECT_BODY
from rt_drake.model.plant import (
    CUP_FRAME,
    make_arm_plant,
)
from rt_drake.model.resources import scenarios_dir
from rt_drake.model.scenario import load_scenario
from rt_drake.simulation._station import MakeStation
from rt_drake.simulation.move_grasp import held_object

COARSE = """radius: 0.0125
    points: 4
    friction: 0.3
    sides: 3
    suction_force: 20.0
    max_normal_force: 33.3"""
TWO_CUPS = f"""tool:
  cups:
  - pose: {{translation: [0.06, 0.0, 0.0]}}
    {COARSE}
  - pose: {{translation: [-0.06, 0.0, 0.0]}}
    {COARSE}
"""
ONE_CUP = "cup:\n  " + COARSE.replace("\n    ", "\n  ") + "\n"
LIFT = 0.15  # m
SWING = 0.5  # rad, joint 1 (away from the bin)
T_HOLD = 0.3  # s, sealed at rest before the MOVE
T_AFTER = 0.3  # s, at rest after it


def _scenario(tmp_path, cups: str, name: str):
    """carton_two_cups.yaml with its tool replaced by ``cups``.

    The carton starts at its goal, on the open destination zone: the test
    lifts it clear of every wall.
    """
    text = (scenarios_dir() / "carton_two_cups.yaml").read_text()
    start = next(line for line in text.splitlines() if "  start:" in line)
    goal = next(line for line in text.splitlines() if "  goal:" in line)
    text = text.replace(start, goal.replace("goal:", "start:"))
    head, rest = text.split("tool:\n", 1)
    tail = rest[rest.index("\nvacuum:") :]
    path = tmp_path / f"{name}.yaml"
    path.write_text(head + cups + tail)
    return load_scenario(path)


def _simulate(scenario, trajectory, t_final):
    """Play ``trajectory`` after T_HOLD with the valve on; X_CO per 10 ms."""
    station = MakeStation(scenario)
    builder = DiagramBuilder()
    cell = builder.AddSystem(station.diagram)
    source = builder.AddSystem(
        TrajectorySource(
            trajectory, output_derivative_order=2, zero_derivatives_beyond_limits=True
        )
    )
    split = builder.AddSystem(Demultiplexer([12, 6]))
    builder.Connect(source.get_output_port(), split.get_input_port())
    builder.Connect(split.get_output_port(0), cell.GetInputPort("robot.desired_state"))
    builder.Connect(
        split.get_output_port(1), cell.GetInputPort("robot.desired_acceleration")
    )
    valve = builder.AddSystem(ConstantVectorSource([1.0]))
    builder.Connect(valve.get_output_port(), cell.GetInputPort("suction.valve"))
    simulator = Simulator(builder.Build())
    context = simulator.get_mutable_context()
    plant = station.plant
    plant_context = plant.GetMyMutableContextFromRoot(context)
    plant.SetPositions(plant_context, station.models.robot, trajectory.value(0.0))
    (name,) = station.object_names
    body = plant.GetBodyByName(OBJECT_BODY, station.models.objects[name])
    cup = plant.GetFrameByName(CUP_FRAME)
    offsets = []
    for t in np.arange(0.0, t_final + 1e-9, 0.01):
        simulator.AdvanceTo(t)
        X_CO = cup.CalcPoseInWorld(plant_context).inverse() @ plant.EvalBodyPoseInWorld(
            plant_context, body
        )
        offsets.append(X_CO.translation())
    return np.array(offsets)


def _delayed(result, delay: float) -> PiecewisePolynomial:
    """The retimed motion after ``delay`` s at rest: cubic Hermite, 2 ms knots."""
    times = np.linspace(0.0, result.duration, int(result.duration / 2e-3) + 2)
    q, v = result.trajectory.sample(times + result.trajectory.start_time(), order=1)
    times = np.concatenate([[0.0], times + delay])
    q = np.vstack([q[:1], q])
    v = np.vstack([np.zeros_like(v[:1]), v])
    return PiecewisePolynomial.CubicHermite(times, q.T, v.T)


@pytest.fixture(scope="module")
def scenarios_and_move(tmp_path_factory):
    """The two-cup and one-cup scenarios and the MOVE retimed for two cups."""
    tmp_path = tmp_path_factory.mktemp("two_cups")
    two = _scenario(tmp_path, TWO_CUPS, "two")
    one = _scenario(tmp_path, ONE_CUP, "one")
    obj = two.objects[0]
    ik = IkMotions(two)
    X_WC = ik.grasp(obj)
    q_grasp = ik.ik(X_WC, np.array(two.robot.home))
    q_up = ik.ik(ik.raised(X_WC, LIFT), q_grasp)
    plant = make_arm_plant(two)
    grasp = GraspConstraint.for_tool(
        held_object(obj, obj.grasp.GetDeterministicValue()), two.tool_parameters()
    )
    result = retime(
        plant,
        np.array([q_grasp, q_up, q_up + [SWING, 0, 0, 0, 0, 0]]),
        JointLimits.from_plant(plant, two.robot),
        grasp,
        cup=CupFrame.of(plant),
    )
    return two, one, result


@pytest.mark.slow
def test_two_cups_carry_the_carton_one_cup_drops_it(scenarios_and_move):
    two, one, result = scenarios_and_move
    trajectory = _delayed(result, T_HOLD)
    t_final = T_HOLD + result.duration + T_AFTER
    carried = _simulate(two, trajectory, t_final)
    drift = np.linalg.norm(carried - carried[0], axis=1).max()
    assert drift < 2e-3, drift
    dropped = _simulate(one, trajectory, t_final)
    assert np.linalg.norm(dropped[-1] - dropped[0]) > 0.05
