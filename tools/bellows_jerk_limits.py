"""The grasp ramp from a bellows cup's natural period, for a scenario's objects.

    python tools/bellows_jerk_limits.py SCENARIO [--cup vs060_bellows]

The bellows and the held object are a spring-mass system. A step in the
commanded acceleration makes it overshoot; an acceleration ramp as long as
the system's natural period T_n leaves no residual vibration (an undamped
oscillator driven by a ramp of duration T_r keeps an amplitude factor
``|sin(pi T_r / T_n) / (pi T_r / T_n)|``, zero at T_r = T_n). So each
joint's jerk in the grasp-constrained MOVE is limited to ``a_max / T_n``
(the scenario's ``planning.grasp_ramp_s: T_n``): going from rest to its
acceleration limit takes at least T_n. The motions without the grasp
constraint keep the robot's own ``robot.jerk_limits``.

A ramp longer than T_n still leaves an overshoot during the ramp: the
dynamic load factor of an undamped oscillator under a ramp of duration
``t_r`` to a constant load is ``1 + |sin(pi x) / (pi x)|``, ``x = t_r /
T_n`` (Chopra, Dynamics of Structures, "step force with finite rise
time"), at most ``1 + 0.217`` for ``x >= 1`` (at ``pi x = 4.493``, where
``tan(pi x) = pi x``). Retiming under ``F w <= (1 - m) g`` with ``m >= 1 -
1 / 1.217 = 0.178`` keeps the overshoot in the grasp set; the tool prints
that ``planning.grasp_margin``.

T_n is the longest period of the modes of the held object on the tool's
bellows (:mod:`rt_drake.dynamics.bellows_modes`): the eigenvalues of the
tool's 6 x 6 stiffness, every cup's bushing in parallel at its pose X_TC
(two cups 2 d apart stiffen torsion by ``2 k_lateral d^2`` and tilt across
the pair by ``2 k_axial d^2``), against the spatial inertia of the object
and the lips about the tool frame. For one cup these are the axial,
lateral, tilt and torsion periods ``2 pi sqrt(m / k)`` and ``2 pi sqrt(I /
k)``, coupled where the centre of mass lies off the cup. An object with an
uncertainty set (``objects[].uncertainty``) gives the longest period over
the corners of its set that are bodies. Prints the periods (longest
first), the ``planning.grasp_ramp_s`` line (s) and the grasp-constrained
MOVE's jerk limits it gives (rad/s^3) for the scenario's acceleration
limits (the URDF's when the scenario gives none).
"""

from __future__ import annotations

import argparse

import numpy as np
from pydrake.math import RigidTransform, RotationMatrix

from rt_drake.dynamics.bellows_modes import held_inertia, mode_periods, tool_stiffness
from rt_drake.model.cup_physics import DEFAULT_BELLOWS_CUP, load_bellows_cup
from rt_drake.model.held import held_object_of
from rt_drake.model.plant import make_arm_plant, robot_position_indices
from rt_drake.model.resources import resolve_scenario_path
from rt_drake.model.scenario import load_scenario
from rt_drake.retiming import JointLimits
from rt_drake.uncertainty.object_samples import ObjectInertia, corners


def main() -> None:
    """Print the periods, the grasp ramp and its jerk limits."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenario")
    parser.add_argument("--cup", default=DEFAULT_BELLOWS_CUP)
    args = parser.parse_args()
    scenario = load_scenario(resolve_scenario_path(args.scenario))
    cup = load_bellows_cup(args.cup)
    plant = make_arm_plant(scenario)
    X_TCs = [
        mount_pose(mount.R_TC, mount.p_TC) for mount in scenario.tool_parameters().cups
    ]
    K = tool_stiffness(cup, X_TCs)
    longest = 0.0
    for obj in scenario.objects:
        helds = [held_object_of(obj)]
        if obj.uncertainty is not None and not obj.uncertainty.is_zero():
            X_OC = obj.grasp.GetDeterministicValue()
            sample = corners(ObjectInertia.of_model(obj), obj.uncertainty)
            helds += [o.held(X_OC) for o in sample]
        periods = [mode_periods(K, held_inertia(h, cup, X_TCs))[0] for h in helds]
        nominal, worst = periods[0], max(periods, key=lambda T: T[0])
        line = ", ".join(f"{1e3 * T:.0f}" for T in nominal)
        print(f"modes ({obj.name}, {len(X_TCs)} cup(s)): {line} ms")
        if len(periods) > 1:
            print(
                f"  longest over the {len(periods) - 1} corners of its set: "
                f"{1e3 * worst[0]:.0f} ms"
            )
        longest = max(longest, worst[0])
    limits = JointLimits.from_plant(plant, scenario.robot)
    robot = plant.GetModelInstanceByName(scenario.robot.model_instance)
    assert len(robot_position_indices(plant, robot)) == len(limits.acceleration)
    jerk = np.asarray(limits.acceleration) / longest
    print(f"longest: {longest * 1e3:.0f} ms")
    print(f"  grasp_ramp_s: {longest:.3f}")
    print(f"  grasp_margin: {overshoot_margin():.3f}")
    values = ", ".join(f"{j:.1f}" for j in jerk)
    print(f"its grasp-constrained jerk limits, rad/s^3 (before robot's): [{values}]")


def mount_pose(R_TC: np.ndarray, p_TC: np.ndarray) -> RigidTransform:
    """X_TC of a cup mount."""
    return RigidTransform(RotationMatrix(R_TC), p_TC)


def overshoot_margin() -> float:
    """``1 - 1 / (1 + max_{x >= 1} |sin(pi x) / (pi x)|)``: 0.178 (module docstring)."""
    x = np.linspace(1.0, 3.0, 200001)
    factor = 1.0 + np.max(np.abs(np.sin(np.pi * x) / (np.pi * x)))
    return 1.0 - 1.0 / factor


if __name__ == "__main__":
    main()
