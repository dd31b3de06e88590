"""Vertical line heights from the cell's geometry (``approach_offset: auto``).

Above a pick and a place the cup moves along a vertical line. With ``auto``
that line is the shortest one whose top keeps the cup (the tool body, its
rim included) and the held object clear of everything else in the cell (bin
walls, the neighbouring objects, the stack) by ``approach_clearance``:

    h* = min { h in {0, dh, 2 dh, ...} : d(h) >= clearance },   dh = 1 mm,

where d(h) is the smallest signed distance (m; negative in penetration)
between {tool, held object}, rigidly posed with the cup frame at
``X_WC_end`` raised by h along world z, and every other collision geometry
of the cell and the objects at their current poses. The arm's links are left
out: they follow from inverse kinematics, which the planner checks anyway.
Every height below h* on the grid is closer than the clearance, so a line
1 cm shorter breaks it. The search steps up the grid, skipping the heights
that the 1-Lipschitz bound |d(h') - d(h)| <= |h' - h| already rules out.

The distances come from a separate MultibodyPlant (:class:`LineProbe`): the
cell and the objects as in the scenario, plus a free "probe" body carrying
copies of the tool body's collision shapes (poses in the tool body frame),
and the held object's own free body placed at X_WO = X_WC X_CO. Objects not
in the cell are parked far below it. Drake's
``ComputeSignedDistancePairwiseClosestPoints`` does the geometry.
"""

from __future__ import annotations

import numpy as np
from pydrake.geometry import ProximityProperties, SceneGraph
from pydrake.math import RigidTransform
from pydrake.multibody.plant import AddMultibodyPlantSceneGraph, MultibodyPlant
from pydrake.multibody.tree import Body, SpatialInertia
from pydrake.systems.framework import DiagramBuilder

from rt_drake.errors import RtDrakeError
from rt_drake.model.object_model import OBJECT_BODY
from rt_drake.model.plant import ObjectMode, add_scenario_models, scenario_cup_frame
from rt_drake.model.scenario import Scenario

#: m, the grid step of the line height.
HEIGHT_STEP = 0.001
#: m, the highest line searched.
MAX_HEIGHT = 0.5
#: m, where objects not in the cell are parked (world z).
_PARKED_Z = -50.0


class LineHeightError(RtDrakeError):
    """No height up to ``MAX_HEIGHT`` clears the cell.

    The planner raises it again as a PlanningError naming phase and object.
    """


class LineProbe:
    """Signed distances of the tool and a held object posed along a line.

    Built once per scenario (about 0.1 s); each distance query a fraction
    of a millisecond.
    """

    def __init__(self, scenario: Scenario) -> None:
        builder = DiagramBuilder()
        plant, scene_graph = AddMultibodyPlantSceneGraph(builder, time_step=0.0)
        models = add_scenario_models(plant, scenario, ObjectMode.FREE)
        cup_frame = scenario_cup_frame(plant, scenario)
        tool = cup_frame.body()
        self._X_TC = cup_frame.GetFixedPoseInBodyFrame()
        self._probe = plant.AddRigidBody(
            "line_probe",
            plant.AddModelInstance("line_probe"),
            SpatialInertia.SolidSphereWithMass(1.0, 0.01),
        )
        inspector = scene_graph.model_inspector()
        for index, geometry in enumerate(plant.GetCollisionGeometriesForBody(tool)):
            properties = inspector.GetProximityProperties(geometry)
            plant.RegisterCollisionGeometry(
                self._probe,
                inspector.GetPoseInFrame(geometry),
                inspector.GetShape(geometry).Clone(),
                f"probe_{index}",
                ProximityProperties(properties)
                if properties is not None
                else ProximityProperties(),
            )
        plant.Finalize()
        self._diagram = builder.Build()
        self._context = self._diagram.CreateDefaultContext()
        self._plant: MultibodyPlant = plant
        self._scene_graph: SceneGraph = scene_graph
        self._plant_context = plant.GetMyMutableContextFromRoot(self._context)
        self._objects: dict[str, Body] = {
            name: plant.GetBodyByName(OBJECT_BODY, instance)
            for name, instance in models.objects.items()
        }
        arm = {models.robot, models.tool}
        self._ignored = {
            plant.GetBodyFrameIdOrThrow(plant.get_body(b).index())
            for instance in arm
            for b in plant.GetBodyIndices(instance)
        }
        self._probe_frame = plant.GetBodyFrameIdOrThrow(self._probe.index())

    def distance(
        self,
        X_WC: RigidTransform,
        held: str | None,
        X_CO: RigidTransform | None,
        others: dict[str, RigidTransform | None],
        horizon: float,
    ) -> float:
        """d: smallest signed distance (m) of tool + held object to the rest.

        Args:
            X_WC: pose of the cup frame C in the world.
            held: the object carried, or None.
            X_CO: pose of the held object's body in C.
            others: X_WO of every other object (None: not in the cell).
            horizon: m; pairs farther apart than this are not computed, and
                ``horizon`` is returned when every pair is.
        """
        plant, context = self._plant, self._plant_context
        plant.SetFreeBodyPose(context, self._probe, X_WC @ self._X_TC.inverse())
        moving = {self._probe_frame}
        for index, (name, body) in enumerate(self._objects.items()):
            if name == held:
                assert X_CO is not None
                X_WO = X_WC @ X_CO
                moving.add(plant.GetBodyFrameIdOrThrow(body.index()))
            else:
                X_WO = others.get(name)
            if X_WO is None:  # parked apart from each other, far below the cell
                X_WO = RigidTransform([10.0 * index, 0.0, _PARKED_Z])
            plant.SetFreeBodyPose(context, body, X_WO)
        query = self._scene_graph.get_query_output_port().Eval(
            self._scene_graph.GetMyContextFromRoot(self._context)
        )
        inspector = query.inspector()
        nearest = horizon
        for pair in query.ComputeSignedDistancePairwiseClosestPoints(horizon):
            frames = (inspector.GetFrameId(pair.id_A), inspector.GetFrameId(pair.id_B))
            inside = [frame in moving for frame in frames]
            if inside[0] == inside[1]:  # both moving (rigid together) or neither
                continue
            if any(frame in self._ignored for frame in frames):
                continue
            nearest = min(nearest, float(pair.distance))
        return nearest

    def line_height(
        self,
        X_WC_end: RigidTransform,
        held: str | None,
        X_CO: RigidTransform | None,
        others: dict[str, RigidTransform | None],
        clearance: float,
    ) -> float:
        """h*, the shortest line (m, on the 1 mm grid) clear by ``clearance``.

        Raises:
            LineHeightError: no height up to ``MAX_HEIGHT`` is clear.
        """
        steps = int(round(MAX_HEIGHT / HEIGHT_STEP))
        horizon = clearance + HEIGHT_STEP
        k = 0
        while k <= steps:
            h = k * HEIGHT_STEP
            X_WC = RigidTransform([0.0, 0.0, h]) @ X_WC_end
            d = self.distance(X_WC, held, X_CO, others, horizon)
            if d >= clearance:
                return h
            # d is 1-Lipschitz in h (a rigid translation by dh changes every
            # distance by at most |dh|): every height closer than
            # clearance - d above h fails too.
            k += max(1, int(np.ceil((clearance - d) / HEIGHT_STEP - 1e-9)))
        raise LineHeightError(
            f"no vertical line up to {MAX_HEIGHT} m keeps the cup and "
            f"{held or 'nothing'} {clearance} m clear of the cell"
        )


__all__ = ["HEIGHT_STEP", "LineHeightError", "LineProbe", "MAX_HEIGHT"]
