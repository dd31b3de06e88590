"""The pick's path shaped as the MOVE's: the transit between its two lines.

The planner's blended pick (:mod:`rt_drake.planning._pick`) is one clamped
spline from the placed object (or home) through the retreat's IK points up
to the retreat's top, the transit, and the descent's IK points from the
approach pose down to the grasp; the spline is refined only until it is
clean and stays on its lines. :func:`shape_pick` keeps both lines, point
for point, and shapes the transit between them with the MOVE's optimiser
(:meth:`~._optimizer.MoveOptimizer.shape`): the family
:meth:`~._family.PathFamily.between_lines` (free via points starting at
the transit's corners, :func:`~._family.corners` over ``s`` in
``[s_retreat, s_approach]``), scored by the coarse TOPP-RA under the joint
velocity and acceleration limits alone (nothing is held: no grasp rows, no
tilt bound), in the same number of candidate paths as a MOVE
(``planning.max_evaluations``; no clock decides anything), on a search grid
of :data:`SEARCH_GRIDPOINTS` points (placed by the blended path's time, as
a MOVE's 24: on 24 the coarse retimer's last segment, over the short
descent line, took 126 s for a 0.76 s pick of the stacking cell; 48 points
follow the final retime). A candidate is kept if

- the cup stays on both lines within the blended pick's tolerances
  (:func:`rt_drake.planning.line_deviation`: 1 mm, 0.5 deg, 200 samples
  per line);
- the planner's continuous collision check
  (:func:`rt_drake.planning.dense_check.check_path`) passes in the REACH
  scene the blended pick was certified in (the grasped face, and the face
  under the cup at the start, moved in by the touch allowance);
- its retime as played (``played``: e.g. the cycle's jerk-limited retime
  placed by the acceleration-limited profile of
  :func:`~._finish.retime_adaptive`; without it, that profile) is shorter
  than the blended path's on the same scheme; of the ``finish_tries``
  best candidates of the search, the fastest so is kept. The search itself
  scores paths at the acceleration limits, as a MOVE's: a jerk-limited
  retime costs about 60 times more.

Else the blended pick is returned as it was (``improved`` False, the reasons
in ``rejected``).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

import numpy as np

from rt_drake.planning import PlannedPick, line_deviation
from rt_drake.planning.dense_check import check_path
from rt_drake.planning.scene import PlanningScene
from rt_drake.retiming import RetimeResult
from rt_drake.shaping._family import PathFamily, corners
from rt_drake.shaping._optimizer import MoveOptimizer
from rt_drake.shaping._options import MovePlanner, OptimizedMove
from rt_drake.shaping._shape_task import ShapeTask, StageClock
from rt_drake.types.path import GeometricPath
from rt_drake.types.phase import Phase

#: Points of the pick's search grid (module docstring).
SEARCH_GRIDPOINTS = 48


@dataclasses.dataclass(frozen=True)
class ShapedPick:
    """Result of :func:`shape_pick`.

    Attributes:
        pick: The pick to play: the blended pick with the shaped path (its
            ``s_retreat`` and ``s_approach`` at the shaped path's line
            tops), or the blended pick as it was if not ``optimized.improved``.
        optimized: The search's result (``spline``: the blended pick's path;
            ``retimed``: ``pick``'s path at the acceleration limits).
    """

    pick: PlannedPick
    optimized: OptimizedMove


def shape_pick(
    optimizer: MoveOptimizer,
    planner: MovePlanner,
    pick: PlannedPick,
    played: Callable[[GeometricPath, RetimeResult], RetimeResult] | None = None,
    timings: dict[str, float] | None = None,
) -> ShapedPick:
    """A pick as fast as found from the blended pick ``pick`` (same lines).

    Args:
        optimizer: The MOVE's optimiser (its options: the budget, via
            points, steps; its limits: without jerk).
        planner: The cycle planner, whose scene holds the objects as the
            pick sees them.
        pick: The planner's blended pick.
        played: The retime a pick is played with, from its path and its
            acceleration-limited retime (None: that retime).
        timings: Stage times (s) already spent.

    Raises:
        RetimeError: the blended path cannot be retimed.
    """
    planned = pick.path
    optimizer = optimizer.with_options(
        dataclasses.replace(optimizer.options, search_gridpoints=SEARCH_GRIDPOINTS)
    )
    chain = optimizer.chain
    watch = StageClock(timings)
    with watch("setup"):
        scene = planner.prepare(
            Phase.REACH, planned.object, planned.q_start, planned.X_OC
        )
    knots, waypoints = planned.path.knots, planned.path.waypoints
    head = waypoints[knots <= pick.s_retreat]
    tail = waypoints[knots >= pick.s_approach]
    span = (pick.s_retreat, pick.s_approach)
    scale = np.broadcast_to(
        np.asarray(optimizer.options.joint_scale, float), chain.num_joints
    )

    def family_through(via: int) -> PathFamily:
        reference = corners(planned.path, via, span=span)
        return PathFamily.between_lines(chain, head, tail, reference, scale)

    def certify(family: PathFamily, path: GeometricPath) -> str | None:
        return _certify_pick(scene, family, path)

    task = ShapeTask(
        scene, planned, None, family_through, certify, np.pi, span, 0, played
    )
    shaped = optimizer.shape(task, watch)
    if not shaped.improved:
        return ShapedPick(pick, shaped)
    path = shaped.path
    s_top = float(path.knots[len(head) - 1]) if len(head) > 1 else 0.0
    replaced = dataclasses.replace(planned, path=path, polyline=path.waypoints)
    return ShapedPick(
        dataclasses.replace(
            pick,
            path=replaced,
            s_retreat=s_top,
            s_approach=float(path.knots[-len(tail)]),
        ),
        shaped,
    )


def _certify_pick(
    scene: PlanningScene, family: PathFamily, path: GeometricPath
) -> str | None:
    """None if the pick's path stays on its lines and passes the collision check."""
    s_top, s_approach = family.segment_ends(path.knots)
    lines = [(s_approach, 1.0, scene.cup_pose(family.q_place))]
    if len(family.up):
        lines.append((0.0, s_top, scene.cup_pose(family.q_grasp)))
    for line in lines:
        deviation = line_deviation(scene, path, *line)
        if not deviation.ok:
            return (
                f"{1e3 * deviation.offset_m:.2f} mm, "
                f"{np.degrees(deviation.tilt_rad):.2f} deg off a vertical line "
                f"at s = {deviation.s:.3f}"
            )
    check = check_path(scene, path)
    if not check.ok:
        return f"{check.reason} at s = {check.s:.3f}"
    return None


__all__ = ["SEARCH_GRIDPOINTS", "ShapedPick", "shape_pick"]
