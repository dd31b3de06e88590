"""The grasp margin of one MOVE from the bellows cup's ring, found by retiming.

The retimer keeps the *quasi-static* wrench ``w(t)`` of a MOVE (the held
object's inertia and weight; N m, N; in the cup or tool frame T, about its
origin) inside the shrunk set ``F w <= (1 - m) g``. On bellows cups the
object rings: the cups carry ``K d(t)``, the tool's stiffness times the held
body's deflection, with ``M d'' + C d' + K d = w`` (the tool's linear modes,
:mod:`rt_drake.dynamics.bellows_modes`: catalogue stiffness and damping, the
held object's and lips' inertia; integrated exactly for ``w`` linear between
samples ``STEP_S`` apart, from rest in equilibrium). :func:`ring_load`
measures, on the unshrunk rows,

    r_static = max_t max_rows F w(t) / g,   r_ring = max_t max_rows F K d(t) / g,

and ``D = r_ring / r_static``, the dynamic load factor. The ring stays in
the set when ``r_ring <= 1``; since the retime holds ``r_static <= 1 - m``,
``(1 - m) D <= 1`` is sufficient, and the two agree when a grasp row is
active (a grasp-limited MOVE). :func:`retime_for_ring` accepts a margin on
``r_ring <= 1``, the statement itself.

:func:`retime_for_ring` searches m for one MOVE: from ``start``, each retime
at m gives ``r_ring(m)``; held (``<= 1``) makes m an upper end of the
bracket, not held a lower end, and a margin the retimer refuses (gravity
alone, or the path, outside the shrunk set) an upper end too. The next m is
``1 - (1 - m) / r_ring`` (shrink the set by the overshoot: with a row active,
the fixed point ``m = 1 - 1 / D(m)``), moved to at least ``tolerance`` from
m (so that a step from below that falls just short of the edge does not
creep up on it), when it falls inside the bracket, else the bracket's
midpoint; the upper end starts at the largest m gravity allows
along the path's grid (``1 - max_s max_rows F w_rest(s) / g``), so no retime
is spent above it. It stops when a held m lies within ``tolerance`` of a
lower end, after at most ``max_retimes`` retimes, deterministically. It
returns the least held m found, or raises :class:`RingNotHeldError`.

What it bounds: the linear modes' response to the planned wrench, at the
samples, on the rows the planner states, from the MOVE's start to its end.
What it does not: the lip's nonlinearity (peel, the seal's leak, friction
that is not the planner's rows), the ring left after the MOVE's end, a
command that departs from the planned trajectory (interpolation, tracking
error), a set of objects (an uncertainty set: one object's modes only).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

import numpy as np
from pydrake.multibody.plant import MultibodyPlant
from pydrake.systems.framework import Context
from pydrake.trajectories import Trajectory

from rt_drake import arguments
from rt_drake.dynamics.bellows_modes import BellowsTool
from rt_drake.dynamics.cup_frame import CupFrame
from rt_drake.dynamics.wrench import object_wrench, path_wrench_coefficients
from rt_drake.retiming._joint_path import PathLike, as_joint_path
from rt_drake.retiming._retime_errors import (
    RetimeError,
    RetimeInputError,
    RetimeStatus,
)
from rt_drake.retiming._solve import RetimeResult
from rt_drake.retiming.grasp_constraint import GraspConstraint

#: s, the spacing of the load's samples (at most; the MOVE's length divided
#: evenly). The shortest catalogue period is 124 ms: at 2 ms a peak between
#: samples is at most ``1 - cos(pi 2 / 124)``, 0.13 %, above the samples'.
STEP_S = 0.002
#: Share of g: stop when the least held m is within this of a lower end.
TOLERANCE = 0.01
#: Retimes per MOVE at most.
MAX_RETIMES = 8


class RingNotHeldError(RetimeError):
    """No margin the retimer accepts keeps the bellows' ring in the grasp set."""

    status = RetimeStatus.RING_NOT_HELD


@dataclasses.dataclass(frozen=True)
class RingLoad:
    """The ring of one retimed MOVE on the unshrunk rows (module docstring).

    Attributes:
        static: ``r_static``, the largest row of the planned wrench.
        ring: ``r_ring``, the largest row of the wrench the bellows carry.
        t_peak: s into the MOVE at which ``ring`` is reached.
    """

    static: float
    ring: float
    t_peak: float

    @property
    def factor(self) -> float:
        """``D = ring / static``, the dynamic load factor."""
        return self.ring / self.static


@dataclasses.dataclass(frozen=True)
class RingRetime:
    """A MOVE retimed with the least margin found that holds its ring.

    Attributes:
        result: The retime under ``grasp.with_margin(margin)``.
        grasp: That constraint (the shrunk set).
        margin: m, the share of g kept free.
        load: Its ring (``load.ring <= 1``).
        retimes: How many retimes the search took (this one included).
        tried: ``(m, r_ring or None if refused)`` of each retime, in order.
    """

    result: RetimeResult
    grasp: GraspConstraint
    margin: float
    load: RingLoad
    retimes: int
    tried: tuple[tuple[float, float | None], ...]


def ring_load(
    plant: MultibodyPlant,
    trajectory: Trajectory,
    grasp: GraspConstraint,
    tool: BellowsTool,
    context: Context | None = None,
    cup: CupFrame | None = None,
) -> RingLoad:
    """The ring of ``trajectory`` (rad, s) on ``grasp``'s rows (module docstring).

    ``w`` is the wrench ``grasp.held`` needs (:func:`~rt_drake.dynamics.
    wrench.object_wrench`, in the frame ``cup``, default the plant's
    ``suction_cup``) at equally spaced samples at most :data:`STEP_S` apart,
    from the trajectory's own derivatives; ``K d`` is
    :meth:`BellowsTool.carried`. Rows: ``grasp.F``, ``grasp.g`` as given
    (pass the unshrunk set).
    """
    _check(plant, grasp, tool, "ring_load")
    start, end = trajectory.start_time(), trajectory.end_time()
    n = max(int(np.ceil((end - start) / STEP_S)), 1)
    t = np.linspace(start, end, n + 1)
    q, v, a = _states(trajectory, t)
    w = object_wrench(plant, grasp.held, q, v, a, context, cup)
    carried = tool.carried(t, w, grasp.held)
    static = _rows(grasp, w)
    ring = _rows(grasp, carried)
    peak = int(np.argmax(ring))
    return RingLoad(float(static.max()), float(ring[peak]), float(t[peak] - start))


def retime_for_ring(
    retime_with: Callable[[GraspConstraint], RetimeResult],
    path: PathLike,
    grasp: GraspConstraint,
    tool: BellowsTool,
    plant: MultibodyPlant,
    context: Context | None = None,
    cup: CupFrame | None = None,
    start: float = 0.0,
    tolerance: float = TOLERANCE,
    max_retimes: int = MAX_RETIMES,
) -> RingRetime:
    """Retime ``path`` with the least margin that holds the bellows' ring.

    ``retime_with(grasp.with_margin(m))`` retimes the MOVE at m (the
    caller's grid and limits); ``grasp`` is the unshrunk set, ``tool`` the
    bellows cups holding ``grasp.held`` (in the frame ``cup``). The search
    and what it bounds: module docstring.

    Raises:
        RetimeError: the retime at ``start`` fails (as it would without the
            ring), or :class:`RingNotHeldError`: the ring exceeds the set at
            every margin tried, up to the largest gravity allows at rest.
    """
    _check(plant, grasp, tool, "retime_for_ring")
    if grasp.is_robust:
        raise RetimeInputError(
            "retime_for_ring: the ring of a set of objects is not bounded (one "
            "object's modes only); give the nominal grasp or a fixed margin"
        )
    rest = _rest_margin(plant, path, grasp, context, cup)
    lo, hi = start, rest
    if hi <= start:
        raise RingNotHeldError(
            f"the bellows' ring cannot be held: gravity alone takes "
            f"{1.0 - hi:.3f} of the grasp set at rest, no margin above "
            f"{max(hi, 0.0):.3f} is left (start {start:.3f})"
        )
    best: tuple[float, RetimeResult, RingLoad] | None = None
    tried: list[tuple[float, float | None]] = []
    m = start
    for _ in range(max_retimes):
        try:
            result = retime_with(grasp.with_margin(m))
        except RetimeInputError:
            raise
        except RetimeError:
            if not tried:
                raise
            tried.append((m, None))
            hi = m
            m = 0.5 * (lo + hi)
            continue
        load = ring_load(plant, result.trajectory, grasp, tool, context, cup)
        tried.append((m, load.ring))
        if load.ring <= 1.0:
            best = (m, result, load)
            hi = m
        else:
            lo = m
        if best is not None and hi - lo <= tolerance:
            break
        proposal = 1.0 - (1.0 - m) / load.ring  # at least a tolerance away
        if load.ring > 1.0:
            proposal = max(proposal, m + tolerance)
        else:
            proposal = min(proposal, m - tolerance)
        m = proposal if lo < proposal < hi else 0.5 * (lo + hi)
    if best is None:
        rows = ", ".join(
            f"{m:.3f} {'refused' if r is None else f'{r:.3f}'}" for m, r in tried
        )
        raise RingNotHeldError(
            f"the bellows' ring exceeds the grasp set at every margin of "
            f"{len(tried)} retimes (m, ring rows: {rows}); gravity allows m up "
            f"to {rest:.3f}"
        )
    m, result, load = best
    return RingRetime(result, grasp.with_margin(m), m, load, len(tried), tuple(tried))


def _rest_margin(
    plant: MultibodyPlant,
    path: PathLike,
    grasp: GraspConstraint,
    context: Context | None,
    cup: CupFrame | None,
    samples: int = 200,
) -> float:
    """The largest m gravity allows at rest along ``path``: ``1 - max F w_rest / g``.

    ``w_rest(s) = c(s)``, the wrench of the object held still at ``q(s)``
    (:func:`~rt_drake.dynamics.wrench.path_wrench_coefficients`), at
    ``samples`` equally spaced s in [0, 1].
    """
    s = np.linspace(0.0, 1.0, samples)
    q = as_joint_path(path)
    _, _, c = path_wrench_coefficients(
        plant, grasp.held, q(s), q(s, 1), q(s, 2), context, cup
    )
    return 1.0 - float(_rows(grasp, c).max())


def _states(
    trajectory: Trajectory, t: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(q, q', q'')`` at times ``t``, each (N, n).

    Vectorised where the trajectory samples itself (the retimer's), else
    through Drake's ``value`` and ``EvalDerivative``.
    """
    sample = getattr(trajectory, "sample", None)
    if sample is not None:
        q, v, a = sample(t, 2)
        return q, v, a
    q = np.array([np.ravel(trajectory.value(x)) for x in t])
    v = np.array([np.ravel(trajectory.EvalDerivative(x, 1)) for x in t])
    a = np.array([np.ravel(trajectory.EvalDerivative(x, 2)) for x in t])
    return q, v, a


def _check(plant: object, grasp: object, tool: object, where: str) -> None:
    """The types of ``plant``, ``grasp`` and ``tool`` (RetimeInputError, named)."""
    arguments.instance(
        plant, "plant", MultibodyPlant, where=where, error=RetimeInputError
    )
    arguments.instance(
        grasp, "grasp", GraspConstraint, where=where, error=RetimeInputError
    )
    arguments.instance(tool, "tool", BellowsTool, where=where, error=RetimeInputError)


def _rows(grasp: GraspConstraint, w: np.ndarray) -> np.ndarray:
    """``max_rows F w / g`` at each sample, (N,)."""
    return ((w @ grasp.F.T) / grasp.g).max(axis=1)


__all__ = [
    "MAX_RETIMES",
    "STEP_S",
    "TOLERANCE",
    "RingLoad",
    "RingNotHeldError",
    "RingRetime",
    "retime_for_ring",
    "ring_load",
]
