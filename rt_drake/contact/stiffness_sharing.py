"""The wrench set of a tool of compliant cups that split the load by stiffness.

Bellows cups (:class:`~rt_drake.contact.CupStiffness`) on a rigid tool hold
a rigid object in parallel: the tool does not choose how the cups share the
load, their springs do. The object, displaced on the tool by a small twist
``d = [theta; x]`` (about T's origin, in T), deflects cup i at its frame C_i
by ``Ad_i^T d`` (``Ad_i = [[R, [p]x R], [0, R]]``, :meth:`CupMount.adjoint`:
``w_T = Ad_i w_C``), so cup i puts on the object, about C_i's origin in C_i,
``w_Ci = K_Ci Ad_i^T d`` (``K_Ci`` its 6x6 stiffness,
:meth:`~rt_drake.contact.CupStiffness.matrix`). The cups together carry the
whole wrench, ``w = sum_i Ad_i w_Ci = K d`` with ``K = sum_i Ad_i K_Ci
Ad_i^T``, so each cup's share is linear in w:

    w_Ci = S_i w,   S_i = K_Ci Ad_i^T K^-1          (sum_i Ad_i S_i = I).

The split is of the whole wrench ``[torque; force]``: shear and torsion
(friction) as well as the normal load and the tilting moments, which the
rims' equal springs of :mod:`rt_drake.contact.load_sharing` split alone.
At zero load the bellows carry nothing: each cup's suction and its rim's
push cancel, which is how the suction enters its set W_c. Then the grasp
holds when every cup's share lies in its own set, ``F_c w_Ci <= g_c``
(W_c: the exact rim set with its suction offset, and a compliant lip's peel
rows where the cup states ``peel_fraction``,
:func:`~rt_drake.contact.cached_wrench_polytope`):

    W_stiffness = {w : F_ci S_i w <= g_ci  for every cup i},

the rows stacked over the cups, unit-normed, so ``F w - g`` is a signed
distance in raw wrench units. One cup: ``S = Ad^-1``, the cup's own W_c
moved to T, whatever its stiffness. Conventions: wrenches ``[torque;
force]`` (N m, N) the cups exert on the object, about T's origin, in T.
"""

from __future__ import annotations

import numpy as np

from rt_drake import arguments
from rt_drake.contact._cache import cached_wrench_polytope
from rt_drake.contact.load_sharing import SharedLoadSet
from rt_drake.contact.tool import ToolParameterError, ToolParameters


def stiffness_split(tool: ToolParameters) -> np.ndarray:
    """Return ``S`` (n, 6, 6): cup i's wrench ``w_Ci = S[i] w`` (module docstring).

    ``w`` about T's origin in T; ``w_Ci`` about C_i's origin in C_i.

    Raises:
        ToolParameterError: a cup without a stated ``stiffness``.
    """
    arguments.instance(tool, "tool", ToolParameters, where="stiffness_split")
    tool.validate()
    stiffness = []
    for i, mount in enumerate(tool.cups):
        if mount.stiffness is None:
            raise ToolParameterError(
                f"cup {i}: load sharing 'stiffness' needs the cup's stiffness "
                "(axial, lateral, tilt, torsion), got none"
            )
        stiffness.append(mount.stiffness.matrix())
    adjoints = [mount.adjoint() for mount in tool.cups]
    K = sum(Ad @ K_C @ Ad.T for Ad, K_C in zip(adjoints, stiffness, strict=True))
    K_inv = np.linalg.inv(K)
    return np.array(
        [K_C @ Ad.T @ K_inv for Ad, K_C in zip(adjoints, stiffness, strict=True)]
    )


def stiffness_shared_polytope(tool: ToolParameters) -> tuple[np.ndarray, np.ndarray]:
    """Return ``(F, g)``: W_stiffness of ``tool`` as unit rows ``F w <= g``.

    Rows ``F_ci S_i w <= g_ci`` for every cup i (module docstring), each
    cup's W_c from :func:`~rt_drake.contact.cached_wrench_polytope` (computed
    once per cup model); exact duplicates dropped.

    Raises:
        ToolParameterError: see :func:`stiffness_split`.
    """
    arguments.instance(tool, "tool", ToolParameters, where="stiffness_shared_polytope")
    split = stiffness_split(tool)
    rows, offsets = [], []
    for mount, S in zip(tool.cups, split, strict=True):
        own = cached_wrench_polytope(mount.cup)
        rows.append(own.F @ S)
        offsets.append(own.g)
    F, g = np.vstack(rows), np.concatenate(offsets)
    norms = np.linalg.norm(F, axis=1)
    F, g = F / norms[:, None], g / norms
    keep = np.unique(np.round(np.column_stack([F, g]), 12), axis=0, return_index=True)[
        1
    ]
    keep.sort()
    return F[keep], g[keep]


def stiffness_shared_set(tool: ToolParameters) -> SharedLoadSet:
    """W_stiffness of ``tool``: its rows and a membership test (milliseconds).

    A :class:`~rt_drake.contact.SharedLoadSet` (a tool's set under a load
    split), so it goes wherever the elastic set goes.
    """
    arguments.instance(tool, "tool", ToolParameters, where="stiffness_shared_set")
    F, g = stiffness_shared_polytope(tool)
    return SharedLoadSet(cup=tool, F=F, g=g)


__all__ = ["stiffness_shared_polytope", "stiffness_shared_set", "stiffness_split"]
