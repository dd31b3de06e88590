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

T_n is the longest period of the bellows' modes with each object of the
scenario: axial and lateral ``T = 2 pi sqrt((m + m_lip) / k)``, tilt and
torsion ``T = 2 pi sqrt(I / k)`` with I the object's moment of inertia about
the lip's axes (its centre of mass moved to the cup origin). Prints the
periods, the ``planning.grasp_ramp_s`` line (s) and the grasp-constrained
MOVE's jerk limits it gives (rad/s^3) for the scenario's acceleration limits
(the URDF's when the scenario gives none).
"""

from __future__ import annotations

import argparse
import math

import numpy as np

from rt_drake.model.cup_physics import DEFAULT_BELLOWS_CUP, load_bellows_cup
from rt_drake.model.held import held_object_of
from rt_drake.model.plant import make_arm_plant, robot_position_indices
from rt_drake.model.resources import resolve_scenario_path
from rt_drake.model.scenario import load_scenario
from rt_drake.retiming import JointLimits


def main() -> None:
    """Print the periods, the grasp ramp and its jerk limits."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenario")
    parser.add_argument("--cup", default=DEFAULT_BELLOWS_CUP)
    args = parser.parse_args()
    scenario = load_scenario(resolve_scenario_path(args.scenario))
    cup = load_bellows_cup(args.cup)
    plant = make_arm_plant(scenario)
    periods: dict[str, float] = {}
    for obj in scenario.objects:
        held = held_object_of(obj)
        p = held.p_CoScm_C
        I_Co = held.I_Scm_C + held.mass * (p @ p * np.eye(3) - np.outer(p, p))
        total = held.mass + cup.lip_mass
        for axis, inertia, k in (
            ("axial", total, cup.axial_stiffness),
            ("lateral", total, cup.lateral_stiffness),
            ("tilt", max(I_Co[0, 0], I_Co[1, 1]), cup.tilt_stiffness),
            ("torsion", I_Co[2, 2], cup.torsion_stiffness),
        ):
            T = 2 * math.pi * math.sqrt(inertia / k)
            periods[f"{axis} ({obj.name})"] = T
    period = max(periods.values())
    limits = JointLimits.from_plant(plant, scenario.robot)
    robot = plant.GetModelInstanceByName(scenario.robot.model_instance)
    assert len(robot_position_indices(plant, robot)) == len(limits.acceleration)
    jerk = np.asarray(limits.acceleration) / period
    print("periods: " + ", ".join(f"{k} {v * 1e3:.0f} ms" for k, v in periods.items()))
    print(f"longest: {period * 1e3:.0f} ms")
    print(f"  grasp_ramp_s: {period:.3f}")
    print(f"  grasp_margin: {overshoot_margin():.3f}")
    values = ", ".join(f"{j:.1f}" for j in jerk)
    print(f"its grasp-constrained jerk limits, rad/s^3 (before robot's): [{values}]")


def overshoot_margin() -> float:
    """``1 - 1 / (1 + max_{x >= 1} |sin(pi x) / (pi x)|)``: 0.178 (module docstring)."""
    x = np.linspace(1.0, 3.0, 200001)
    factor = 1.0 + np.max(np.abs(np.sin(np.pi * x) / (np.pi * x)))
    return 1.0 - 1.0 / factor


if __name__ == "__main__":
    main()
