"""Retime your own arm along your own waypoints, under joint limits and a cup.

What it shows: nothing here comes from a scenario. The arm is a four-joint
URDF written below (a yaw base and three pitch joints, with its velocity
and ``drake:acceleration`` limits), its cup frame C a fixed frame at the
end of the last link (+z out of the cup, pointing down when the pitch
angles sum to zero). The cup and the 1.2 kg box it carries are plain
numbers, and the path is a plain (K, 4) numpy array of waypoints: the
retimer joins them with the clamped cubic spline through them at
chord-length knots (zero velocity at both ends) and makes it time-optimal.
The motion is retimed twice, under the joint limits alone and with the
cup's grasp constraint ``F w <= g``, re-checked at 1 kHz and saved as an
``.npz`` file.

What it prints (one ``key: value`` per line):

- ``joints``: the arm's joints, and ``waypoints``: how many;
- ``grasp rows``: the rows of the cup's exact wrench polytope;
- ``duration joint limits``: the duration under the joint limits alone, s;
- ``duration with cup``: the duration that also keeps the box on the cup, s;
- ``min margin``: the smallest margin to any limit found by the 1 kHz
  check, as a fraction of the limit (positive is room, negative over the
  limit; the contract is >= -0.001);
- ``check passed``: True when every limit and the grasp hold;
- ``saved``: the ``.npz`` file written, and its samples.

How to run it::

    python examples/02_your_own_arm.py             # writes ./my_arm.npz
    python examples/02_your_own_arm.py out.npz     # or the file you name

It takes about 10 s on a busy 2-core machine (3 s of CPU).
"""

from __future__ import annotations

import sys

import numpy as np
from pydrake.multibody.parsing import Parser
from pydrake.multibody.plant import MultibodyPlant

from rt_drake import (
    CupFrame,
    CupParameters,
    GraspConstraint,
    HeldObject,
    JointLimits,
    check_trajectory,
    path_waypoints_and_knots,
    retime,
    sample_trajectory,
    save_trajectory,
)


def _link(name: str, mass: float, length: float) -> str:
    """A link of ``mass`` kg, a rod of ``length`` m along its x axis."""
    inertia = mass * length**2 / 12.0 + 1e-4
    return f"""
  <link name="{name}">
    <inertial>
      <origin xyz="{length / 2} 0 0"/>
      <mass value="{mass}"/>
      <inertia ixx="1e-4" ixy="0" ixz="0" iyy="{inertia}" iyz="0" izz="{inertia}"/>
    </inertial>
  </link>"""


def _joint(
    name: str, parent: str, child: str, xyz: str, axis: str, v: float, a: float
) -> str:
    """A revolute joint of ``v`` rad/s and ``a`` rad/s^2 (and +-3 rad)."""
    return f"""
  <joint name="{name}" type="revolute">
    <parent link="{parent}"/>
    <child link="{child}"/>
    <origin xyz="{xyz}"/>
    <axis xyz="{axis}"/>
    <limit lower="-3" upper="3" effort="100" velocity="{v}" drake:acceleration="{a}"/>
  </joint>"""


#: The arm: base yaw at 0.3 m, then shoulder, elbow and wrist pitch joints
#: (links 0.35, 0.30 and 0.08 m along x); the cup 5 cm below the wrist
#: link's end, its z axis turned to point down (rpy = (pi, 0, 0)).
URDF = f"""<?xml version="1.0"?>
<robot name="my_arm" xmlns:drake="http://drake.mit.edu">
  <link name="base"/>
  {_link("turret", 2.0, 0.05)}
  {_link("upper_arm", 1.5, 0.35)}
  {_link("forearm", 1.0, 0.30)}
  {_link("wrist", 0.3, 0.08)}
  <link name="cup"/>
  {_joint("yaw", "base", "turret", "0 0 0.3", "0 0 1", 2.0, 8.0)}
  {_joint("shoulder", "turret", "upper_arm", "0 0 0", "0 1 0", 2.0, 8.0)}
  {_joint("elbow", "upper_arm", "forearm", "0.35 0 0", "0 1 0", 2.5, 10.0)}
  {_joint("wrist_pitch", "forearm", "wrist", "0.30 0 0", "0 1 0", 3.0, 12.0)}
  <joint name="cup_mount" type="fixed">
    <parent link="wrist"/>
    <child link="cup"/>
    <origin xyz="0.08 0 -0.05" rpy="3.141592653589793 0 0"/>
  </joint>
</robot>
"""

#: The path: (K, 4) joint waypoints, rad. The three pitch angles sum to
#: zero at every waypoint, so the cup points straight down at each.
WAYPOINTS = np.array(
    [
        [-1.2, 0.30, 0.60, -0.90],
        [-0.6, -0.10, 0.70, -0.60],
        [0.2, -0.20, 0.50, -0.30],
        [0.9, 0.20, 0.40, -0.60],
        [1.3, 0.35, 0.55, -0.90],
    ]
)

#: The cup (m, N) and the box it carries: 1.2 kg, 20 x 15 x 6 cm, its centre
#: 3 cm beyond the cup's face (in C, kg m^2 about its centre of mass).
CUP = CupParameters(
    radius=0.015, points=6, friction=0.5, sides=4,
    suction_force=25.0, max_normal_force=60.0,
)  # fmt: skip
BOX = HeldObject(
    mass=1.2,
    p_CoScm_C=np.array([0.0, 0.0, 0.03]),
    I_Scm_C=1.2 / 12.0 * np.diag([0.0261, 0.0436, 0.0625]),  # (b²+c², a²+c², a²+b²)
)


def build_arm() -> MultibodyPlant:
    """The arm of :data:`URDF`, its base welded to the world."""
    plant = MultibodyPlant(0.0)
    Parser(plant).AddModelsFromString(URDF, "urdf")
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("base"))
    plant.Finalize()
    return plant


def main(out: str = "my_arm.npz") -> None:
    """Retime :data:`WAYPOINTS` on :data:`URDF`'s arm, check and save it."""
    plant = build_arm()
    cup_frame = CupFrame.of(plant, "cup")
    limits = JointLimits.from_plant(plant)  # the URDF's velocity, acceleration
    grasp = GraspConstraint.for_cup(BOX, CUP)

    free = retime(plant, WAYPOINTS, limits, cup=cup_frame)
    result = retime(plant, WAYPOINTS, limits, grasp, cup=cup_frame)
    check = check_trajectory(plant, result.trajectory, limits, grasp, cup=cup_frame)

    # The file records the waypoints and the chord-length knots of the spline.
    waypoints, knots = path_waypoints_and_knots(WAYPOINTS)
    saved = sample_trajectory(
        plant, result, BOX, grasp, CUP, "box", waypoints, knots,
        cup_frame=cup_frame.frame,
    )  # fmt: skip
    save_trajectory(out, saved)

    print(f"joints: {plant.num_positions()}")
    print(f"waypoints: {len(WAYPOINTS)}")
    print(f"grasp rows: {len(grasp.g)}")
    print(f"duration joint limits: {free.duration:.4f} s")
    print(f"duration with cup: {result.duration:.4f} s")
    print(f"min margin: {check.min_margin():+.2e}")
    print(f"check passed: {check.passed()}")
    print(f"saved: {out} ({len(saved.t)} samples)")


if __name__ == "__main__":
    main(*sys.argv[1:2])
