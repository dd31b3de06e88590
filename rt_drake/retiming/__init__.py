"""Internals of :func:`rt_drake.retime.retime` (TOPP-RA under grasp stability).

- :mod:`.path`: the joint path ``q(s)`` in the planner's spline convention.
- :mod:`.limits`: joint limits and the grasp constraint ``F w <= g``.
- :mod:`.at_rest`: the object and the arm must be holdable at rest.
- :mod:`.rows`: which grasp rows the stage LPs get, and the exactness check
  (compiled).
- :mod:`.passes`: TOPP-RA's passes on precomputed constraints.
- :mod:`.seidel`: toppra's seidel LP and the passes, compiled with numba.
- :mod:`.warm`: compiles the kernels before anything is timed.
- :mod:`.timed_path`: the retimed trajectory as a Drake ``Trajectory``.
- :mod:`.check`: dense (1 kHz) verification of a timed trajectory.
- :mod:`.errors`: typed errors and statuses.
"""
