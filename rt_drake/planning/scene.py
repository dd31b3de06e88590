"""The planner's collision world: one checker per scenario, updated per query.

:class:`PlanningScene` builds, once, a ``RobotDiagram`` of the scenario's
cell, robot and tool (no objects) and a ``SceneGraphCollisionChecker`` whose
robot is the arm plus the tool. Objects never enter the plant: they are
shapes added to the checker (``AddCollisionShapeToFrame``), so moving one is
a remove-and-add (about 2 ms a shape here; an unchanged object is skipped),
not a rebuild (about 0.4 s):

- a resting object is environment, its shapes attached to the world frame
  at its current pose X_WO (group ``object:<name>``);
- the carried object is part of the robot, its shapes attached to the cup
  frame C at X_CO (group ``held``). Same body as the cup and rim, so the
  checker never tests the load against the tool that holds it.

Contact the cycle needs is allowed by an explicit allowance, nothing else:
:meth:`PlanningScene.set_object` can move the face the cup grasps inward by
``allowance`` (m), so a cup resting on that face (end of REACH, start of the
APPROACH after a place) is not a collision while every other part of the
object still is. Padding is zero: the scenarios leave 0.5 mm gaps.

Configurations q are the plant's positions: the robot's joint angles (rad).
"""

from __future__ import annotations

import numpy as np
from pydrake.geometry import Shape
from pydrake.math import RigidTransform
from pydrake.planning import (
    LinearDistanceAndInterpolationProvider,
    RobotClearance,
    RobotDiagramBuilder,
    SceneGraphCollisionChecker,
)

from rt_drake.errors import ScenarioError
from rt_drake.model.plant import (
    ObjectMode,
    add_scenario_models,
    scenario_cup_frame,
)
from rt_drake.model.scenario import Scenario
from rt_drake.planning._bounds import MotionBounds
from rt_drake.planning._geometry import (
    PosedShape,
    bounding_radius,
    object_geometries,
    shrink_face,
)

#: Edge step of the checker's straight-line checks, in the weighted metric
#: ``||R_max * dq||_2`` (m; ``R_max[j]`` the largest lever arm of joint j,
#: :class:`~rt_drake.planning._bounds.MotionBounds`, with the scenario's
#: largest load), about how far the farthest robot point moves per check.
EDGE_STEP = 0.02


class PlanningScene:
    """Cell + robot + tool in a collision checker, objects as added shapes.

    Attributes:
        scenario: the scenario the scene was built from.
        plant: the checker's plant (positions = robot joint angles, rad).
        checker: the ``SceneGraphCollisionChecker``.
        cup_frame: the frame C of the cup.
        lower, upper: joint limits (rad).
        bounds: lever arms and radii of the robot's bodies, for the current load.
        held: name of the carried object, or None.
    """

    def __init__(self, scenario: Scenario, edge_step: float = EDGE_STEP) -> None:
        builder = RobotDiagramBuilder(time_step=0.0)
        plant = builder.plant()
        models = add_scenario_models(plant, scenario, ObjectMode.NONE)
        plant.Finalize()
        diagram = builder.Build()
        if plant.num_positions() != plant.num_positions(models.robot):
            raise ScenarioError(
                f"the planner needs every joint to be the robot's: "
                f"{plant.num_positions()=} but {plant.num_positions(models.robot)=}"
            )
        self.scenario = scenario
        self.plant = plant
        self.cup_frame = scenario_cup_frame(plant, scenario)
        self.lower = plant.GetPositionLowerLimits()
        self.upper = plant.GetPositionUpperLimits()
        self._query_port = diagram.scene_graph().get_query_output_port()
        self.bounds = MotionBounds(
            plant,
            diagram.scene_graph(),
            [models.robot, models.tool],
            self.cup_frame.body().index(),
        )
        # Edge metric weights: the largest lever arms with the largest load.
        self.bounds.set_load(
            max(
                (
                    self._load_radius(
                        o.model, o.grasp.GetDeterministicValue().inverse()
                    )
                    for o in scenario.objects
                ),
                default=0.0,
            )
        )
        provider = LinearDistanceAndInterpolationProvider(
            plant, self.bounds.radii.max(axis=1)
        )
        self.bounds.set_load(0.0)
        self.checker = SceneGraphCollisionChecker(
            model=diagram,
            robot_model_instances=[models.robot, models.tool],
            distance_and_interpolation_provider=provider,
            edge_step_size=edge_step,
            env_collision_padding=0.0,
            self_collision_padding=0.0,
        )
        self.bounds.set_self_pairs(self.checker.IsCollisionFilteredBetween)
        self._fk_context = plant.CreateDefaultContext()  # cup_poses' scratch
        self._labels: dict = {}  # GeometryId of an added shape -> label
        self._groups: dict[str, object] = {}  # group -> key of what it holds
        self.held: str | None = None

    # -- objects -------------------------------------------------------------

    def set_object(
        self,
        name: str,
        X_WO: RigidTransform | None,
        model: str | None = None,
        allowance_normal_O: np.ndarray | None = None,
        allowance: float = 0.0,
    ) -> None:
        """Put object ``name`` (model URL) in the environment at X_WO, or remove it.

        Args:
            name: object name (its group is ``object:<name>``).
            X_WO: pose of the object frame O in W; None removes the object.
            model: the object's model; defaults to the scenario's.
            allowance_normal_O: outward normal (in O) of the face the cup may
                touch; that box face is moved inward by ``allowance`` (m).
            allowance: m, see above.
        """
        group = f"object:{name}"
        model = model or self.scenario.object(name).model
        key = None
        if X_WO is not None:
            normal = None if allowance_normal_O is None else tuple(allowance_normal_O)
            key = (model, X_WO.GetAsMatrix34().tobytes(), normal, allowance)
        if self._groups.get(group) == key:
            return
        self.checker.RemoveAllAddedCollisionShapes(group)
        self._groups[group] = key
        if X_WO is None:
            return
        shapes = list(object_geometries(model))
        if allowance_normal_O is not None:
            shapes = [shrink_face(p, allowance_normal_O, allowance) for p in shapes]
        self._add(group, name, self.plant.world_frame(), shapes, X_WO)

    def attach(self, name: str, X_CO: RigidTransform, model: str | None = None) -> None:
        """Carry object ``name``: its shapes ride on the cup frame at X_CO."""
        model = model or self.scenario.object(name).model
        key = (model, X_CO.GetAsMatrix34().tobytes())
        if self._groups.get("held") == key:
            return
        self.detach()
        self._groups["held"] = key
        self._add(
            "held", f"{name} (held)", self.cup_frame, object_geometries(model), X_CO
        )
        self.held = name
        self.bounds.set_load(self._load_radius(model, X_CO))

    def detach(self) -> None:
        """Drop the carried object's shapes (if any)."""
        if self._groups.get("held") is not None:
            self.checker.RemoveAllAddedCollisionShapes("held")
            self._groups["held"] = None
            self.bounds.set_load(0.0)
        self.held = None

    def add_obstacle(self, name: str, shape: Shape, X_WG: RigidTransform) -> None:
        """Add a static obstacle G at X_WG (group ``obstacle:<name>``)."""
        self._add(
            f"obstacle:{name}",
            name,
            self.plant.world_frame(),
            [PosedShape(shape, RigidTransform())],
            X_WG,
        )
        self._groups[f"obstacle:{name}"] = "added"

    def remove_obstacle(self, name: str) -> None:
        """Remove the obstacles added as ``name``."""
        self.checker.RemoveAllAddedCollisionShapes(f"obstacle:{name}")
        self._groups.pop(f"obstacle:{name}", None)

    # -- queries -------------------------------------------------------------

    def is_free(self, q: np.ndarray) -> bool:
        """True if q has no collision (robot, load, environment)."""
        return self.checker.CheckConfigCollisionFree(q)

    def edge_free(self, q_a: np.ndarray, q_b: np.ndarray) -> bool:
        """True if the straight joint-space segment q_a -> q_b is collision-free.

        Checked at the edge step (``EDGE_STEP`` of the weighted metric).
        """
        return self.checker.CheckEdgeCollisionFree(q_a, q_b)

    def within_limits(self, q: np.ndarray, tolerance: float = 1e-9) -> bool:
        """True if q is inside the joint limits (rad)."""
        return bool(
            np.all(q >= self.lower - tolerance) and np.all(q <= self.upper + tolerance)
        )

    def clearance(self, q: np.ndarray, influence: float) -> RobotClearance:
        """Signed distances (m) of every unfiltered pair closer than ``influence``."""
        return self.checker.CalcRobotClearance(q, influence)

    def cup_pose(self, q: np.ndarray) -> RigidTransform:
        """X_WC, pose of the cup frame at q."""
        context = self.checker.UpdatePositions(q)
        return self.plant.CalcRelativeTransform(
            context, self.plant.world_frame(), self.cup_frame
        )

    def cup_poses(self, q: np.ndarray) -> list[RigidTransform]:
        """X_WC at each row of q (N, n): forward kinematics only, no geometry."""
        world = self.plant.world_frame()
        poses = []
        for row in np.atleast_2d(q):
            self.plant.SetPositions(self._fk_context, row)
            poses.append(
                self.plant.CalcRelativeTransform(
                    self._fk_context, world, self.cup_frame
                )
            )
        return poses

    def cup_frames(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """R_WC (N, 3, 3) and p_WC (N, 3) (m) at each row of q (N, n), vectorised.

        The cup's body pose from
        :class:`~rt_drake.dynamics.body_kinematics.BodyKinematics`, times the cup
        frame's fixed pose in that body: :meth:`cup_poses` as arrays.
        """
        column = self.bounds.column_lookup[int(self.cup_frame.body().index())]
        R, p = self.bounds.kinematics.poses(q)
        R_WB = np.moveaxis(R[column], -1, 0)  # (N, 3, 3)
        p_WB = p[column].T  # (N, 3)
        X_BC = self.cup_frame.GetFixedPoseInBodyFrame()
        R_WC = R_WB @ X_BC.rotation().matrix()
        p_WC = p_WB + R_WB @ X_BC.translation()
        return R_WC, p_WC

    def collisions(self, q: np.ndarray) -> list[str]:
        """Name the colliding pairs at q: ``"vs060::link3 with cell::top_plate"``."""
        self.checker.UpdatePositions(q)
        query = self._query_port.Eval(
            self.checker.model_context().scene_graph_context()
        )
        inspector = query.inspector()
        found: list[str] = []
        for pair in query.ComputeSignedDistancePairwiseClosestPoints(0.0):
            if pair.distance > 0.0:
                continue
            body_a = self.plant.GetBodyFromFrameId(inspector.GetFrameId(pair.id_A))
            body_b = self.plant.GetBodyFromFrameId(inspector.GetFrameId(pair.id_B))
            robot_a = self.checker.IsPartOfRobot(body_a)
            if not (robot_a or self.checker.IsPartOfRobot(body_b)):
                continue
            if self.checker.IsCollisionFilteredBetween(body_a, body_b):
                continue
            a = self._label(inspector, pair.id_A, body_a)
            b = self._label(inspector, pair.id_B, body_b)
            text = f"{a} with {b}" if robot_a else f"{b} with {a}"
            if text not in found:
                found.append(text)
        return found

    # -- internals -----------------------------------------------------------

    def _add(self, group, label, frame, shapes, X_FO: RigidTransform) -> None:
        inspector = self._inspector()
        before = set(inspector.GetAllGeometryIds())
        for posed in shapes:
            self.checker.AddCollisionShapeToFrame(
                group, frame, posed.shape, X_FO @ posed.X_FG
            )
        inspector = self._inspector()
        for geometry in set(inspector.GetAllGeometryIds()) - before:
            self._labels[geometry] = label

    def _inspector(self):
        context = self.checker.model_context().scene_graph_context()
        return self._query_port.Eval(context).inspector()

    def _label(self, inspector, geometry, body) -> str:
        if geometry in self._labels:
            return self._labels[geometry]
        if self.checker.IsPartOfRobot(body):
            model = self.plant.GetModelInstanceName(body.model_instance())
            return f"{model}::{body.name()}"
        return inspector.GetName(geometry)

    def _load_radius(self, model: str, X_CO: RigidTransform) -> float:
        """Bounding radius (m) of a load at X_CO about the tool body's origin."""
        X_TC = self.cup_frame.GetFixedPoseInBodyFrame()
        return max(
            float(np.linalg.norm((X_TC @ X_CO @ p.X_FG).translation()))
            + bounding_radius(p.shape)
            for p in object_geometries(model)
        )


__all__ = ["EDGE_STEP", "PlanningScene"]
