"""The scripts in examples/ run and print what their docstrings promise.

Each script runs as a user runs it (``python examples/xx.py``, in a fresh
working directory, with this environment's ``PYTHONPATH``), and its printed
numbers and written files are checked by other routes than rt_drake's:

- a saved ``.npz`` trajectory: its joint velocities against finite
  differences of its positions, and against the limits read from the URDF;
  its cup poses ``X_WC`` give, by finite differences and Newton-Euler, the
  wrench the cup exerts on the object, which must lie in the file's
  ``F w <= g`` (and touch its boundary where the grasp made the motion
  slower than the joint limits alone);
- the duration under the joint limits alone of the example's own arm:
  Drake's ``Toppra`` on the same clamped cubic spline (rebuilt from the
  file's waypoints, its knots checked to be the chord lengths);
- the two-cup tool and the campaign's weak cup: the object's weight (mass
  from the model file) against the cups' suction forces;
- the campaign: its printed rows against its SQLite database.

Each example takes 10-50 s on a busy 2-core machine; one test per example,
so that pytest-xdist can spread them.
"""

from __future__ import annotations

import ast
import os
import re
import sqlite3
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest
from pydrake.multibody.optimization import CalcGridPointsOptions, Toppra
from pydrake.trajectories import PiecewisePolynomial
from scipy.spatial.transform import Rotation

import rt_drake
from rt_drake import SavedTrajectory, load_trajectory

pytestmark = pytest.mark.slow

REPO = Path(__file__).resolve().parents[2]
EXAMPLES = REPO / "examples"
SCRIPTS = sorted(EXAMPLES.glob("[0-9][0-9]_*.py"))
#: m/s^2, the plants' gravity (Drake's default), along -z of W.
GRAVITY = 9.81
#: The contract of the 1 kHz check, on every limit and on the grasp.
CONTRACT = 1e-3
#: Allowed excess of the finite-difference wrench over ``F w <= g``: the
#: second differences of 1 ms samples smooth the retimer's jumps of s''.
FD_TOLERANCE = 5e-3
DRAKE_NS = "{http://drake.mit.edu}"


def _run(script: str, cwd: Path) -> dict[str, str]:
    """Run examples/``script`` in ``cwd``; the ``key: value`` lines it prints.

    A key printed several times (the campaign's ``row`` and ``held``) keeps
    every value, one per line.
    """
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(
        p for p in (str(REPO), os.environ.get("PYTHONPATH")) if p
    )
    done = subprocess.run(
        [sys.executable, str(EXAMPLES / script)],
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert done.returncode == 0, done.stdout + done.stderr
    printed: dict[str, str] = {}
    for line in done.stdout.splitlines():
        key, colon, value = line.partition(": ")
        if colon and re.fullmatch(r"[a-z][a-z ]*", key):
            printed[key] = f"{printed[key]}\n{value}" if key in printed else value
    return printed


def _seconds(text: str) -> float:
    number, unit = text.split()
    assert unit == "s"
    return float(number)


def _cup_wrenches(saved: SavedTrajectory) -> np.ndarray:
    """(M', 6) the wrench [torque; force] the cup exerts on the object, in C.

    From the cup poses alone: the object's centre of mass p_WS = p_WC + R_WC
    p_CS, its acceleration a by second central differences, the angular
    velocity w_W from log(R(t+h) R(t-h)^T) / 2h and its derivative by central
    differences; then Newton-Euler about the centre of mass, moved to Co:
    f = m R^T (a - g), tau = I alpha + omega x I omega + p_CS x f (in C).
    Uses the uniformly spaced samples (all but the last, at the duration).
    """
    t = saved.t[:-1]
    h = float(np.diff(t).mean())
    assert np.allclose(np.diff(t), h, atol=1e-9)
    R = saved.X_WC[:-1, :3, :3]
    p_WS = saved.X_WC[:-1, :3, 3] + R @ saved.p_CoScm_C
    a_W = (p_WS[2:] - 2.0 * p_WS[1:-1] + p_WS[:-2]) / h**2  # samples 1..M-2
    turn = Rotation.from_matrix(R[2:] @ np.transpose(R[:-2], (0, 2, 1)))
    w_W = turn.as_rotvec() / (2.0 * h)  # samples 1..M-2
    alpha_W = (w_W[2:] - w_W[:-2]) / (2.0 * h)  # samples 2..M-3
    R_CW = np.transpose(R[2:-2], (0, 2, 1))
    g_W = np.array([0.0, 0.0, -GRAVITY])
    f_C = saved.object_mass * np.einsum("nij,nj->ni", R_CW, a_W[1:-1] - g_W)
    w_C = np.einsum("nij,nj->ni", R_CW, w_W[1:-1])
    alpha_C = np.einsum("nij,nj->ni", R_CW, alpha_W)
    I = saved.I_Scm_C  # noqa: E741
    tau_C = alpha_C @ I.T + np.cross(w_C, w_C @ I.T) + np.cross(saved.p_CoScm_C, f_C)
    return np.hstack([tau_C, f_C])


def _grasp_use(saved: SavedTrajectory) -> float:
    """max over samples and rows of F w / g (<= 1: inside the grasp set)."""
    assert saved.F.shape[0] > 0
    return float((_cup_wrenches(saved) @ saved.F.T / saved.g).max())


def _urdf_limits(root: ET.Element) -> tuple[np.ndarray, np.ndarray]:
    """Velocity and drake:acceleration limits of a URDF's revolute joints."""
    joints = root.findall("joint")  # not a transmission's <joint>
    limits = [j.find("limit") for j in joints if j.get("type") == "revolute"]
    velocity = [float(limit.get("velocity")) for limit in limits]
    acceleration = [float(limit.get(f"{DRAKE_NS}acceleration")) for limit in limits]
    return np.array(velocity), np.array(acceleration)


def _check_joint_limits(saved: SavedTrajectory, velocity, acceleration) -> None:
    """qd is dq/dt, and qd, qdd are within the limits (the check's contract)."""
    h = saved.t[1] - saved.t[0]
    qd = (saved.q[2:-1] - saved.q[:-3]) / (2.0 * h)
    assert np.abs(qd - saved.qd[1:-2]).max() < 1e-2  # rad/s
    assert (np.abs(saved.qd) <= velocity * (1.0 + CONTRACT)).all()
    assert (np.abs(saved.qdd) <= acceleration * (1.0 + CONTRACT)).all()


def _load_example(name: str) -> ModuleType:
    """The example's module, for its constants (its main() is not run)."""
    import importlib.util

    spec = importlib.util.spec_from_file_location(name, EXAMPLES / f"{name}.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _model_mass(model: str) -> float:
    """The mass (kg) an object's SDF states."""
    root = ET.parse(REPO / "models" / "objects" / model).getroot()
    (mass,) = root.iter("mass")
    return float(mass.text)


def test_there_are_four_examples_on_the_public_api_only():
    """Each imports only rt_drake's public names, numpy, pydrake and stdlib."""
    assert len(SCRIPTS) >= 4
    for script in SCRIPTS:
        tree = ast.parse(script.read_text())
        docstring = ast.get_docstring(tree)
        assert docstring and f"python examples/{script.name}" in docstring
        assert "What it prints" in docstring and "What it shows" in docstring
        assert any(
            isinstance(node, ast.FunctionDef) and node.name == "main"
            for node in tree.body
        )
        assert 'if __name__ == "__main__":' in script.read_text()
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom):
                modules = [node.module or ""]
                if modules[0].split(".")[0] == "rt_drake":
                    assert node.module == "rt_drake", (script.name, node.module)
                    names = {alias.name for alias in node.names}
                    assert names <= set(rt_drake.__all__), (script.name, names)
            elif isinstance(node, ast.Import):
                modules = [alias.name for alias in node.names]
                assert not any(m.startswith("rt_drake.") for m in modules)
            else:
                continue
            for module in modules:
                top = module.split(".")[0]
                assert top in {"numpy", "pydrake", "rt_drake", "__future__"} or (
                    top in sys.stdlib_module_names
                ), (script.name, module)


def test_01_retime_a_move(tmp_path):
    printed = _run("01_retime_a_move.py", tmp_path)
    assert printed["object"] == "notebook"
    assert printed["check passed"] == "True"
    assert float(printed["min margin"]) >= -CONTRACT
    with_grasp = _seconds(printed["duration with grasp"])
    without = _seconds(printed["duration without grasp"])
    assert 0.0 < without < with_grasp  # the grasp binds on this MOVE
    assert float(printed["min margin without grasp"]) < -0.1  # it would slip

    saved = load_trajectory(tmp_path / "move.npz")
    assert printed["saved"] == f"move.npz ({len(saved.t)} samples)"
    assert saved.duration == pytest.approx(with_grasp, abs=5e-5)
    assert saved.object_name == "notebook"
    assert saved.object_mass == pytest.approx(_model_mass("notebook.sdf"))
    assert len(saved.g) == int(printed["grasp rows"])
    urdf = ET.parse(REPO / "models" / "robot" / "vs060.urdf").getroot()
    _check_joint_limits(saved, *_urdf_limits(urdf))
    # Inside F w <= g, and on its boundary: the grasp is what limits it.
    assert 1.0 - 1e-2 < _grasp_use(saved) <= 1.0 + FD_TOLERANCE


def test_02_your_own_arm(tmp_path):
    printed = _run("02_your_own_arm.py", tmp_path)
    example = _load_example("02_your_own_arm")
    assert printed["joints"] == "4"
    assert printed["waypoints"] == str(len(example.WAYPOINTS))
    assert printed["check passed"] == "True"
    assert float(printed["min margin"]) >= -CONTRACT
    free = _seconds(printed["duration joint limits"])
    with_cup = _seconds(printed["duration with cup"])
    assert 0.0 < free < with_cup

    saved = load_trajectory(tmp_path / "my_arm.npz")
    assert saved.duration == pytest.approx(with_cup, abs=5e-5)
    np.testing.assert_array_equal(saved.waypoints, example.WAYPOINTS)
    np.testing.assert_allclose(saved.q[0], example.WAYPOINTS[0], atol=1e-12)
    np.testing.assert_allclose(saved.q[-1], example.WAYPOINTS[-1], atol=1e-9)
    chords = np.linalg.norm(np.diff(example.WAYPOINTS, axis=0), axis=1)
    knots = np.concatenate([[0.0], np.cumsum(chords)]) / chords.sum()
    np.testing.assert_allclose(saved.knots, knots, atol=1e-12)
    velocity, acceleration = _urdf_limits(ET.fromstring(example.URDF))
    _check_joint_limits(saved, velocity, acceleration)
    assert 1.0 - 1e-2 < _grasp_use(saved) <= 1.0 + FD_TOLERANCE

    # Joint limits alone, by Drake's TOPP-RA on the clamped cubic spline
    # through the same waypoints at the same knots, on a fine grid (limits
    # only at its points: at most the true optimum, plus its own error).
    # The example's default grid of about 100 points is coarser: its
    # duration is measured 4.4 % above (1.575 s against 1.508 s).
    n = len(velocity)
    spline = PiecewisePolynomial.CubicWithContinuousSecondDerivatives(
        knots, example.WAYPOINTS.T, np.zeros(n), np.zeros(n)
    )
    options = CalcGridPointsOptions()
    options.max_seg_length, options.min_points = 1e-3, 1000
    toppra = Toppra(spline, example.build_arm(), Toppra.CalcGridPoints(spline, options))
    toppra.AddJointVelocityLimit(-velocity, velocity)
    toppra.AddJointAccelerationLimit(-acceleration, acceleration)
    s_of_t = toppra.SolvePathParameterization()
    optimum = s_of_t.end_time() - s_of_t.start_time()
    assert optimum * (1.0 - 2e-3) <= free <= optimum * 1.06


def test_03_two_cup_tool(tmp_path):
    printed = _run("03_two_cup_tool.py", tmp_path)
    assert printed["object"] == "heavy_carton"
    assert printed["one cup"].startswith("GraspUnstableAtRestError: ")
    assert printed["check passed"] == "True"
    assert float(printed["min margin"]) >= -CONTRACT
    duration = _seconds(printed["duration with two cups"])
    assert duration > 0.0

    saved = load_trajectory(tmp_path / "two_cups.npz")
    assert saved.duration == pytest.approx(duration, abs=5e-5)
    assert len(saved.g) == int(printed["tool rows"])
    values = dict(zip(saved.cup_names, saved.cup_values, strict=True))
    suction = [values[f"cups[{i}].suction_force"] for i in (0, 1)]
    assert [values[f"cups[{i}].p_TC[0]"] for i in (0, 1)] == [0.06, -0.06]
    # One cup cannot pull the carton up: its rim only pushes, so the most it
    # pulls is its suction; two cups can.
    weight = _model_mass("heavy_carton.sdf") * GRAVITY
    assert float(printed["weight"].removesuffix(" N")) == pytest.approx(weight, 1e-3)
    assert max(suction) < weight < sum(suction)
    urdf = ET.parse(REPO / "models" / "robot" / "vs060.urdf").getroot()
    _check_joint_limits(saved, *_urdf_limits(urdf))
    assert _grasp_use(saved) <= 1.0 + FD_TOLERANCE


def test_04_campaign(tmp_path):
    printed = _run("04_campaign.py", tmp_path)
    out = tmp_path / "campaign_example"
    rows = {line.split()[1]: line for line in printed["row"].splitlines()}
    assert set(rows) == {"paper", "weak"}
    paper = re.fullmatch(
        r"kindle_box paper constrained ok: duration (\S+) s, held True, "
        r"slip (\S+) mm",
        rows["paper"],
    )
    assert paper is not None, rows["paper"]
    assert rows["weak"].startswith(
        "kindle_box weak constrained infeasible: error GraspUnstableAtRestError: "
    )
    # The weak cup's 1 N of suction is less than the box's weight; the
    # paper cup's 20 N is more.
    assert 1.0 < _model_mass("kindle_box.sdf") * GRAVITY < 20.0
    assert printed["held"].splitlines() == ["paper 1/1", "weak 0/0"]

    with sqlite3.connect(out / "campaign.db") as connection:
        (duration, slip, success) = connection.execute(
            "SELECT duration_s, slip_translation_mm, success FROM rollouts"
            " WHERE cup = 'paper'"
        ).fetchone()
        assert connection.execute("SELECT COUNT(*) FROM rollouts").fetchone() == (2,)
    assert float(paper[1]) == pytest.approx(duration, abs=5e-4)
    assert float(paper[2]) == pytest.approx(slip, abs=5e-3)
    assert success == 1 and 0.5 < duration < 5.0
    assert printed["report"] == str(Path("campaign_example") / "report")
    table = (out / "report" / "summary.md").read_text()
    assert "| kindle_box | paper | 1/1 |" in table
    assert "| kindle_box | weak | 0/0 | - | 1 |" in table
