"""rt_drake: critically fast suction-cup pick-and-place on Drake.

The package is layered so that data flows one way:
scenario -> plant -> (IK, planner) -> path -> (dynamics + grasp constraint)
-> retimer -> trajectory -> diagram simulation -> report.
The pure maths (``rt_drake.contact``) imports no Drake.
"""

__version__ = "0.1.0"
