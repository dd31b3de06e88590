"""Objects the robot does not know exactly: inertial sets and their samples.

- :mod:`.inertial_set`: the set of an object's possible inertial parameters.
- :mod:`.object_samples`: objects drawn from that set (for checks and sweeps).
"""
