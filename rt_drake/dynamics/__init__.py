"""The held object's wrench along a path: kinematics and Newton-Euler in the cup frame.

- :mod:`.chain` (kernels in :mod:`.chain_kernels`, numba): the one forward
  kinematics of rt_drake, a serial chain from the world to a body, batched;
  for the cup with the Jacobian's axes (the retimer's and the optimiser's).
- :mod:`.body_kinematics`: every robot body's pose at thousands of samples at
  once, each body's chain through the same kernel (the planner's dense
  collision check).
- :mod:`.cup_frame`: the cup frame C of a plant, looked up once.
- :mod:`.bellows_modes`: the modes of an object held by a tool of bellows
  cups (stiffness, damping, inertia, periods) and the wrench they carry
  under a load (``bellows_wrench``): the simulation's bellows checks and
  the retimer's ring margin share them.
- :mod:`.wrench`: the object wrench and joint torques along a path, Drake's
  route; :mod:`.newton_euler` the equations; :mod:`.regressor` the wrench as
  linear in the object's inertial parameters.
"""
