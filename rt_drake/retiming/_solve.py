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

This module holds the algorithm, :func:`retime`'s loop of solves and
refinements; :mod:`._retime_inputs` checks its arguments,
:mod:`._position_limits` the path against the position limits,
:mod:`._exact_solve` is one solve exact for every grasp row and
:mod:`._retime_result` assembles :class:`RetimeResult`.
"""

from __future__ import annotations

import numpy as np
from pydrake.multibody.plant import MultibodyPlant
from pydrake.systems.framework import Context

from rt_drake.dynamics.cup_frame import CupFrame
from rt_drake.retiming._at_rest import check_torque_at_rest
from rt_drake.retiming._between import refinement_points
from rt_drake.retiming._between_refusal import refuse_excess
from rt_drake.retiming._exact_solve import (
    joint_constraints,
    solve_exact,
    stacked_cuts,
)
from rt_drake.retiming._grasp_rows import (
    ROW_TOLERANCE,
    ObjectRows,
)
from rt_drake.retiming._jerk import check_smooth, jerk_limited
from rt_drake.retiming._jerk_set import SetGrasp
from rt_drake.retiming._joint_cuts import joint_cuts, joint_split_points
from rt_drake.retiming._joint_path import (
    PathLike,
    ToppraPath,
    as_joint_path,
)
from rt_drake.retiming._position_limits import check_position_limits
from rt_drake.retiming._retime_errors import RetimeInputError
from rt_drake.retiming._retime_inputs import (
    check_arguments,
    check_jerk_start,
    check_objects,
)
from rt_drake.retiming._retime_result import (
    RetimeResult,
    jerk_result,
    profile_result,
)
from rt_drake.retiming._robust_grasp import SetRows
from rt_drake.retiming._samples import (
    PathSamples,
    sample_path,
)
from rt_drake.retiming._samples import with_points as merge_samples
from rt_drake.retiming._segments import Segments
from rt_drake.retiming._set_tables import parameter_columns
from rt_drake.retiming.grid import bound_steps, initial_grid
from rt_drake.retiming.limits import (
    GraspConstraint,
    JointLimits,
    ObjectSetGrasp,
)
from rt_drake.retiming.passes import Engine, StageRows

#: Relative excess over a limit between grid points that makes the retimer
#: add a grid point there (the contract, checked at 1 kHz, is 1e-3).
BETWEEN_TOLERANCE = 5e-4
#: Rounds of grid refinement at most (each shrinks an overshoot about 4x).
MAX_REFINEMENTS = 8
#: Rounds of cuts for the joint limits inside segments, at most, per grid;
#: then the segments still exceeded are split (a refinement).
MAX_CUT_ROUNDS = 4


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
    jerk_start: RetimeResult | None = None,
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
        jerk_start: With jerk limits: an earlier jerk-limited retime of the
            same path, whose ``s'^2`` (linear between its grid points) the
            LPs start from instead of TOPP-RA's profile (on a finer grid,
            from the profile they already found; the result may still be
            longer: keep the shorter). None: TOPP-RA's.

    Raises:
        RetimeInputError: malformed path, limits or grid, a path that
            leaves the joint position limits, ``sd_start``, ``sd_end``
            not finite and >= 0, ``start_time`` not finite, an unknown
            ``engine``.
        GraspUnstableAtRestError: gravity alone breaks the grasp somewhere.
        TorqueLimitAtRestError: holding the arm still exceeds a torque limit.
        PathNotControllableError: no admissible speed reaches the end (with
            jerk limits also: the LPs keep the speed 0 inside the path).
        LimitsBetweenGridPointsError: a limit is still exceeded between grid
            points, beyond the 1e-3 contract, after the last refinement.
    """
    check_arguments(sd_start, sd_end, start_time)
    engine = Engine.of(engine)
    check_objects(plant, limits, grasp, context, cup)
    if jerk_start is not None:
        check_jerk_start(jerk_start, limits.jerk)
    spline = as_joint_path(path)  # checks the path
    n = spline.num_joints
    if n != plant.num_positions() or n != limits.num_joints:
        raise RetimeInputError(
            f"path has {n} joints but {plant.num_positions()=} and {limits.num_joints=}"
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
    joints = joint_constraints(samples, segments, limits)
    while True:
        fixed = joints if cuts is None else [*joints, cuts]
        profile = solve_exact(
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
                cuts = new_cuts if cuts is None else stacked_cuts(cuts, new_cuts)
                cut_rounds += 1
                total_cuts += 1
                continue
            if new_cuts is None and not points.size:
                break  # every limit holds between grid points
            if refinements == MAX_REFINEMENTS:
                refuse_excess(
                    segments, samples, x, u, limits, normals, row_max, between,
                    MAX_REFINEMENTS, MAX_CUT_ROUNDS,
                )  # fmt: skip
                break
            # The cuts have not converged: split the segments they are in.
            points = joint_split_points(segments, x, u, limits, BETWEEN_TOLERANCE)
        added = sample(points)
        hold_at_rest(added)
        samples = merge_samples(samples, added)
        segments = Segments(samples, knots, spline)
        joints = joint_constraints(samples, segments, limits)
        refinements += 1
        cuts = None  # made for the old segments
        cut_rounds = set_cut_rounds = 0
    s = samples.s
    if limits.jerk is not None:
        single = grasp is not None and not isinstance(family, SetRows)
        x_first = profile.x if jerk_start is None else _start_profile(jerk_start, s)
        jerk = jerk_limited(
            spline, sample, s, x_first, limits,
            grasp.F if single and grasp is not None else None,
            grasp.g if single and grasp is not None else None,
            SetGrasp(family.normals, family.layout, family.torque_normals)
            if isinstance(family, SetRows) else None,
            sd_start, sd_end, start_time, BETWEEN_TOLERANCE,
        )  # fmt: skip
        return jerk_result(jerk, family, refinements, total_cuts)
    return profile_result(
        spline, samples, profile, limits, family, start_time, refinements, total_cuts
    )


def _start_profile(start: RetimeResult, s: np.ndarray) -> np.ndarray:
    """``start``'s ``s'^2`` at ``s`` (1/s^2), linear between its grid points."""
    return np.interp(s, start.gridpoints, start.sd**2)


def _check_torque(samples: PathSamples, limits: JointLimits) -> None:
    """Check that the arm (and one held object) can be held at the samples."""
    if samples.torque is not None and limits.torque is not None:
        check_torque_at_rest(samples.s, samples.torque.c, limits.torque)


__all__ = [
    "BETWEEN_TOLERANCE",
    "MAX_CUT_ROUNDS",
    "MAX_REFINEMENTS",
    "ROW_TOLERANCE",
    "RetimeResult",
    "check_position_limits",
    "retime",
]
