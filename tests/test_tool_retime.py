"""Retiming under a two-cup tool's wrench sets, checked independently.

The tool frame T is the plant's ``suction_cup`` frame; the two cups sit
0.12 m apart on T's x axis. A coarse cup model (4 rim points, 3-sided
friction polygons) keeps the exact sets small: 100 rows for one cup, 4266
for the tool (about a second). The reference is an LP written apart
(``tests/tool_reference.py``), over every rim force of every cup as a convex
combination of its friction pyramid's vertices (not the H-form of
``rt_drake.contact._lp``), applied to the object wrenches of the retimed
motion computed by Newton-Euler from the bodies' accelerations
(:mod:`rt_drake.dynamics.newton_euler`). ``for_tool``'s default set (the rims as
equal springs, ``load_sharing="elastic"``) is checked by
``rt_drake.contact.shared_load_residual``, an LP that ties each normal force
to a rigid displacement instead of using the set's rows; the tests of the
free split (``load_sharing="any"``, the exact Minkowski sum) ask for it.
"""

from __future__ import annotations

import numpy as np
import pytest
from pydrake.multibody.plant import MultibodyPlant
from tool_reference import residual as _residual

from rt_drake import (
    CupFrame,
    CupMount,
    CupParameters,
    GraspConstraint,
    HeldObject,
    JointLimits,
    ToolParameters,
    check_trajectory,
    retime,
)
from rt_drake.contact import (
    CupStiffness,
    lp_residual,
    shared_load_residual,
    stiffness_shared_set,
    stiffness_split,
)
from rt_drake.dynamics.newton_euler import reference_object_wrench
from rt_drake.model.parser import make_parser
from rt_drake.retiming import GraspUnstableAtRestError, RetimeInputError

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


@pytest.fixture(scope="module")
def arm() -> MultibodyPlant:
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


def _box(mass: float, p_TScm: list[float]) -> HeldObject:
    """A 0.2 x 0.1 x 0.06 m box of ``mass`` kg, its centre at ``p_TScm``."""
    a, b, c = 0.2, 0.1, 0.06
    inertia = mass / 12.0 * np.diag([b * b + c * c, a * a + c * c, a * a + b * b])
    return HeldObject(mass, np.array(p_TScm), inertia)


ONE = [(CUP, np.zeros(3))]
TWO = [(CUP, np.array([0.06, 0.0, 0.0])), (CUP, np.array([-0.06, 0.0, 0.0]))]
#: The two cups as bellows (the catalogue's stiffness, models/cups/).
BELLOWS_CUPS = ToolParameters(
    cups=[
        CupMount(m.cup, m.R_TC, m.p_TC, CupStiffness(700.0, 1000.0, 2.0, 1.0))
        for m in TWO_CUPS.cups
    ]
)


def _object_wrenches(plant, result, held, count=60):
    trajectory = result.trajectory
    times = np.linspace(0.0, result.duration, count)
    q = np.array([trajectory.value(t).ravel() for t in times])
    v = np.array([trajectory.EvalDerivative(t, 1).ravel() for t in times])
    vdot = np.array([trajectory.EvalDerivative(t, 2).ravel() for t in times])
    return reference_object_wrench(plant, held, CupFrame.of(plant), q, v, vdot)


@pytest.fixture(scope="module")
def limits(arm):
    return JointLimits.from_plant(arm)


def test_the_reference_lp_agrees_with_the_exact_tool_set_at_rest():
    """Static carton wrenches: inside W_T iff the reference LP says so."""
    exact = GraspConstraint.for_tool(
        _box(1.0, [0, 0, 0.03]), TWO_CUPS, load_sharing="any"
    )
    rng = np.random.default_rng(3)
    wrenches = []
    for _ in range(40):
        mass, x = rng.uniform(0.5, 6.0), rng.uniform(-0.1, 0.1)
        weight = np.array([0.0, 0.0, mass * 9.81])  # gravity along +z_T
        p = np.array([x, rng.uniform(-0.02, 0.02), 0.03])
        wrenches.append(np.concatenate([-np.cross(p, weight), -weight]))
    wrenches = np.array(wrenches)
    distance = (wrenches @ exact.F.T - exact.g).max(axis=1)
    residual = _residual(wrenches, TWO)
    clear = np.abs(distance) > 1e-6
    assert np.all((distance[clear] <= 0) == (residual[clear] <= 1e-9))
    assert 5 < np.sum(distance < 0) < 35  # both kinds were drawn


def test_two_cups_hold_a_box_one_cup_cannot_hold_at_rest(arm, limits):
    held = _box(2.5, [0.0, 0.0, 0.03])  # 24.5 N: more than one cup's 20 N
    with pytest.raises(GraspUnstableAtRestError):
        retime(arm, SWING, limits, GraspConstraint.for_cup(held, CUP))
    grasp = GraspConstraint.for_tool(held, TWO_CUPS)
    result = retime(arm, SWING, limits, grasp)
    check = check_trajectory(arm, result.trajectory, limits, grasp)
    assert check.min_margin() >= -1e-3, check.summary()
    wrenches = _object_wrenches(arm, result, held)
    assert _residual(wrenches, TWO).max() <= 1e-3
    assert _residual(wrenches, ONE).min() > 1.0  # one cup: N short everywhere


def test_two_cups_move_an_offset_box_faster_than_one(arm, limits):
    held = _box(0.8, [0.01, 0.0, 0.03])
    one = retime(arm, SWING, limits, GraspConstraint.for_cup(held, CUP))
    grasp = GraspConstraint.for_tool(held, TWO_CUPS)
    two = retime(arm, SWING, limits, grasp)
    assert two.duration < 0.9 * one.duration
    for result, cups in ((one, ONE), (two, TWO)):
        wrenches = _object_wrenches(arm, result, held)
        assert _residual(wrenches, cups).max() <= 1e-3
    # The two-cup motion is too fast for one cup somewhere.
    assert _residual(_object_wrenches(arm, two, held), ONE).max() > 1e-2


@pytest.mark.slow
def test_an_inner_approximation_is_sound_and_no_faster_than_the_exact_set(arm, limits):
    held = _box(2.5, [0.0, 0.0, 0.03])
    exact = retime(
        arm, SWING, limits, GraspConstraint.for_tool(held, TWO_CUPS, load_sharing="any")
    )
    samples = _object_wrenches(arm, exact, held, count=200)
    inner = GraspConstraint.inner_for_tool(held, TWO_CUPS, samples, max_vertices=60)
    result = retime(arm, SWING, limits, inner)
    assert result.duration >= exact.duration - 1e-6
    wrenches = _object_wrenches(arm, result, held)
    assert _residual(wrenches, TWO).max() <= 1e-3


def test_the_spring_split_retime_holds_by_an_independent_lp(arm, limits):
    """Default set: the motion's Newton-Euler wrenches pass the spring LP."""
    held = _box(2.5, [0.01, 0.0, 0.03])
    elastic = retime(arm, SWING, limits, GraspConstraint.for_tool(held, TWO_CUPS))
    wrenches = _object_wrenches(arm, elastic, held, count=80)
    assert shared_load_residual(wrenches, TWO_CUPS).max() <= 1e-3
    free = retime(
        arm, SWING, limits, GraspConstraint.for_tool(held, TWO_CUPS, load_sharing="any")
    )
    assert elastic.duration >= free.duration - 1e-9  # springs: a subset
    # The free split's motion asks the springs for more than they hold.
    wrenches = _object_wrenches(arm, free, held, count=200)
    assert shared_load_residual(wrenches, TWO_CUPS).max() > 1e-2


def test_the_stiffness_split_retime_holds_every_cups_share_by_its_lp(arm, limits):
    """Each cup's share of the motion's wrenches lies in its own rim set (LP)."""
    held = _box(2.5, [0.01, 0.0, 0.03])
    grasp = GraspConstraint.for_tool(held, BELLOWS_CUPS, load_sharing="stiffness")
    result = retime(arm, SWING, limits, grasp)
    wrenches = _object_wrenches(arm, result, held, count=60)
    shares = np.einsum("cij,nj->nci", stiffness_split(BELLOWS_CUPS), wrenches)
    for i, mount in enumerate(BELLOWS_CUPS.cups):
        assert lp_residual(shares[:, i], mount.cup).max() <= 1e-3, i
    np.testing.assert_allclose(grasp.F, stiffness_shared_set(BELLOWS_CUPS).F)
    # The rims' spring set lets friction come from both cups: faster, and a
    # cup's own share then leaves its set.
    elastic = retime(arm, SWING, limits, GraspConstraint.for_tool(held, BELLOWS_CUPS))
    assert elastic.duration < result.duration
    wrenches = _object_wrenches(arm, elastic, held, count=60)
    shares = np.einsum("cij,nj->nci", stiffness_split(BELLOWS_CUPS), wrenches)
    assert lp_residual(shares[:, 0], BELLOWS_CUPS.cups[0].cup).max() > 1e-2


def test_a_bad_load_sharing_is_refused():
    with pytest.raises(RetimeInputError, match="load_sharing must be one of"):
        GraspConstraint.for_tool(_box(1.0, [0, 0, 0.03]), TWO_CUPS, load_sharing="x")


def test_a_tool_grasp_is_described_and_a_cup_is_not_a_tool():
    grasp = GraspConstraint.for_tool(_box(2.5, [0, 0, 0.03]), TWO_CUPS)
    assert grasp.describe() == "object 2.5 kg, 2 cups, suction 20 + 20 N"
    with pytest.raises(RetimeInputError, match="needs a ToolParameters"):
        GraspConstraint.for_tool(_box(1.0, [0, 0, 0.03]), CUP)  # type: ignore[arg-type]


TOOL_SCENARIO = """
directives: []
robot: {home: [0, 0, 0, 0, 0, 0]}
tool:
  cups:
    - pose: {translation: [0.06, 0, 0]}
      suction_force: 25.0
    - pose: {translation: [-0.06, 0, 0], rotation: !Rpy {deg: [0, 0, 90]}}
objects:
  - name: box
    model: package://rt_drake/objects/notebook.sdf
"""


def _write(tmp_path, text):
    path = tmp_path / "tool.yaml"
    path.write_text(text)
    return path


def test_a_scenario_tool_gives_its_cups_and_poses(tmp_path):
    from rt_drake import load_scenario

    scenario = load_scenario(_write(tmp_path, TOOL_SCENARIO))
    tool = scenario.tool_parameters()
    assert [m.cup.suction_force for m in tool.cups] == [25.0, 20.0]
    np.testing.assert_allclose(tool.cups[1].p_TC, [-0.06, 0.0, 0.0])
    np.testing.assert_allclose(tool.cups[1].R_TC @ [1, 0, 0], [0, 1, 0], atol=1e-12)
    text = TOOL_SCENARIO.split("tool:")[0] + "objects:"
    single = load_scenario(_write(tmp_path, text + TOOL_SCENARIO.split("objects:")[1]))
    assert len(single.tool_parameters().cups) == 1


STIFFNESS = "\n      stiffness: {axial: 700, lateral: 1000, tilt: 2, torsion: 1}"
STIFF_SCENARIO = (
    TOOL_SCENARIO.replace("tool:\n", "tool:\n  load_sharing: stiffness\n")
    .replace("suction_force: 25.0", "suction_force: 25.0" + STIFFNESS)
    .replace("deg: [0, 0, 90]}}", "deg: [0, 0, 90]}}" + STIFFNESS)
)


def test_a_scenario_tool_states_its_cups_stiffness(tmp_path):
    from rt_drake import load_scenario

    tool = load_scenario(_write(tmp_path, STIFF_SCENARIO)).tool_parameters()
    assert [m.stiffness for m in tool.cups] == [CupStiffness(700, 1000, 2, 1)] * 2


def test_the_shipped_stiffness_scenario_states_its_catalogue_cups_values():
    from rt_drake import load_scenario, scenarios_dir
    from rt_drake.model.cup_physics import load_bellows_cup

    scenario = load_scenario(
        scenarios_dir() / "carton_two_cups_bellows_20n_stiffness.yaml"
    )
    assert scenario.tool.load_sharing == "stiffness"
    bellows = load_bellows_cup(scenario.cup_physics.cup)
    catalogue = CupStiffness(
        axial=bellows.axial_stiffness,
        lateral=bellows.lateral_stiffness,
        tilt=bellows.tilt_stiffness,
        torsion=bellows.torsion_stiffness,
    )
    tool = scenario.tool_parameters()
    assert [m.stiffness for m in tool.cups] == [catalogue] * len(tool.cups)
    assert [m.cup.friction for m in tool.cups] == [bellows.friction] * 2


@pytest.mark.parametrize(
    ("old", "new", "message"),
    [
        (
            "suction_force: 25.0" + STIFFNESS,
            "suction_force: 25.0",
            r"key 'tool.cups\[0\].stiffness': load_sharing 'stiffness' needs",
        ),
        (
            "lateral: 1000,",
            "",
            r"key 'tool.cups\[0\].stiffness.lateral': .* > 0 N/m, got nan",
        ),
        (
            "torsion: 1}",
            "torsion: -1}",
            r"key 'tool.cups\[0\].stiffness.torsion': .*got -1",
        ),
    ],
)
def test_a_wrong_stiffness_is_refused_naming_the_key(tmp_path, old, new, message):
    from rt_drake import ScenarioError, load_scenario

    with pytest.raises(ScenarioError, match=message):
        load_scenario(_write(tmp_path, STIFF_SCENARIO.replace(old, new, 1)))


NO_CUPS = "tool:\n  cups: []\nobjects:" + TOOL_SCENARIO.split("objects:")[1]


@pytest.mark.parametrize(
    ("old", "new", "message"),
    [
        (
            "suction_force: 25.0",
            "suction_force: -1.0",
            r"'tool.cups\[0\].suction_force'",
        ),
        (
            "suction_force: 25.0",
            "suction: 25.0",
            r"unknown key 'tool.cups\[0\].suction'",
        ),
        ("tool:", "cup: {radius: 0.01}\ntool:", "keys 'cup' and 'tool'"),
        ("points", "points", "key 'tool.cups': a tool needs at least one cup"),
        (
            "tool:\n",
            "tool:\n  load_sharing: rigid\n",
            "key 'tool.load_sharing': must be one of elastic, any, stiffness, "
            "got 'rigid'",
        ),
        (
            "[0.06, 0, 0]}",
            "[0.06, 0, 0.01]}",
            "key 'tool.load_sharing': cup 0: elastic load sharing needs every cup",
        ),
    ],
)
def test_a_wrong_tool_is_refused_naming_the_key(tmp_path, old, new, message):
    from rt_drake import ScenarioError, load_scenario

    text = TOOL_SCENARIO.replace(old, new, 1)
    if "at least one cup" in message:
        text = TOOL_SCENARIO.split("tool:")[0] + NO_CUPS
    with pytest.raises(ScenarioError, match=message):
        load_scenario(_write(tmp_path, text))


def test_rt_drake_constraint_refuses_a_multi_cup_tool_by_name(tmp_path):
    from rt_drake import ScenarioError, load_scenario

    scenario = load_scenario(_write(tmp_path, TOOL_SCENARIO))
    message = "key 'tool': rt-drake constraint takes one cup"
    with pytest.raises(ScenarioError, match=message):
        scenario.single_cup("rt-drake constraint")


PEEL = "\n      peel_fraction: 0.5"


def test_a_stiffness_tool_states_each_cups_peel_limit(tmp_path):
    from rt_drake import load_scenario

    text = STIFF_SCENARIO.replace("suction_force: 25.0", "suction_force: 25.0" + PEEL)
    tool = load_scenario(_write(tmp_path, text)).tool_parameters()
    assert [m.cup.peel_fraction for m in tool.cups] == [0.5, None]


@pytest.mark.parametrize("sharing", ["", "  load_sharing: any\n"])
def test_a_peel_limit_without_the_stiffness_split_is_refused(tmp_path, sharing):
    from rt_drake import ScenarioError, load_scenario

    text = TOOL_SCENARIO.replace("tool:\n", "tool:\n" + sharing).replace(
        "suction_force: 25.0", "suction_force: 25.0" + PEEL
    )
    name = "any" if sharing else "elastic"
    message = (
        r"tool.yaml: key 'tool.cups\[0\].peel_fraction': needs 'tool.load_sharing: "
        rf"stiffness' .*, got load_sharing '{name}'$"
    )
    with pytest.raises(ScenarioError, match=message):
        load_scenario(_write(tmp_path, text))
