"""The family of MOVE paths the search explores.

A path is the planner's clamped chord-length spline (rad, s in [0, 1])
through the waypoints::

    q_grasp, up_1 .. up_m, v_1 .. v_K, down_m .. down_1, q_place

- ``up_k``: the cup raised straight up from its grasp pose X_WC(q_grasp) by
  ``k h / m`` (m), same orientation, solved by Newton's method from the
  previous one; ``down_k`` likewise above the place pose. They fix the
  vertical end segments: the spline's end slopes are zero and it passes
  through points 1 cm apart on the vertical line.
- ``v_k = r_k + D x_k``: free via points; ``r_k`` the corners of the
  planner's spline path (:func:`corners`: for a MOVE, the top of the lift
  and the point above the place), ``x_k`` (n,) the search's parameters and
  ``D = diag(scale)`` (rad per unit). ``x = 0`` is the planner's path with
  short vertical ends.
- A pick's path (:meth:`PathFamily.between_lines`) keeps the planner's own
  lines instead: ``q_grasp, up_1 .. up_m`` are the retreat's IK points
  from the placed object (none without a retreat), ``down_m .. down_1,
  q_place`` the descent's from the approach pose to the grasp, and only the
  transit between them is searched.
- With ``vertical=True`` each via point is projected onto the configurations
  whose cup axis points down (Gauss-Newton on the horizontal part of ``z_C -
  d``, d the unit gravity direction), for ``max_tilt_deg = 0``.
"""

from __future__ import annotations

import numpy as np

from rt_drake.errors import RtDrakeError
from rt_drake.shaping.cup_chain import CupChain
from rt_drake.types.path import GeometricPath


class FamilyError(RtDrakeError):
    """A vertical end segment could not be solved (the search keeps the spline)."""


def corners(
    path: GeometricPath,
    count: int,
    samples: int = 200,
    span: tuple[float, float] = (0.0, 1.0),
) -> np.ndarray:
    """The ``count`` configurations (count, n) where ``path`` turns most.

    Douglas-Peucker in joint space over ``s in span``: from the chord
    q(s_0) -> q(s_1), repeatedly add the sample farthest (2-norm, rad) from
    the polyline so far; returned in path order. A straight path gets evenly
    spaced samples.
    """
    s = np.linspace(*span, samples)
    q = path.value(s)
    chosen = [0, samples - 1]
    for _ in range(count):
        best, best_distance = None, 0.0
        for a, b in zip(chosen[:-1], chosen[1:], strict=True):
            if b - a < 2:
                continue
            chord = q[b] - q[a]
            offset = q[a + 1 : b] - q[a]
            t = np.clip(offset @ chord / max(chord @ chord, 1e-18), 0.0, 1.0)
            distance = np.linalg.norm(offset - t[:, None] * chord, axis=1)
            k = int(np.argmax(distance))
            if distance[k] > best_distance:
                best, best_distance = a + 1 + k, distance[k]
        if best is None:
            break
        chosen = sorted([*chosen, best])
    inner = chosen[1:-1]
    spread = np.linspace(0, samples - 1, count + 2)[1:-1].astype(int)
    inner = sorted({*inner, *spread})[:count] if len(inner) < count else inner
    return q[np.array(inner)]


class PathFamily:
    """Waypoints of the family's paths from parameters x (P, K n).

    Args:
        chain: Batched kinematics of the arm.
        q_grasp, q_place: First and last configurations (rad).
        reference: (K, n) configurations the via points start from.
        vertical_height: h (m), length of each vertical end segment.
        vertical_points: m, waypoints on each vertical segment.
        scale: (n,) rad per unit of x for each joint.
        vertical: Project the via points onto a vertical cup.

    Raises:
        FamilyError: Newton's method failed on a vertical segment.
    """

    def __init__(
        self,
        chain: CupChain,
        q_grasp: np.ndarray,
        q_place: np.ndarray,
        reference: np.ndarray,
        vertical_height: float,
        vertical_points: int,
        scale: np.ndarray,
        vertical: bool = False,
    ) -> None:
        self.chain = chain
        self.q_grasp = np.asarray(q_grasp, float)
        self.q_place = np.asarray(q_place, float)
        self.scale = np.asarray(scale, float)
        self.vertical = vertical
        self.up, down = self._vertical_lines(vertical_height, vertical_points)
        self.down = down[::-1]
        reference = np.asarray(reference, float)
        self.reference = self.project_vertical(reference) if vertical else reference
        self.dim = self.reference.size

    @classmethod
    def between_lines(
        cls,
        chain: CupChain,
        head: np.ndarray,
        tail: np.ndarray,
        reference: np.ndarray,
        scale: np.ndarray,
    ) -> PathFamily:
        """The paths from the line ``head`` to the line ``tail`` (a pick's).

        Args:
            chain: Batched kinematics of the arm.
            head: (1 + m, n) the path's first configuration and the IK points
                of the line it leaves along (the retreat; only the first
                without one).
            tail: (m' + 1, n) the IK points of the line it ends along (the
                descent, from its top to the grasp).
            reference: (K, n) configurations the via points start from.
            scale: (n,) rad per unit of x for each joint.
        """
        family = cls.__new__(cls)
        family.chain = chain
        family.q_grasp = np.asarray(head[0], float)
        family.q_place = np.asarray(tail[-1], float)
        family.scale = np.asarray(scale, float)
        family.vertical = False
        family.up = np.asarray(head[1:], float)
        family.down = np.asarray(tail[:-1], float)
        family.reference = np.asarray(reference, float)
        family.dim = family.reference.size
        return family

    @property
    def tops(self) -> np.ndarray:
        """(2, n): where the path leaves its first line and joins its last."""
        first = self.up[-1] if len(self.up) else self.q_grasp
        last = self.down[0] if len(self.down) else self.q_place
        return np.array([first, last])

    def _vertical_lines(self, height: float, count: int) -> np.ndarray:
        """(2, count, n): the points up from the grasp and up from the place.

        Newton's method for all of them at once, each seeded at its end.
        """
        ends = np.array([self.q_grasp, self.q_place])
        R, p = self.chain.cup_pose(ends)
        up = -self.chain.gravity_W / np.linalg.norm(self.chain.gravity_W)
        h = height * np.arange(1, count + 1) / count
        targets = p[:, None, :] + h[None, :, None] * up
        R_targets = np.broadcast_to(R[:, None], (2, count, 3, 3))
        seeds = np.broadcast_to(ends[:, None], (2, count, len(self.q_grasp)))
        q, error = self.chain.solve_pose(R_targets, targets, seeds, iterations=20)
        if error.max() > 1e-8:
            _, k = np.unravel_index(int(np.argmax(error)), error.shape)
            raise FamilyError(
                f"cup pose {1e3 * h[k]:.0f} mm above an end of the MOVE unreachable "
                f"by Newton's method (pose error {error.max():.1e})"
            )
        return q

    def project_vertical(self, q: np.ndarray, iterations: int = 4) -> np.ndarray:
        """Configurations near q (..., n) with the cup axis along gravity.

        ``e(q) = B^T (z_C - d)`` with B two horizontal unit vectors; since
        ``dz_C = w x z_C = -[z_C]x J_w dq``, Gauss-Newton steps
        ``dq = -J_e^+ e`` with ``J_e = -B^T [z_C]x J_w``.
        """
        q = np.array(q, float)
        down = self.chain.gravity_W / np.linalg.norm(self.chain.gravity_W)
        B = np.linalg.svd(np.eye(3) - np.outer(down, down))[0][:, :2]
        for _ in range(iterations):
            J, R, _ = self.chain.jacobian(q)
            z = R[..., :, 2]
            error = (z - down) @ B
            zx = np.zeros((*z.shape[:-1], 3, 3))
            zx[..., 0, 1], zx[..., 0, 2] = -z[..., 2], z[..., 1]
            zx[..., 1, 0], zx[..., 1, 2] = z[..., 2], -z[..., 0]
            zx[..., 2, 0], zx[..., 2, 1] = -z[..., 1], z[..., 0]
            J_e = -B.T @ zx @ J[..., :3, :]
            JJ = J_e @ np.swapaxes(J_e, -1, -2) + 1e-12 * np.eye(2)
            step = np.swapaxes(J_e, -1, -2) @ np.linalg.solve(JJ, error[..., None])
            q[..., self.chain.order] -= step[..., 0]
        return q

    def via(self, x: np.ndarray) -> np.ndarray:
        """Via points (P, K, n) for parameters x (P, K n)."""
        x = np.asarray(x, float).reshape(-1, *self.reference.shape)
        v = self.reference + self.scale * x
        return self.project_vertical(v) if self.vertical else v

    def waypoints(self, x: np.ndarray) -> np.ndarray:
        """All waypoints (P, 2 + 2 m + K, n) of the paths for parameters x."""
        v = self.via(x)
        count = v.shape[0]
        ends = [
            np.broadcast_to(a, (count, *a.shape))
            for a in (self.q_grasp[None], self.up, self.down, self.q_place[None])
        ]
        return np.concatenate([ends[0], ends[1], v, ends[2], ends[3]], axis=1)

    def segment_ends(self, knots: np.ndarray) -> tuple[float, float]:
        """The parameters s at the tops of the vertical end segments (from knots)."""
        return float(knots[len(self.up)]), float(knots[-1 - len(self.down)])


__all__ = ["FamilyError", "PathFamily", "corners"]
