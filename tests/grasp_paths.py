"""Joint paths the retiming tests share (rad).

``BACK``: a MOVE-like swing from the VS-060's home on which the notebook's
grasp binds (retimed without the grasp, the notebook slips by 20 %:
tests/retiming/test_solve.py).
"""

from __future__ import annotations

import numpy as np

#: The VS-060's home configuration (rad), the shipped scenarios' ``robot.home``.
HOME = np.array([0.0, 0.35, 1.75, 0.0, 1.04, 0.0])
BACK = np.array(
    [
        HOME,
        HOME + [-0.4, 0.1, -0.2, 0.0, 0.1, -0.5],
        HOME + [-1.2, -0.1, 0.2, 0, -0.1, -0.8],
    ]
)
