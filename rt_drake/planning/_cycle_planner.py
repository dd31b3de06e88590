"""Collision-free paths for the phases of a pick-and-place cycle (paper III-A).

- APPROACH: current q -> cup above the object (grasp pose raised by the
  object's ``approach_offset`` along world z; with ``"auto"``, by the
  shortest line that keeps the cup and the object clear of the cell,
  :meth:`CyclePlanner.line_height`).
- REACH: straight down to the grasp pose X_WC = X_WO X_OC (cup face on the
  object's top face): IK every ``LINE_STEP`` of the descent, each seeded and
  costed by the previous solution; no RRT. The target's grasped face is
  modelled ``TOUCH_ALLOWANCE`` lower, so the cup may touch (and press 2 mm
  into) that face and nothing else of the object.
- PICK (:meth:`CyclePlanner.plan_pick`, :mod:`._pick`): APPROACH and REACH
  blended into one path without a stop at the approach pose, after a
  vertical retreat from an object just placed. The cycle's first pick tries
  the APPROACH as one straight joint-space line first
  (:meth:`CyclePlanner.straight_approach`, :mod:`._straight_approach`).
- MOVE: the object attached to the cup, through four anchors: grasp, lift
  (the grasp raised by ``approach_offset``; the IK line of the REACH passed
  in, reversed, when that REACH came down from there), above the place pose
  (raised likewise, or by half or a quarter of it if that is out of reach),
  place (X_WO_goal X_OC). What a real cell does: lift out of the bin, transfer, set down
  vertically. A lift or above-place pose that is unreachable or colliding
  is skipped. The path's ``lines_m`` gives the heights of the two vertical
  lines it runs (the cycle's floor counts them).

Each phase tries the spline through its anchors first and connects them
(straight edges, IK lines for the vertical moves, RRT-Connect) only if that
spline is not clean (:mod:`._connect`). Grasp yaw: the scenario's X_OC or its
flip by 180 deg about z_C; APPROACH takes whichever IK solution is nearer q,
REACH and MOVE keep the flip the cup has. A call is deterministic for the
planner's seed and raises a :class:`~rt_drake.planning._planning_errors.PlanningError`
naming phase and object within its budget (plus one IK round).
"""

from __future__ import annotations

import dataclasses

import numpy as np
from pydrake.math import RigidTransform

from rt_drake import arguments
from rt_drake.errors import InputError
from rt_drake.model.plant import home_configuration
from rt_drake.model.scenario import Scenario
from rt_drake.planning._connect import (
    PhaseEnds,
    describe,
    ik_line,
    through,
)
from rt_drake.planning._ik import CupIk
from rt_drake.planning._line_heights import LineHeightError, LineProbe
from rt_drake.planning._pick import (
    PlannedPick,
    plan_pick,
    turned_descent,
)
from rt_drake.planning._planner_steps import (
    TOUCH_ALLOWANCE,
    PlannerSteps,
    check_pose,
    pose_key,
)
from rt_drake.planning._planning_errors import (
    GoalInCollisionError,
    PlanningError,
    UnreachablePoseError,
)
from rt_drake.planning._straight_approach import straight_approach
from rt_drake.planning.result import PlannedPath
from rt_drake.planning.scene import PlanningScene
from rt_drake.types.phase import Phase

#: m, how close the cup's origin must be to a grasp pose to be holding it.
GRASP_TOLERANCE_M = 0.002
#: rad, how close the cup's orientation must be to a grasp pose likewise.
GRASP_TOLERANCE_RAD = 0.02
#: s, default time budget of one planning call.
BUDGET_S = 1.0
#: s, the largest budget accepted (a call that finds no path uses it all).
MAX_BUDGET_S = 600.0
#: heights of MOVE's above-place anchor tried, in units of approach_offset.
ABOVE_FRACTIONS = (1.0, 0.5, 0.25)


def _raised(X_WC: RigidTransform, height: float) -> RigidTransform:
    return RigidTransform([0.0, 0.0, height]) @ X_WC


class CyclePlanner(PlannerSteps):
    """Plans APPROACH, REACH and MOVE for a scenario's objects.

    Object poses (``object_poses``, X_WO) start at the scenario's starts;
    after a place, call :meth:`set_object_pose` with the goal. A plan depends
    only on its arguments, the object poses and the seed: nothing carries
    over from one call to the next.
    """

    def __init__(
        self,
        scenario: Scenario,
        seed: int = 0,
        budget_s: float = BUDGET_S,
        scene: PlanningScene | None = None,
    ) -> None:
        arguments.instance(scenario, "scenario", Scenario, where="CyclePlanner")
        if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)):
            raise InputError(f"planner seed must be an integer, got {seed!r}")
        if not (
            isinstance(budget_s, (int, float, np.number))
            and np.isfinite(budget_s)
            and 0.0 < budget_s <= MAX_BUDGET_S
        ):
            raise InputError(
                f"planning budget must be in (0, {MAX_BUDGET_S:g}] s, got {budget_s!r}"
            )
        self.scenario = scenario
        self.seed = seed
        self.budget_s = budget_s
        self.scene = PlanningScene(scenario) if scene is None else scene
        self.ik = CupIk(self.scene.plant, self.scene.cup_frame)
        self.q_home = home_configuration(self.scene.plant, scenario)
        self.object_poses: dict[str, RigidTransform | None] = {
            o.name: o.start.GetDeterministicValue() for o in scenario.objects
        }
        # The scene is loaded with the cell and the objects at their start
        # poses (adding an object's shapes to the checker takes ~3 ms); each
        # plan then re-adds only what its phase changes.
        for obj in scenario.objects:
            X_WO = self.object_poses[obj.name]
            self.scene.set_object(obj.name, X_WO, obj.model, None, TOUCH_ALLOWANCE)
        self._probe: LineProbe | None = None
        self._heights: dict[tuple, float] = {}
        if any(scenario.approach_offset(o.name) is None for o in scenario.objects):
            self._probe = LineProbe(scenario)
            self._nominal_heights()

    def set_object_pose(self, name: str, X_WO: RigidTransform | None) -> None:
        """Move object ``name`` to X_WO (None: the object left the cell)."""
        self.scenario.object(name)
        if X_WO is not None:
            check_pose(X_WO, f"pose of object '{name}'")
        self.object_poses[name] = X_WO

    def line_height(self, name: str, X_WO: RigidTransform, at: Phase) -> float:
        """Length (m) of the vertical line above object ``name`` at X_WO.

        The scenario's ``approach_offset``, or with ``"auto"`` the shortest
        line keeping the cup and the object ``planning.approach_clearance``
        clear of the cell as it is now (:mod:`._line_heights`). ``at``:
        the phase the line belongs to (APPROACH/REACH above the pick, MOVE
        above the place), for messages.
        """
        offset = self.scenario.approach_offset(name)
        if offset is not None:
            return offset
        assert self._probe is not None  # built when any object is "auto"
        X_OC = self.grasps(name)[0]
        others = {k: v for k, v in self.object_poses.items() if k != name}
        key = (name, pose_key(X_WO), *((k, pose_key(v)) for k, v in others.items()))
        if key not in self._heights:
            try:
                self._heights[key] = self._probe.line_height(
                    X_WO @ X_OC,
                    name,
                    X_OC.inverse(),
                    others,
                    self.scenario.planning.approach_clearance,
                )
            except LineHeightError as error:
                raise PlanningError(
                    at, name, f"approach_offset auto: {error}"
                ) from None
        return self._heights[key]

    def _nominal_heights(self) -> None:
        """Compute the lines of the scenario's own cycle before any plan.

        Objects in order, each placed at its goal: no plan of that cycle
        waits for a line height.
        """
        saved = dict(self.object_poses)
        for obj in self.scenario.objects:
            X_start = self.object_poses[obj.name]
            if X_start is not None:
                self.line_height(obj.name, X_start, Phase.APPROACH)
            X_goal = obj.goal.GetDeterministicValue()
            self.line_height(obj.name, X_goal, Phase.MOVE)
            self.object_poses[obj.name] = X_goal
        self.object_poses = saved

    # -- phases -------------------------------------------------------------

    def plan_approach(self, q_current: np.ndarray, name: str) -> PlannedPath:
        """Path from ``q_current`` to the cup above object ``name``."""
        goal = self.approach_goal(q_current, name)
        anchors = [goal.q_start, goal.q_goal]
        return through(self.scene, self.ik, anchors, goal.X_OC, goal.attempt)

    def straight_approach(self, q_current: np.ndarray, name: str) -> PlannedPath | None:
        """The APPROACH as one straight joint-space line, None if it is not clean.

        :mod:`._straight_approach` (no RRT: the caller plans otherwise).
        """
        return straight_approach(self, q_current, name)

    def approach_goal(
        self, q_current: np.ndarray, name: str, prepared: bool = False
    ) -> PhaseEnds:
        """The APPROACH's ends (no path yet): the cup above ``name``, nearest q.

        Leaves the scene prepared for the APPROACH from ``q_current``, or,
        if ``prepared``, checks start and goal in the scene as it is (the
        pick's: :mod:`._pick`).
        """
        attempt = self._begin(Phase.APPROACH, name)
        q_current = self._configuration(attempt, q_current, "q_current")
        if not prepared:
            with attempt.watch("scene"):
                self.prepare(Phase.APPROACH, name, q_current)
        self._check_start(attempt, q_current)
        grasps = self.grasps(name)
        X_WO = self._pose(attempt)
        offset = self.line_height(name, X_WO, Phase.APPROACH)
        targets = [_raised(X_WO @ X_OC, offset) for X_OC in grasps]
        with attempt.watch("ik"):
            index, q_goal = self._solve(attempt, "approach", targets, q_current)
        return PhaseEnds(attempt, q_current, q_goal, grasps[index])

    def plan_reach(
        self, q_approach: np.ndarray, name: str, turn: bool = False
    ) -> PlannedPath:
        """Straight descent from ``q_approach`` to the grasp of ``name``.

        ``turn``: through the blended pick's descent (:func:`._pick.turned_descent`:
        the IK line and a point ``TURN_STEP`` below its top), so that a MOVE
        lifts along the same line as after a blended pick.
        """
        line = self.descent_line(q_approach, name)
        assert line.chain is not None  # descent_line raises otherwise
        chain = line.chain
        if turn:
            with line.attempt.watch("ik"):
                chain = turned_descent(self, chain)
        planned = through(self.scene, self.ik, list(chain), line.X_OC, line.attempt)
        return dataclasses.replace(planned, descent=chain)

    def descent_line(
        self, q_approach: np.ndarray, name: str, prepared: bool = False
    ) -> PhaseEnds:
        """The REACH's IK line from ``q_approach`` down to the grasp (no spline).

        ``chain`` holds the line's configurations (``q_goal`` the last, on
        the grasp, collision-free). Leaves the scene prepared for the REACH
        from ``q_approach``, or, if ``prepared``, checks in the scene as it is.
        """
        attempt = self._begin(Phase.REACH, name)
        q_approach = self._configuration(attempt, q_approach, "q_approach")
        X_start = self.scene.cup_pose(q_approach)
        X_OC = self._nearest_grasp(attempt, X_start)
        if not prepared:
            with attempt.watch("scene"):
                self.prepare(Phase.REACH, name, q_approach, X_OC)
        self._check_start(attempt, q_approach)
        with attempt.watch("ik"):
            line = ik_line(self.ik, q_approach, X_start, self._pose(attempt) @ X_OC)
        chain = line.chain
        if chain is None:
            raise UnreachablePoseError(
                Phase.REACH,
                name,
                f"descent pose {1e3 * line.unreached_m:.0f} mm above the grasp "
                "unreachable from the previous one",
            )
        if not self._valid(chain[-1]):
            raise GoalInCollisionError(
                Phase.REACH, name, describe(self.scene, chain[-1], "goal")
            )
        return PhaseEnds(attempt, q_approach, chain[-1], X_OC, chain)

    def plan_pick(
        self, q_start: np.ndarray, name: str, retreat: bool = False
    ) -> PlannedPick:
        """APPROACH and REACH of ``name`` as one path, after a retreat if asked.

        ``retreat``: the cup rests on a placed object at ``q_start`` and first
        rises vertically off it (:mod:`._pick`).
        """
        return plan_pick(self, q_start, name, retreat)

    def plan_move(
        self,
        q_grasp: np.ndarray,
        name: str,
        X_WO_goal: RigidTransform | None = None,
        reach: PlannedPath | None = None,
    ) -> PlannedPath:
        """Carry ``name`` from the grasp at ``q_grasp`` to X_WO_goal (default: goal).

        Args:
            q_grasp: The configuration holding the object (rad).
            name: The object.
            X_WO_goal: Where to place it (default: the scenario's goal).
            reach: The REACH that ended at ``q_grasp``, if any: the MOVE then
                lifts along its descent, reversed, when that fits.
        """
        attempt = self._begin(Phase.MOVE, name)
        q_grasp = self._configuration(attempt, q_grasp, "q_grasp")
        obj = self.scenario.object(name)
        if X_WO_goal is None:
            X_WO_goal = obj.goal.GetDeterministicValue()
        else:
            check_pose(X_WO_goal, "goal pose X_WO_goal", attempt)
        X_OC = self._nearest_grasp(attempt, self.scene.cup_pose(q_grasp))
        X_grasp = self._pose(attempt) @ X_OC
        error = self.scene.cup_pose(q_grasp).InvertAndCompose(X_grasp)
        distance = np.linalg.norm(error.translation())
        angle = error.rotation().ToAngleAxis().angle()
        if distance > GRASP_TOLERANCE_M or angle > GRASP_TOLERANCE_RAD:
            raise PlanningError(
                Phase.MOVE,
                name,
                f"start configuration does not hold the object (cup "
                f"{1e3 * distance:.1f} mm, {np.degrees(angle):.1f} deg from its grasp)",
            )
        with attempt.watch("scene"):
            self.prepare(Phase.MOVE, name, q_grasp, X_OC)
        self._check_start(attempt, q_grasp)
        X_place = X_WO_goal @ X_OC
        lift_height = self.line_height(name, self._pose(attempt), Phase.MOVE)
        place_height = self.line_height(name, X_WO_goal, Phase.MOVE)
        # An "auto" line is already the shortest that keeps the clearance.
        fractions = ABOVE_FRACTIONS if self.scenario.approach_offset(name) else (1.0,)
        X_lift = _raised(X_grasp, lift_height)
        with attempt.watch("ik"):
            lift = self._reversed_reach(reach, name, q_grasp, X_lift)
            q_lift = self._optional(X_lift, q_grasp) if lift is None else lift[-1]
            for fraction in fractions:  # lower if the full height is out of reach
                X_above = _raised(X_place, fraction * place_height)
                q_above = self._optional(X_above, q_grasp if q_lift is None else q_lift)
                if q_above is not None:
                    break
            near = q_grasp if q_above is None else q_above
            _, q_place = self._solve(attempt, "place", [X_place], near)
        anchors = [q_grasp]
        lines: list[tuple[RigidTransform, RigidTransform] | None] = []
        if lift is not None:  # REACH's IK line, reversed: already straight
            anchors += list(lift[1:])
            lines += [None] * (len(lift) - 1)
        elif q_lift is not None:
            anchors.append(q_lift)
            lines.append((X_grasp, X_lift))
        if q_above is not None:
            anchors.append(q_above)
            lines.append(None)
        anchors.append(q_place)
        lines.append((X_above, X_place) if q_above is not None else None)
        planned = through(self.scene, self.ik, anchors, X_OC, attempt, lines)
        heights = (
            0.0 if lift is None and q_lift is None else lift_height,
            0.0 if q_above is None else fraction * place_height,
        )
        return dataclasses.replace(planned, lines_m=heights)

    def plan_between(
        self,
        q_start: np.ndarray,
        q_goal: np.ndarray,
        name: str,
        X_OC: RigidTransform | None = None,
    ) -> PlannedPath:
        """Spline, or RRT-Connect + shortcut + spline, between two configurations.

        With ``X_OC``, object ``name`` is carried (cup at X_OC in O): a MOVE;
        without, it stays in the environment at its current pose: an
        APPROACH.
        """
        phase = Phase.APPROACH if X_OC is None else Phase.MOVE
        attempt = self._begin(phase, name)
        q_start = self._configuration(attempt, q_start, "q_start")
        q_goal = self._configuration(attempt, q_goal, "q_goal")
        if X_OC is not None:
            check_pose(X_OC, "grasp X_OC", attempt)
        with attempt.watch("scene"):
            self.prepare(phase, name, q_start, X_OC)
        self._check_start(attempt, q_start)
        if not self._valid(q_goal):
            raise GoalInCollisionError(
                phase, name, describe(self.scene, q_goal, "goal")
            )
        if X_OC is None:
            X_OC = self.grasps(name)[0]
        return through(self.scene, self.ik, [q_start, q_goal], X_OC, attempt)

    def configuration_for(
        self,
        X_WC: RigidTransform,
        q_near: np.ndarray,
        name: str = "",
        phase: Phase = Phase.MOVE,
    ) -> np.ndarray:
        """Collision-free q with the cup at X_WC, nearest ``q_near``.

        Uses the scene as last prepared; ``phase`` and ``name`` label errors.
        Raises UnreachablePoseError or GoalInCollisionError.
        """
        attempt = self._begin(phase, name, check=False)
        q_near = self._configuration(attempt, q_near, "q_near")
        check_pose(X_WC, "cup pose X_WC", attempt)
        return self._solve(attempt, "cup", [X_WC], q_near)[1]

    def _reversed_reach(
        self,
        reach: PlannedPath | None,
        name: str,
        q_grasp: np.ndarray,
        X_lift: RigidTransform,
    ) -> np.ndarray | None:
        """The REACH's IK line reversed (grasp -> lift), if it fits this MOVE.

        It does if that REACH was for ``name``, ended at q_grasp, came down
        from X_lift and its start is valid with the load attached.
        """
        if reach is None or reach.descent is None or reach.object != name:
            return None
        chain = reach.descent[::-1]
        if not np.allclose(chain[0], q_grasp, rtol=0.0, atol=1e-12):
            return None
        error = self.scene.cup_pose(chain[-1]).InvertAndCompose(X_lift)
        if np.linalg.norm(error.translation()) > 1e-5 or not self._valid(chain[-1]):
            return None
        return chain


__all__ = [
    "BUDGET_S",
    "MAX_BUDGET_S",
    "CyclePlanner",
    "GRASP_TOLERANCE_M",
    "GRASP_TOLERANCE_RAD",
    "PhaseEnds",
    "TOUCH_ALLOWANCE",
]
