"""Retiming under a two-cup tool against one cup and no grasp constraint.

Run: ``PYTHONPATH=. python benchmarks/bench_tool_retime.py [--repeats 3]``.

The plant is the VS060 with the suction tool (tool frame T = the plant's
``suction_cup`` frame); the path is ``SWING`` of
``tests/test_tool_retime.py`` (3 waypoints), default grid. Each cup is the
coarse model ``CupParameters(points=4, sides=3)`` (the paper's radius,
friction and forces); the tool has two of them at x = +/-0.06 m in T. The
object is a 0.8 kg box whose centre of mass is 0.01 m off the cup axis and
0.03 m below the cup.

For each grasp, in the same run: the exact set computed without the cache
(``contact_wrench_polytope`` for one cup, ``tool_wrench_polytope`` for the
tool's free split, ``SharedLoadSet`` for its spring split: rows, vertices
where the method gives them, CPU seconds), then ``retime`` ``--repeats``
times (duration, best CPU seconds). A second table: the spring split of two
and four paper cups (6 points, 4 sides; pair at x = +/-0.06 m, four at the
corners of a 0.12 m square), rows and CPU seconds, and the retime of the
same box under two paper cups (springs) against one paper cup. CPU time is
``time.process_time`` (the machine is shared). OpenBLAS is made
single-threaded, as in ``bench_retime.py``.
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402
from pydrake.multibody.plant import MultibodyPlant  # noqa: E402

from rt_drake import (  # noqa: E402
    CupMount,
    CupParameters,
    GraspConstraint,
    HeldObject,
    JointLimits,
    SharedLoadSet,
    ToolParameters,
    contact_wrench_polytope,
    retime,
    tool_wrench_polytope,
)
from rt_drake.model.parser import make_parser  # noqa: E402

CUP = CupParameters(points=4, sides=3)
TWO_CUPS = ToolParameters(
    cups=[
        CupMount(CUP, np.eye(3), [0.06, 0.0, 0.0]),
        CupMount(CUP, np.eye(3), [-0.06, 0.0, 0.0]),
    ]
)
HOME = np.array([0.0, 0.35, 1.75, 0.0, 1.04, 0.0])
SWING = np.array(
    [
        HOME,
        HOME + [0.6, -0.2, -0.2, 0.0, 0.3, 0.4],
        HOME + [1.2, 0.0, 0.0, 0, 0, 0.7],
    ]
)


def arm_plant() -> MultibodyPlant:
    """The VS060 with the suction tool welded to link6, finalized."""
    plant = MultibodyPlant(0.0)
    parser = make_parser(plant)
    (robot,) = parser.AddModels(url="package://rt_drake/robot/vs060.urdf")
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("base_link", robot))
    (tool,) = parser.AddModels(url="package://rt_drake/tool/suction_tool.urdf")
    plant.WeldFrames(
        plant.GetFrameByName("link6", robot), plant.GetFrameByName("tool", tool)
    )
    plant.Finalize()
    return plant


def box(mass: float, p_TScm: list[float]) -> HeldObject:
    """A 0.2 x 0.1 x 0.06 m box of ``mass`` kg, its centre at ``p_TScm``."""
    a, b, c = 0.2, 0.1, 0.06
    inertia = mass / 12.0 * np.diag([b * b + c * c, a * a + c * c, a * a + b * b])
    return HeldObject(mass, np.array(p_TScm), inertia)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()

    plant = arm_plant()
    limits = JointLimits.from_plant(plant)
    held = box(0.8, [0.01, 0.0, 0.03])

    rows = []
    for name, compute, make_grasp in (
        (
            "one cup",
            lambda: contact_wrench_polytope(CUP),
            lambda p: GraspConstraint(held=held, F=p.F, g=p.g, cup=CUP),
        ),
        (
            "two cups",
            lambda: tool_wrench_polytope(TWO_CUPS),
            lambda p: GraspConstraint(held=held, F=p.F, g=p.g, cup=TWO_CUPS),
        ),
        (
            "two cups, springs",
            lambda: SharedLoadSet.of(TWO_CUPS),
            lambda p: GraspConstraint(held=held, F=p.F, g=p.g, cup=TWO_CUPS),
        ),
        ("no grasp constraint", None, None),
    ):
        exact = "-"
        grasp = None
        if compute is not None:
            start = time.process_time()
            polytope = compute()
            cpu = time.process_time() - start
            vertices = getattr(polytope, "vertices", None)
            count = "-" if vertices is None else len(vertices)
            exact = f"{len(polytope.F)} / {count} / {cpu:.3f}"
            grasp = make_grasp(polytope)
        retime(plant, SWING, limits, grasp)  # warm-up (numba, caches)
        times, duration = [], 0.0
        for _ in range(args.repeats):
            start = time.process_time()
            result = retime(plant, SWING, limits, grasp)
            times.append(time.process_time() - start)
            duration = result.duration
        rows.append((name, exact, duration, min(times)))

    print(
        "| grasp | exact set (rows / vertices / CPU s) | duration (s) "
        "| retime CPU (s) |"
    )
    print("|---|---|---|---|")
    for name, exact, duration, cpu in rows:
        print(f"| {name} | {exact} | {duration:.3f} | {cpu:.3f} |")
    paper_tables(plant, limits, held, args.repeats)


def paper_tables(
    plant: MultibodyPlant, limits: JointLimits, held: HeldObject, repeats: int
) -> None:
    """Spring sets of two and four paper cups; retime two against one."""
    paper = CupParameters()
    corners = (
        [(0.06, 0.0), (-0.06, 0.0)],
        [(x, y) for x in (0.06, -0.06) for y in (0.06, -0.06)],
    )
    print()
    print("| paper cups | spring set rows | CPU (s) |")
    print("|---|---|---|")
    pair = None
    for places in corners:
        tool = ToolParameters(
            cups=[CupMount(paper, np.eye(3), [x, y, 0.0]) for x, y in places]
        )
        start = time.process_time()
        shared = SharedLoadSet.of(tool)
        cpu = time.process_time() - start
        print(f"| {len(places)} | {len(shared.F)} | {cpu:.3f} |")
        pair = pair or shared
    assert pair is not None
    one = contact_wrench_polytope(paper)
    print()
    print("| grasp (paper cups) | rows | duration (s) | retime CPU (s) |")
    print("|---|---|---|---|")
    for name, F, g in (
        ("one cup", one.F, one.g),
        ("two cups, springs", pair.F, pair.g),
    ):
        grasp = GraspConstraint(held=held, F=F, g=g)
        retime(plant, SWING, limits, grasp)  # warm-up
        times = []
        for _ in range(repeats):
            start = time.process_time()
            result = retime(plant, SWING, limits, grasp)
            times.append(time.process_time() - start)
        print(f"| {name} | {len(F)} | {result.duration:.3f} | {min(times):.3f} |")


if __name__ == "__main__":
    main()
