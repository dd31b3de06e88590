"""Time-optimal retiming of a joint path under grasp stability: :func:`retime`.

:func:`retime` finds the fastest time scaling s(t) of a path ``q(s)`` (the
planner's clamped spline) such that, rest to rest,

- ``|q'(s) s'| <= v_max`` and ``|q'(s) s'' + q''(s) s'^2| <= qdd_max``;
- optionally ``|tau| <= tau_max`` (inverse dynamics with the held object);
- optionally the grasp ``F (a(s) s'' + b(s) s'^2 + c(s)) <= g``, the object
  wrench of :mod:`rt_drake.dynamics.wrench` in the grasp polytope of
  :mod:`rt_drake.contact` (paper eqs 1, 6, 20),

by TOPP-RA on a uniform grid with toppra's interpolation discretization and
its seidel LP, compiled (:mod:`.passes`).

Exactness of the grasp rows: the polytope has hundreds of rows (834 for the
paper's cup) and only a few dozen bound the (u, x) slices along a path. The
stage LPs get the rows that ray shooting picks along the path
(:func:`rt_drake.retiming.stage_rows.rest_and_candidates`); then every row is
evaluated at every (u, x) the LPs enforced (both interpolation blocks,
:func:`rt_drake.retiming.stage_rows.wrench_ratios`), and any violated row is added
and the passes rerun (``repairs``). The returned profile is then admissible
for the full constraint and, as TOPP-RA's pointwise-maximal profile of a
relaxation of it, the very profile TOPP-RA computes with all rows (the tests
compare with toppra on all rows).

A grasp of a set of objects (:meth:`GraspConstraint.robust`: every object of
an uncertainty set, every cup of a friction and suction range) takes the same
steps with (row, vertex) pairs of the set's outer parameter set instead of
rows (:mod:`._robust_grasp`): the exactness check evaluates every row's worst
vertex in closed form, and between grid points the worst object is held by
cuts at the sub-points (then grid points, as for one object). A set of zero
width is one object and takes the single-object code (:mod:`._grasp_rows`),
unchanged.

The robot must be able to stop anywhere on the path: the object must be held
by gravity's wrench alone (``F c(s) < g``) and the arm's gravity torques must
be within limits at every grid point, else a typed error says where (for a
set, naming its worst object).

Between grid points (:mod:`._between`): joint limits are held by cuts (up to
:data:`MAX_CUT_ROUNDS` rounds per grid), torques and grasp by new grid points;
where cuts do not converge, the segments are split as well. If a limit is
still exceeded beyond the 1e-3 contract after :data:`MAX_REFINEMENTS`
refinements, :class:`._retime_errors.LimitsBetweenGridPointsError` says where: the
retimer never returns a trajectory it knows exceeds a limit.
"""

from __future__ import annotations

import dataclasses
import functools
from typing import NamedTuple

import numpy as np
import toppra
from pydrake.multibody.plant import MultibodyPlant
from pydrake.systems.framework import Context
from toppra.constraint import LinearConstraint

from rt_drake import arguments
from rt_drake.dynamics.cup_frame import CupFrame
from rt_drake.dynamics.wrench import PathCoefficients
from rt_drake.retiming._at_rest import check_torque_at_rest
from rt_drake.retiming._between import (
    Segments,
    interior_rows,
    joint_cuts,
    joint_excess_max,
    joint_split_points,
    refinement_points,
)
from rt_drake.retiming._between_kernels import position_excess
from rt_drake.retiming._check import (
    DEFAULT_TOLERANCE,
    Margin,
)
from rt_drake.retiming._grasp_rows import (
    ROW_TOLERANCE,
    ObjectRows,
)
from rt_drake.retiming._jerk import check_smooth, jerk_limited
from rt_drake.retiming._jerk_set import SetGrasp
from rt_drake.retiming._jerk_timed_path import JerkTimedPath
from rt_drake.retiming._joint_path import (
    JointPath,
    PathLike,
    ToppraPath,
    as_joint_path,
)
from rt_drake.retiming._retime_errors import (
    LimitsBetweenGridPointsError,
    PathNotControllableError,
    RetimeInputError,
    RetimeStatus,
)
from rt_drake.retiming._robust_grasp import SetRows
from rt_drake.retiming._samples import (
    PathSamples,
    sample_path,
)
from rt_drake.retiming._samples import with_points as merge_samples
from rt_drake.retiming._set_tables import parameter_columns
from rt_drake.retiming._timed_path import TimedPath
from rt_drake.retiming.grid import bound_steps, initial_grid
from rt_drake.retiming.limits import (
    GRASP_ATTRIBUTES,
    GraspConstraint,
    JointLimits,
    ObjectSetGrasp,
)
from rt_drake.retiming.passes import (
    AffineConstraint,
    Engine,
    StageRows,
    XBound,
    reachability,
    stage_rows,
)
from rt_drake.retiming.seidel import kernel_array

#: Relative excess over a limit between grid points that makes the retimer
#: add a grid point there (the contract, checked at 1 kHz, is 1e-3).
BETWEEN_TOLERANCE = 5e-4
#: Rounds of grid refinement at most (each shrinks an overshoot about 4x).
MAX_REFINEMENTS = 8
#: Where a non-cubic path is checked against the position limits, in
#: fractions of each segment.
_DENSE = np.arange(1, 16) / 16
#: Rounds of cuts for the joint limits inside segments, at most, per grid;
#: then the segments still exceeded are split (a refinement).
MAX_CUT_ROUNDS = 4


@dataclasses.dataclass(frozen=True, eq=False)
class RetimeResult:
    """A retimed path.

    Attributes:
        trajectory: q(t) (Drake ``Trajectory``; q', q'' by ``EvalDerivative``);
            with jerk limits a :class:`~._jerk_timed_path.JerkTimedPath`.
        duration: s.
        gridpoints: (N+1,) grid s_i.
        sd: (N+1,) path velocity ``s'(s_i)``, 1/s (the s'(s) profile).
        sdd: (N,) constant path acceleration ``s''`` on each segment, 1/s^2;
            with jerk limits its mean over s, ``(x_{i+1} - x_i) / (2 ds_i)``.
        margin: (N+1,) smallest relative slack of all constraints at each grid
            point (1 - |value| / limit; for the grasp ``min (g - F w) / g``),
            taking the acceleration of the segment that starts there:
            positive is room left, negative over the limit (as
            :class:`~._check.TrajectoryCheck`).
        margins: The same per constraint in force (:attr:`Margin.VELOCITY`,
            :attr:`Margin.ACCELERATION`, and :attr:`Margin.TORQUE`,
            :attr:`Margin.GRASP` when limited).
        status: Always ``RetimeStatus.OK`` (failures raise ``RetimeError``).
        grasp_rows: Rows of the grasp polytope the stage LPs used (of
            ``len(grasp.g)``); for a set of objects, (row, vertex) pairs.
        repairs: Times the exactness check added rows and solved again (in
            the last solve).
        refinements: Times points were added to the grid where the torque or
            grasp was exceeded between grid points.
        grasp_objects: Objects whose rows the stage LPs used: 1 for one
            object, the vertex objects of a set (0 without a grasp).
        cuts: Rounds of cuts between grid points (joint limits; for a set of
            objects also its grasp and torques).
        path_acceleration: With jerk limits, (N+1,) ``s''(s_i)`` (continuous,
            linear in s between grid points; :mod:`._jerk_timed_path`);
            else None.
        jerk_lps: With jerk limits, the LPs solved after TOPP-RA (0 without).
    """

    trajectory: TimedPath | JerkTimedPath
    duration: float
    gridpoints: np.ndarray
    sd: np.ndarray
    sdd: np.ndarray
    margin: np.ndarray
    margins: dict[Margin, np.ndarray]
    status: RetimeStatus
    grasp_rows: int
    repairs: int
    refinements: int = 0
    grasp_objects: int = 1
    cuts: int = 0
    path_acceleration: np.ndarray | None = None
    jerk_lps: int = 0


def retime(
    plant: MultibodyPlant,
    path: PathLike,
    limits: JointLimits,
    grasp: GraspConstraint | None = None,
    gridpoints: int | np.ndarray = 100,
    *,
    sd_start: float = 0.0,
    sd_end: float = 0.0,
    start_time: float = 0.0,
    context: Context | None = None,
    engine: Engine | str = Engine.COMPILED,
    cup: CupFrame | None = None,
) -> RetimeResult:
    """Retime ``path`` time-optimally under ``limits`` and ``grasp``.

    Args:
        plant: Finalized plant of the arm and tool only (objects welded or
            left out); positions = the path's joints; frame ``suction_cup``.
        path: (K, n) waypoints (chord-length knots) or a ``GeometricPath``
            (``.waypoints``, ``.knots``), joined by the clamped cubic spline;
            or a Drake ``Trajectory`` or toppra interpolator (see
            :data:`~._joint_path.PathLike`).
        limits: Joint limits (torques limited if ``limits.torque``; with
            ``limits.jerk``, the TOPP-RA profile is then refined by LPs into
            one whose joint jerk is limited, :mod:`._jerk`).
        grasp: Held object and grasp polytope; None: no object.
        gridpoints: Number of uniform grid points in s (>= 2), to which the
            path's knots are added, points so that every piece of the path
            has at least three segments and no step is longer than 0.05 rad
            in joint space and, where the limits would be exceeded between
            grid points, more points (:mod:`.grid`); or an explicit grid,
            refined likewise.
        sd_start: Path velocity ds/dt at the start (1/s; 0 = rest).
        sd_end: Path velocity ds/dt at the end (1/s; 0 = rest).
        start_time: Time (s) at which the trajectory starts.
        context: Scratch context of ``plant``.
        engine: :attr:`Engine.COMPILED` or :attr:`Engine.TOPPRA` (see
            :mod:`rt_drake.retiming.passes`); the values ``"compiled"`` and
            ``"toppra"`` are taken too.
        cup: The cup frame C (default: the plant's ``suction_cup``); build it
            once with ``CupFrame.of(plant, ...)`` when retiming often.

    Raises:
        RetimeInputError: malformed path, limits or grid, a path that
            leaves the joint position limits, ``sd_start``, ``sd_end``
            not finite and >= 0, ``start_time`` not finite, an unknown
            ``engine``, or jerk and torque limits with the grasp of a set of
            objects.
        GraspUnstableAtRestError: gravity alone breaks the grasp somewhere.
        TorqueLimitAtRestError: holding the arm still exceeds a torque limit.
        PathNotControllableError: no admissible speed reaches the end (with
            jerk limits also: the LPs keep the speed 0 inside the path).
        LimitsBetweenGridPointsError: a limit is still exceeded between grid
            points, beyond the 1e-3 contract, after the last refinement.
    """
    _check_arguments(sd_start, sd_end, start_time)
    engine = Engine.of(engine)
    _check_objects(plant, limits, grasp, context, cup)
    spline = as_joint_path(path)  # checks the path
    n = spline.num_joints
    if n != plant.num_positions() or n != limits.num_joints:
        raise RetimeInputError(
            f"path has {n} joints but {plant.num_positions()=} and {limits.num_joints=}"
        )
    robust_jerk = limits.jerk is not None and grasp is not None and grasp.is_robust
    if robust_jerk and limits.torque is not None:
        raise RetimeInputError(
            "jerk limits with the grasp of a set of objects and torque limits are "
            "not supported: retime without torque limits or without jerk limits "
            "(limits.jerk None, --no-jerk-limits)"
        )
    if limits.jerk is not None:
        check_smooth(spline)
    context = context or plant.CreateDefaultContext()
    cup = cup or CupFrame.of(plant)
    knots = spline.breaks
    torque = limits.torque is not None
    family: ObjectRows | SetRows | None = None
    held = columns = None
    if grasp is not None and grasp.is_robust:
        assert isinstance(grasp, ObjectSetGrasp)  # the only robust kind
        family = SetRows(grasp, limits)
        columns = parameter_columns(grasp.objects)[0]
    elif grasp is not None:
        family = ObjectRows(grasp)
        held = grasp.held

    def sample(s: np.ndarray) -> PathSamples:
        return sample_path(
            plant, spline, s, limits.velocity, torque, held, context, cup, columns
        )

    def hold_at_rest(samples: PathSamples) -> None:
        if family is None or not family.robust:
            _check_torque(samples, limits)
        if family is not None:
            family.add(samples)

    samples = sample(bound_steps(initial_grid(gridpoints, knots), spline))
    check_position_limits(plant, samples, spline)
    hold_at_rest(samples)
    # The compiled passes do not need the path; toppra's TOPPRA class does.
    toppra_spline = ToppraPath(spline) if engine is Engine.TOPPRA else None
    refinements = cut_rounds = set_cut_rounds = total_cuts = 0
    cuts: StageRows | None = None
    segments = Segments(samples, knots, spline)
    joints = _joint_constraints(samples, segments, limits)
    while True:
        fixed = joints if cuts is None else [*joints, cuts]
        profile = _solve_exact(
            samples, segments, fixed, family, toppra_spline, sd_start, sd_end, engine
        )
        x, u = profile.x, profile.u
        between = normals = row_max = None
        if isinstance(family, ObjectRows):  # one object: grid points, no cuts
            normals, row_max = family.normals, profile.screen
        elif family is not None and profile.screen is not None:
            tolerance = BETWEEN_TOLERANCE if set_cut_rounds < MAX_CUT_ROUNDS else None
            between, cut = family.between(
                samples, segments, x, u, profile.screen, tolerance
            )
            if cut:  # a set of objects: held at the sub-points, solve again
                set_cut_rounds += 1
                total_cuts += 1
                continue
        points = refinement_points(
            segments, samples, x, u, limits, normals, row_max, BETWEEN_TOLERANCE,
            between,
        )  # fmt: skip
        if not points.size or refinements == MAX_REFINEMENTS:
            new_cuts = joint_cuts(segments, x, u, limits, BETWEEN_TOLERANCE)
            if new_cuts is not None and cut_rounds < MAX_CUT_ROUNDS:
                cuts = new_cuts if cuts is None else _stacked(cuts, new_cuts)
                cut_rounds += 1
                total_cuts += 1
                continue
            if new_cuts is None and not points.size:
                break  # every limit holds between grid points
            if refinements == MAX_REFINEMENTS:
                _refuse_excess(
                    segments, samples, x, u, limits, normals, row_max, between
                )
                break
            # The cuts have not converged: split the segments they are in.
            points = joint_split_points(segments, x, u, limits, BETWEEN_TOLERANCE)
        added = sample(points)
        hold_at_rest(added)
        samples = merge_samples(samples, added)
        segments = Segments(samples, knots, spline)
        joints = _joint_constraints(samples, segments, limits)
        refinements += 1
        cuts = None  # made for the old segments
        cut_rounds = set_cut_rounds = 0
    s = samples.s
    if limits.jerk is not None:
        single = grasp is not None and not isinstance(family, SetRows)
        jerk = jerk_limited(
            spline, sample, s, profile.x, limits,
            grasp.F if single and grasp is not None else None,
            grasp.g if single and grasp is not None else None,
            SetGrasp(family.normals, family.layout)
            if isinstance(family, SetRows) else None,
            sd_start, sd_end, start_time, BETWEEN_TOLERANCE,
        )  # fmt: skip
        margins = jerk.margins
        return RetimeResult(
            trajectory=jerk.trajectory,
            duration=jerk.trajectory.duration,
            gridpoints=jerk.s,
            sd=np.sqrt(jerk.x),
            sdd=np.diff(jerk.x) / (2.0 * np.diff(jerk.s)),
            margin=np.min(np.vstack(list(margins.values())), axis=0),
            margins=margins,
            status=RetimeStatus.OK,
            grasp_rows=jerk.grasp_rows,
            repairs=0 if family is None else family.repairs,
            refinements=refinements,
            grasp_objects=0 if family is None else family.object_count,
            cuts=total_cuts,
            path_acceleration=jerk.u,
            jerk_lps=jerk.lps,
        )
    trajectory = TimedPath(spline, s, profile.x, start_time)
    u = (profile.x[1:] - profile.x[:-1]) / (2.0 * np.diff(s))
    robust = isinstance(family, SetRows)
    margins = _margins(
        limits,
        samples.dq,
        samples.ddq,
        profile.x,
        u,
        None if robust else samples.torque,
    )
    if robust:
        assert isinstance(family, SetRows)
        torque_margin = family.torque_margin(samples, profile.x, u)
        if torque_margin is not None:
            margins[Margin.TORQUE] = torque_margin
    if profile.ratio is not None:
        margins[Margin.GRASP] = 1.0 - profile.ratio
    return RetimeResult(
        trajectory=trajectory,
        duration=trajectory.duration,
        gridpoints=s,
        sd=np.sqrt(np.maximum(profile.x, 0.0)),
        sdd=u,
        margin=np.min(np.vstack(list(margins.values())), axis=0),
        margins=margins,
        status=RetimeStatus.OK,
        grasp_rows=0 if family is None else family.row_count,
        repairs=0 if family is None else family.repairs,
        refinements=refinements,
        grasp_objects=0 if family is None else family.object_count,
        cuts=total_cuts,
    )


def _refuse_excess(
    segments: Segments,
    samples: PathSamples,
    x: np.ndarray,
    u: np.ndarray,
    limits: JointLimits,
    normals: np.ndarray | None,
    row_max: np.ndarray | None,
    between: np.ndarray | None,
) -> None:
    """Raise if a limit is still exceeded beyond the contract between grid points.

    Called after the last refinement; the contract is a relative excess of
    :data:`._check.DEFAULT_TOLERANCE`. An excess above
    :data:`BETWEEN_TOLERANCE` but within the contract is accepted, as the
    trajectory check accepts it.

    Raises:
        LimitsBetweenGridPointsError: naming the limit kind and where (s).
    """
    joint, s_joint = joint_excess_max(segments, x, u, limits)
    if joint > DEFAULT_TOLERANCE:
        raise LimitsBetweenGridPointsError(
            f"a joint velocity or acceleration exceeds its limit by "
            f"{100.0 * joint:.2f} % between grid points near s = {s_joint:.4f} "
            f"after {MAX_REFINEMENTS} refinements and {MAX_CUT_ROUNDS} rounds "
            f"of cuts",
            s_joint,
        )
    beyond = refinement_points(
        segments, samples, x, u, limits, normals, row_max, DEFAULT_TOLERANCE,
        between,
    )  # fmt: skip
    if beyond.size:
        raise LimitsBetweenGridPointsError(
            f"the grasp or a torque exceeds its limit by more than "
            f"{100.0 * DEFAULT_TOLERANCE:.1f} % between grid points near "
            f"s = {beyond[0]:.4f} after {MAX_REFINEMENTS} refinements",
            float(beyond[0]),
        )


def check_position_limits(
    plant: MultibodyPlant, samples: PathSamples, path: JointPath
) -> None:
    """Raise if the path leaves the plant's joint position limits anywhere.

    For a cubic path, exact: at the grid points, and at the extremes of each
    joint inside each segment, the roots in (0, 1) of the quadratic
    ``d q_j(s_i + theta ds_i) / d theta`` (every segment lies inside one
    cubic piece, :mod:`.grid`; :func:`._between_kernels.position_excess`).
    For another path, at the grid points and 15 points inside every segment.
    A tolerance of 1e-9 rad absorbs rounding.

    Raises:
        RetimeInputError: naming the joint, the value, the limit and s.
    """
    lower = plant.GetPositionLowerLimits()
    upper = plant.GetPositionUpperLimits()
    s = samples.s
    if path.cubic:
        found, j, value, at = position_excess(
            *(kernel_array(v) for v in (s, samples.q, samples.dq, samples.ddq)),
            kernel_array(lower),
            kernel_array(upper),
            1e-9,
        )
    else:
        where = np.union1d(s, (s[:-1, None] + np.diff(s)[:, None] * _DENSE).ravel())
        q = path(where)
        outside = (q < lower - 1e-9) | (q > upper + 1e-9)
        found = bool(outside.any())
        if found:
            i, j = (int(k[0]) for k in np.nonzero(outside))
            value, at = float(q[i, j]), float(where[i])
    if not found:
        return
    limit = lower[j] if value < lower[j] else upper[j]
    raise RetimeInputError(
        f"path leaves the position limits of joint {j + 1} "
        f"({_joint_name(plant, j)}) at s = {at:.3f}: {value:.4f} rad, "
        f"limit {limit:.4f} rad",
        s=float(at),
    )


def _joint_name(plant: MultibodyPlant, position_index: int) -> str:
    """The name of the joint owning position ``position_index``."""
    for index in plant.GetJointIndices():
        joint = plant.get_joint(index)
        start = joint.position_start()
        if start <= position_index < start + joint.num_positions():
            return joint.name()
    return f"position {position_index}"


def _stacked(first: StageRows, second: StageRows) -> StageRows:
    """Both sets of cuts (side by side)."""
    return StageRows(
        *(np.hstack([a, b]) for a, b in zip(first.rows, second.rows, strict=True))
    )


def _check_torque(samples: PathSamples, limits: JointLimits) -> None:
    """Check that the arm (and one held object) can be held at the samples."""
    if samples.torque is not None and limits.torque is not None:
        check_torque_at_rest(samples.s, samples.torque.c, limits.torque)


class _Profile(NamedTuple):
    """The passes' profile, checked against every grasp row.

    Attributes:
        x: (N+1,) ``s'^2`` at the grid points; u: (N,) ``s''`` per segment.
        ratio: With a grasp, ``max_k F_k w / g_k`` (N+1,) at each grid point
            (the acceleration of the segment that starts there; the last
            point takes the last one; for a set, the worst object's); else
            None.
        screen: With a grasp, what tells the grasp rows where to look between
            grid points (:class:`~._grasp_rows.Check`); else None.
    """

    x: np.ndarray
    u: np.ndarray
    ratio: np.ndarray | None
    screen: np.ndarray | None


def _joint_constraints(
    samples: PathSamples, segments: Segments, limits: JointLimits
) -> list[LinearConstraint]:
    """The joint limits: at the grid points, and inside segments.

    Velocity and acceleration at the grid points, torques, and the rows of
    :func:`~._between.interior_rows` inside the segments.
    """
    s, dq, ddq = samples.s, samples.dq, samples.ddq
    n = dq.shape[1]
    box = np.vstack([np.eye(n), -np.eye(n)])
    constraints: list[LinearConstraint] = [
        XBound(np.column_stack([np.zeros_like(s), samples.x_cap])),
        AffineConstraint(
            dq, ddq, np.zeros_like(dq), box, np.tile(limits.acceleration, 2)
        ),
        interior_rows(segments, limits),
    ]
    if (
        samples.torque is not None
        and limits.torque is not None
        and samples.torque_set is None  # a set's torques: with its grasp rows
    ):
        constraints.append(
            AffineConstraint(*samples.torque, box, np.tile(limits.torque, 2))
        )
    return constraints


def _solve_exact(
    samples: PathSamples,
    segments: Segments,
    fixed: list[LinearConstraint],
    family: ObjectRows | SetRows | None,
    spline: toppra.SplineInterpolator | None,
    sd_start: float,
    sd_end: float,
    engine: Engine,
) -> _Profile:
    """TOPP-RA with the grasp rows selected, adding missed rows until none.

    ``fixed``: every other constraint (:func:`_joint_constraints`, cuts);
    ``family``: the grasp rows (:mod:`._grasp_rows`, :mod:`._robust_grasp`).
    With a grasp the compiled engine projects ``fixed`` once for all the
    solves.
    """
    s = samples.s
    base = None
    if family is not None:
        family.begin()
        if engine is Engine.COMPILED:
            base = stage_rows(fixed, np.diff(s))
    while True:
        constraints = [] if base is not None else list(fixed)
        if family is not None:
            constraints += family.constraints(samples, segments)
        solution = reachability(constraints, spline, s, sd_start, sd_end, engine, base)
        if solution.x is None or solution.u is None:
            if family is not None and family.widen():
                continue
            where = float(s[solution.failed_stage or 0])
            raise PathNotControllableError(
                f"path not controllable from s = {where:.3f}: no admissible path "
                f"velocity there reaches the end at s' = {sd_end:g} 1/s within the "
                "limits",
                s=where,
            )
        if family is None:
            return _Profile(solution.x, solution.u, None, None)
        check = family.check(samples, segments, solution.x, solution.u)
        if not check.added:
            return _Profile(solution.x, solution.u, check.ratio, check.screen)


def _check_arguments(sd_start: float, sd_end: float, start_time: float) -> None:
    """Refuse NaN, inf or negative path velocities and a NaN start time."""
    for name, value in (("sd_start", sd_start), ("sd_end", sd_end)):
        if not (isinstance(value, (int, float, np.number)) and np.isfinite(value)):
            raise RetimeInputError(f"{name} must be a finite number, got {value!r}")
        if value < 0.0:
            raise RetimeInputError(f"{name} must be >= 0 (1/s), got {value!r}")
    if not (
        isinstance(start_time, (int, float, np.number)) and np.isfinite(start_time)
    ):
        raise RetimeInputError(f"start_time must be finite, got {start_time!r}")


def _check_objects(
    plant: object, limits: object, grasp: object, context: object, cup: object
) -> None:
    """Refuse arguments of the wrong type, naming them."""
    check = functools.partial(
        arguments.instance, where="retime", error=RetimeInputError
    )
    check(plant, "plant", MultibodyPlant)
    check(limits, "limits", JointLimits)
    if grasp is not None:
        arguments.having(
            grasp,
            "grasp",
            "GraspConstraint",
            GRASP_ATTRIBUTES,
            where="retime",
            error=RetimeInputError,
        )
    if context is not None:
        check(context, "context", Context)
    if cup is not None:
        check(cup, "cup", CupFrame)


def _margins(
    limits: JointLimits,
    dq: np.ndarray,
    ddq: np.ndarray,
    x: np.ndarray,
    u: np.ndarray,
    tau: PathCoefficients | None,
) -> dict[Margin, np.ndarray]:
    """Relative slack of the joint constraints at the grid points.

    See RetimeResult; the grasp's comes from the exactness check.
    """
    u = np.append(u, u[-1])[:, None]
    xc = x[:, None]
    out = {
        Margin.VELOCITY: 1.0
        - np.max(np.abs(dq) * np.sqrt(xc) / limits.velocity, axis=1),
        Margin.ACCELERATION: 1.0
        - np.max(np.abs(dq * u + ddq * xc) / limits.acceleration, axis=1),
    }
    if tau is not None:
        torque = tau.a * u + tau.b * xc + tau.c
        out[Margin.TORQUE] = 1.0 - np.max(np.abs(torque) / limits.torque, axis=1)
    return out


__all__ = [
    "BETWEEN_TOLERANCE",
    "MAX_CUT_ROUNDS",
    "MAX_REFINEMENTS",
    "ROW_TOLERANCE",
    "RetimeResult",
    "check_position_limits",
    "retime",
]
