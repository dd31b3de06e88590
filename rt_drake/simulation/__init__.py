"""The simulated cell: a Drake Diagram that runs the pick-and-place cycle.

- :mod:`._station`: ``MakeStation(scenario) -> Station``, the cell's Diagram.
- :mod:`._suction`: the vacuum force (``SuctionCup`` LeafSystem);
  :mod:`rt_drake.model.vacuum`: its build-up, "part present" and release.
- :mod:`._sequencer`: APPROACH .. DETACH per object (``Sequencer`` LeafSystem);
  :mod:`.records`: what it measures (``ObjectRecord``).
- :mod:`.motion`: what the sequencer asks for (``Motion``, ``MotionSource``)
  and the planning-ahead clock (``PendingMotion``).
- :mod:`.online_motions`: the planner plus retimer as the online motion
  source (``OnlineMotions``).
- :mod:`._retimer_system`: the retimer as a LeafSystem (``Retimer``).
- :mod:`rt_drake.dynamics.bellows_modes`: the natural periods of an object
  on a tool of bellows cups and their ring under a load (in dynamics, so
  that the retimer's ring margin can use them too).
- :mod:`._cycle_runner`: station + sequencer, simulated to the end
  (``run_cycle``).
"""

from rt_drake.model.vacuum import VacuumTimeout
from rt_drake.simulation._cycle_runner import (
    CycleResult,
    CycleTimeout,
    build_cycle,
    run_cycle,
)
from rt_drake.simulation._retimer_system import (
    Retimer,
    RetimeRequest,
)
from rt_drake.simulation._sequencer import (
    UPDATE_PERIOD,
    Sequencer,
)
from rt_drake.simulation._station import (
    MakeStation,
    Station,
    StationOptions,
)
from rt_drake.simulation._suction import SuctionCup
from rt_drake.simulation.motion import (
    Motion,
    MotionSource,
    PendingMotion,
    PhasePart,
    PlanTimes,
)
from rt_drake.simulation.move_grasp import held_object
from rt_drake.simulation.online_motions import OnlineMotions
from rt_drake.simulation.records import ObjectRecord, pose_difference

__all__ = [
    "UPDATE_PERIOD",
    "CycleResult",
    "CycleTimeout",
    "MakeStation",
    "Motion",
    "MotionSource",
    "ObjectRecord",
    "OnlineMotions",
    "PendingMotion",
    "PhasePart",
    "PlanTimes",
    "RetimeRequest",
    "Retimer",
    "Sequencer",
    "Station",
    "StationOptions",
    "SuctionCup",
    "VacuumTimeout",
    "build_cycle",
    "held_object",
    "pose_difference",
    "run_cycle",
]
