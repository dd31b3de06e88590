"""Suction-cup grasp stability (paper Section II): numpy, scipy and cdd only.

Conventions (details in :mod:`rt_drake.contact._cup`): cup frame C at the
centre of the contact face, +z out of the cup into the object; a wrench is
``w = [torque; force]`` (N*m, N) that the cup exerts on the object, about C's
origin, expressed in C. The grasp is stable when ``F w <= g``.

- :class:`CupParameters`: the point-contact model of the cup.
- :func:`contact_wrench_polytope`: the exact set W_c (minimal H-rep and
  vertices); :func:`cached_wrench_polytope` stores it on disk.
- :class:`ToolParameters`: a tool of several cups, each a
  :class:`CupMount` (cup and pose in the tool frame T);
  :func:`tool_wrench_polytope`: its exact set W_T, about T's origin, in T
  (also cached by :func:`cached_wrench_polytope`), which lets the cups
  split the load in any way; :class:`SharedLoadSet` (``LoadSharing``
  ``elastic``): the set when the cups share it as equal springs, which a
  rigid tool does (:func:`shared_load_residual`: its independent LP);
  :func:`stiffness_shared_set` (``stiffness``): the set when compliant
  cups, each with its :class:`CupStiffness`, split the whole wrench by
  their stiffness and each cup's share lies in its own W_c.
- :func:`is_realizable` (H-rep), :func:`is_realizable_lp` (independent LP,
  for a cup or a tool).
- :func:`guided_approximation`: the paper's inner approximation.
- :func:`worst_cup_polytope`: the wrenches every cup of a friction and
  suction range can exert (``friction_min``, ``suction_force_min``).
- :func:`peel_rows`: a compliant lip's peel limit (``peel_fraction``),
  rows on the tilting moment that W_c of such a cup includes.

Only :mod:`rt_drake.contact._cup`, :mod:`rt_drake.contact.cup_stiffness` and
:mod:`rt_drake.contact.tool` (numpy) are imported with the package, so a
scenario can name ``CupParameters`` and ``ToolParameters`` cheaply; the
rest (scipy) loads on first use of its names.
"""

from typing import TYPE_CHECKING

from rt_drake._lazy import lazy_attributes
from rt_drake.contact._cup import (
    CupParameters,
    grasp_matrices,
    suction_wrench,
)
from rt_drake.contact.cup_stiffness import CupStiffness
from rt_drake.contact.tool import (
    CupMount,
    LoadSharing,
    ToolParameterError,
    ToolParameters,
)

if TYPE_CHECKING:  # the lazy names below, for type checkers
    from rt_drake.contact._adjacency import TooManyFacetsError
    from rt_drake.contact._cache import (
        cache_path,
        cached_wrench_polytope,
        default_cache_dir,
        load_polytope,
        save_polytope,
    )
    from rt_drake.contact._lp import (
        is_realizable_lp,
        lp_residual,
        shared_load_residual,
    )
    from rt_drake.contact._samplers import object_wrench_sampler
    from rt_drake.contact.approximation import (
        GuidedApproximation,
        guided_approximation,
    )
    from rt_drake.contact.load_sharing import SharedLoadSet, shared_load_polytope
    from rt_drake.contact.peel import peel_rows
    from rt_drake.contact.stiffness_sharing import (
        stiffness_shared_polytope,
        stiffness_shared_set,
        stiffness_split,
    )
    from rt_drake.contact.tool_polytope import (
        ToolWrenchSet,
        tool_summands,
        tool_symmetry,
        tool_wrench_polytope,
    )
    from rt_drake.contact.worst_cup import worst_cup_polytope
    from rt_drake.contact.wrench_polytope import (
        WrenchPolytope,
        contact_wrench_polytope,
        is_realizable,
        with_suction_force,
    )

#: Public name -> submodule defining it, imported on first access.
_LAZY = {
    "GuidedApproximation": "approximation",
    "guided_approximation": "approximation",
    "cache_path": "_cache",
    "cached_wrench_polytope": "_cache",
    "default_cache_dir": "_cache",
    "load_polytope": "_cache",
    "save_polytope": "_cache",
    "is_realizable_lp": "_lp",
    "lp_residual": "_lp",
    "shared_load_residual": "_lp",
    "SharedLoadSet": "load_sharing",
    "shared_load_polytope": "load_sharing",
    "object_wrench_sampler": "_samplers",
    "peel_rows": "peel",
    "stiffness_shared_polytope": "stiffness_sharing",
    "stiffness_shared_set": "stiffness_sharing",
    "stiffness_split": "stiffness_sharing",
    "WrenchPolytope": "wrench_polytope",
    "contact_wrench_polytope": "wrench_polytope",
    "is_realizable": "wrench_polytope",
    "with_suction_force": "wrench_polytope",
    "TooManyFacetsError": "_adjacency",
    "ToolWrenchSet": "tool_polytope",
    "tool_summands": "tool_polytope",
    "tool_symmetry": "tool_polytope",
    "tool_wrench_polytope": "tool_polytope",
    "worst_cup_polytope": "worst_cup",
}

__all__ = [
    "CupMount",
    "CupParameters",
    "CupStiffness",
    "GuidedApproximation",
    "LoadSharing",
    "SharedLoadSet",
    "ToolParameterError",
    "ToolParameters",
    "ToolWrenchSet",
    "TooManyFacetsError",
    "WrenchPolytope",
    "cache_path",
    "cached_wrench_polytope",
    "contact_wrench_polytope",
    "default_cache_dir",
    "grasp_matrices",
    "guided_approximation",
    "is_realizable",
    "is_realizable_lp",
    "load_polytope",
    "lp_residual",
    "object_wrench_sampler",
    "peel_rows",
    "save_polytope",
    "shared_load_polytope",
    "shared_load_residual",
    "stiffness_shared_polytope",
    "stiffness_shared_set",
    "stiffness_split",
    "suction_wrench",
    "tool_summands",
    "tool_symmetry",
    "tool_wrench_polytope",
    "with_suction_force",
    "worst_cup_polytope",
]


__getattr__, __dir__ = lazy_attributes(
    __name__, {name: f"{__name__}.{module}" for name, module in _LAZY.items()}, __all__
)
