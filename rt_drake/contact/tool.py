"""Multi-cup tools: N suction cups mounted on one tool frame T.

Cup i is a :class:`~rt_drake.contact._cup.CupParameters` with its own frame
C_i (origin at the centre of the contact face, +z out of the cup into the
object, see :mod:`rt_drake.contact._cup`), posed in the tool frame T by the
rotation ``R_TCi`` and the position ``p_TCi`` (m) of C_i's origin.

A wrench is ``w = [torque; force]`` (N*m, N) exerted by the cups ON THE
OBJECT. A wrench ``w_C`` of cup i (about C_i's origin, in C_i) is, about T's
origin and in T,

    f_T = R_TC f_C,    tau_T = R_TC tau_C + p_TC x (R_TC f_C),

i.e. ``w_T = Ad_i w_C`` with ``Ad_i = [[R, [p]x R], [0, R]]`` (Drake's
``SpatialForce`` re-expressed in T and shifted to T's origin).
"""

# No ``from __future__ import annotations``: a scenario loader may read the
# dataclass field types, which must be real types, not strings.
import dataclasses
import enum

import numpy as np

from rt_drake.contact._cup import CupParameters
from rt_drake.contact.cup_stiffness import CupStiffness
from rt_drake.errors import InputError

#: Largest ``|R R^T - I|`` (max entry) and ``|det R - 1|`` accepted for R_TC.
ROTATION_TOLERANCE = 1e-9


class ToolParameterError(InputError):
    """A multi-cup tool is described wrongly; the message names the value."""


def _rotation(value: object) -> np.ndarray:
    """Return ``value`` as a read-only (3, 3) rotation matrix, or raise."""
    try:
        R = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ToolParameterError(f"R_TC must be a 3x3 matrix, got {value!r}") from None
    if R.shape != (3, 3):
        raise ToolParameterError(f"R_TC must be a 3x3 matrix, got shape {R.shape}")
    if not np.all(np.isfinite(R)):
        raise ToolParameterError(f"R_TC must be finite, got {R.tolist()}")
    error = float(np.abs(R @ R.T - np.eye(3)).max())
    determinant = float(np.linalg.det(R))
    if error > ROTATION_TOLERANCE or abs(determinant - 1.0) > ROTATION_TOLERANCE:
        raise ToolParameterError(
            f"R_TC must be a rotation (orthonormal, det +1), got "
            f"max|R R^T - I| = {error:.3g}, det = {determinant:.6g}"
        )
    R.setflags(write=False)
    return R


def _position(value: object) -> np.ndarray:
    """Return ``value`` as a read-only finite (3,) position in m, or raise."""
    try:
        p = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ToolParameterError(f"p_TC must be 3 numbers, got {value!r}") from None
    if p.shape != (3,) or not np.all(np.isfinite(p)):
        raise ToolParameterError(
            f"p_TC must be 3 finite numbers (m), got {np.asarray(value).tolist()}"
        )
    p.setflags(write=False)
    return p


@dataclasses.dataclass(frozen=True, eq=False)
class CupMount:
    """One cup of a tool and its pose in the tool frame T.

    Attributes:
        cup: The cup's point-contact model.
        R_TC: (3, 3) rotation of the cup frame C in T (read-only array).
        p_TC: (3,) position of C's origin in T, m (read-only array).
        stiffness: The bellows' stiffness about C's origin, in C, for
            ``LoadSharing.STIFFNESS`` (:mod:`rt_drake.contact.stiffness_sharing`);
            None: not stated (a rigid cup). Not part of the cup's wrench set,
            so :meth:`as_dict` (the cache key) leaves it out.
    """

    cup: CupParameters
    R_TC: np.ndarray = dataclasses.field(default_factory=lambda: np.eye(3))
    p_TC: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(3))
    stiffness: CupStiffness | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.cup, CupParameters):
            raise ToolParameterError(
                f"cup must be a CupParameters, got {type(self.cup).__name__}"
            )
        object.__setattr__(self, "R_TC", _rotation(self.R_TC))
        object.__setattr__(self, "p_TC", _position(self.p_TC))
        if self.stiffness is not None and not isinstance(self.stiffness, CupStiffness):
            raise ToolParameterError(
                f"stiffness must be a CupStiffness or None, got "
                f"{type(self.stiffness).__name__}"
            )

    def adjoint(self) -> np.ndarray:
        """Return ``Ad = [[R, [p]x R], [0, R]]`` (6, 6): w_C -> w_T."""
        R, p = self.R_TC, self.p_TC
        cross = np.array([[0.0, -p[2], p[1]], [p[2], 0.0, -p[0]], [-p[1], p[0], 0.0]])
        adjoint = np.zeros((6, 6))
        adjoint[:3, :3] = adjoint[3:, 3:] = R
        adjoint[:3, 3:] = cross @ R
        return adjoint

    def as_dict(self) -> dict[str, object]:
        """Return the cup's fields and the pose as plain Python numbers."""
        return {
            **self.cup.as_dict(),
            "R_TC": self.R_TC.tolist(),
            "p_TC": self.p_TC.tolist(),
        }


@dataclasses.dataclass(frozen=True, eq=False)
class ToolParameters:
    """A tool carrying one or more suction cups.

    Attributes:
        cups: The cups and their poses in the tool frame T (at least one).
    """

    cups: tuple[CupMount, ...]

    def __post_init__(self) -> None:
        cups = tuple(self.cups) if isinstance(self.cups, (list, tuple)) else None
        if cups is None:
            raise ToolParameterError(
                f"cups must be a list of CupMount, got {type(self.cups).__name__}"
            )
        if not cups:
            raise ToolParameterError("a tool needs at least one cup, got 0")
        for i, mount in enumerate(cups):
            if not isinstance(mount, CupMount):
                raise ToolParameterError(
                    f"cup {i}: expected a CupMount, got {type(mount).__name__}"
                )
        object.__setattr__(self, "cups", cups)
        self.validate()

    @classmethod
    def single(cls, cup: CupParameters) -> "ToolParameters":
        """Return the tool of one cup whose frame is the tool frame."""
        return cls(cups=(CupMount(cup),))

    def validate(self) -> None:
        """Raise ToolParameterError naming the first bad cup and value.

        Cups are mutable, so this re-checks every cup's parameters (and the
        poses, which are read-only arrays checked at construction).
        """
        for i, mount in enumerate(self.cups):
            try:
                mount.cup.validate()
                _rotation(mount.R_TC)
                _position(mount.p_TC)
            except ValueError as error:
                message = str(error).removeprefix("cup ")
                raise ToolParameterError(f"cup {i}: {message}") from None

    @property
    def length_scale(self) -> float:
        """Return ``max_i |p_TCi| + r_i`` (m): the lever arm of the rim forces.

        For one cup at T's origin this is its radius.
        """
        return max(float(np.linalg.norm(m.p_TC)) + m.cup.radius for m in self.cups)

    def as_dict(self) -> dict[str, object]:
        """Return ``{"cups": [...]}`` with every cup's fields and pose."""
        return {"cups": [mount.as_dict() for mount in self.cups]}


class LoadSharing(enum.Enum):
    """How the cups of a tool split the load between them.

    ``ELASTIC``: rigid tool and object on equal rim springs
    (:mod:`rt_drake.contact.load_sharing`; the default for several cups).
    ``ANY``: any split the cups' sets allow (the Minkowski sum of
    :func:`~rt_drake.contact.tool_wrench_polytope`); it over-claims for a
    rigid tool: the two-cup carton slipped in 8 of 20 simulated transports
    retimed under it.
    ``STIFFNESS``: compliant (bellows) cups on a rigid tool split the whole
    wrench by their stated stiffness, and each cup's share must lie in its
    own set (:mod:`rt_drake.contact.stiffness_sharing`; every cup states
    its :class:`~rt_drake.contact.CupStiffness`).
    """

    ELASTIC = "elastic"
    ANY = "any"
    STIFFNESS = "stiffness"


def refuse_peel(tool: ToolParameters, sharing: LoadSharing) -> None:
    """Raise ToolParameterError if a cup of a tool of several states a peel limit.

    A cup's ``peel_fraction`` bounds the tilting moment that cup carries.
    ``LoadSharing.STIFFNESS`` gives each cup its share ``S_i w`` and keeps
    it in the cup's own set, peel rows included; ``ELASTIC`` and ``ANY``
    have no per-cup moment to bound, so they refuse it. One cup: its own set.
    """
    if len(tool.cups) == 1:
        return
    for i, mount in enumerate(tool.cups):
        if mount.cup.peel_fraction is not None:
            raise ToolParameterError(
                f"cup {i}: peel_fraction {mount.cup.peel_fraction!r} needs load "
                f"sharing 'stiffness' (each cup's share in its own set, peel rows "
                f"and all); '{sharing.value}' has no peel rows for a tool of "
                f"{len(tool.cups)} cups"
            )


def is_identity_pose(mount: CupMount) -> bool:
    """Return True if the cup frame is exactly the tool frame."""
    return bool(np.array_equal(mount.R_TC, np.eye(3)) and not np.any(mount.p_TC))
