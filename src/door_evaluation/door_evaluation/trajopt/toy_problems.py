r"""Analytic door-opening test problems shared by tests and the benchmark.

Both problems model, seen from above, a robot arm whose hand holds a door
handle while the door swings about its vertical hinge: robot and door form a
closed kinematic chain ([Zucker 2013] Sec. III), and the door's joints are part of
the optimised state.

* :func:`door_arc_case` -- a planar 3-link arm plus the door hinge angle
  (``m = 4``): the hand must stay on the handle, which moves on a circle of
  radius ``r`` about the hinge, at every free waypoint; the hinge starts at
  0 and must end at ``opening`` (40 deg, the pull of [Banerjee 2015] Sec. IV-3).
* :func:`seed000_sized_case` -- the size of [Zucker 2013]'s HUBO+ experiment:
  ``n = 104`` free waypoints between fixed end poses, ``m = 9`` (seven arm
  joints, door hinge, door handle) and ``k = 181`` equality rows: 46 fix the
  hinge, 55 hold the handle turned 45 deg, 80 keep the hand on the handle
  (2-D position at 40 waypoints instead of the seed's scalar squared
  distance, whose Jacobian vanishes on the constraint).

Kinematics (planar chain with base at the origin, angles cumulative):

.. math::

    p(\theta) = \sum_i l_i (\cos\varphi_i, \sin\varphi_i), \quad
    \varphi_i = \sum_{k \le i} \theta_k, \quad
    \frac{\partial p}{\partial \theta_k} = \sum_{i \ge k} l_i (-\sin\varphi_i, \cos\varphi_i).

Handle point in the door frame ``(a, d) = (r - l_h \cos\beta, d_o)`` (a lever
of length ``l_h`` turned by ``beta`` shortens its top-view projection), in
the world ``p_h = p_{hinge} + R(\psi_0 + \phi) (a, d)`` for hinge angle ``phi``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
import scipy.sparse as sp

from door_trajopt.problem import (
    Constraint,
    ConstraintKind,
    FloatArray,
    JointLimits,
    PostureCost,
    SmoothnessSpec,
    TrajectoryProblem,
)

__all__ = ["DOOR_ARC_CHAIN", "DOOR_ARC_DOOR", "DOOR_ARC_LIMITS", "BenchmarkCase", "HandOnHandle", "IntArray",
           "JointValue", "PlanarChain", "PlanarDoor", "SeedPhases", "TrajectoryShape", "door_arc_case", "door_arc_pose",
           "rotation", "seed000_sized_case", "suffix_sums"]

IntArray = npt.NDArray[np.int64]


def rotation(angle: FloatArray) -> FloatArray:
    """Stack of 2-D rotation matrices, shape ``angle.shape + (2, 2)``."""
    cos, sin = np.cos(angle), np.sin(angle)
    return np.stack([np.stack([cos, -sin], -1), np.stack([sin, cos], -1)], -2)


def suffix_sums(values: FloatArray) -> FloatArray:
    """``out[:, k] = sum_{i >= k} values[:, i]`` (the ``sum_{i >= k}`` of the Jacobian)."""
    return np.cumsum(values[:, ::-1], axis=1)[:, ::-1]


@dataclass(frozen=True)
class PlanarChain:
    """Planar serial arm with revolute joints and the given link lengths (m)."""

    link_lengths: tuple[float, ...]

    @property
    def n_joints(self) -> int:
        """Number of joints."""
        return len(self.link_lengths)

    def hand_positions(self, angles: FloatArray) -> FloatArray:
        """Hand positions ``p(theta)`` for angles of shape ``(T, L)`` -> ``(T, 2)``."""
        cumulative = np.cumsum(angles, axis=1)
        lengths = np.asarray(self.link_lengths)
        return np.stack([np.cos(cumulative) @ lengths, np.sin(cumulative) @ lengths], -1)

    def hand_jacobians(self, angles: FloatArray) -> FloatArray:
        """``dp/dtheta`` of shape ``(T, 2, L)`` (module docstring)."""
        cumulative = np.cumsum(angles, axis=1)
        lengths = np.asarray(self.link_lengths)
        dx = -np.sin(cumulative) * lengths
        dy = np.cos(cumulative) * lengths
        return np.stack([suffix_sums(dx), suffix_sums(dy)], axis=1)

    def three_link_ik(self, target: FloatArray, heading: float, elbow: float = 1.0) -> FloatArray:
        """Closed-form IK of a 3-link chain: hand at ``target`` pointing along ``heading``."""
        l1, l2, l3 = self.link_lengths
        wrist = np.asarray(target) - l3 * np.array([np.cos(heading), np.sin(heading)])
        cos_elbow = (wrist @ wrist - l1**2 - l2**2) / (2.0 * l1 * l2)
        theta2 = elbow * np.arccos(np.clip(cos_elbow, -1.0, 1.0))
        theta1 = np.arctan2(wrist[1], wrist[0]) - np.arctan2(
            l2 * np.sin(theta2), l1 + l2 * np.cos(theta2)
        )
        return np.array([theta1, theta2, heading - theta1 - theta2])


@dataclass(frozen=True)
class PlanarDoor:
    """Door seen from above: hinge point, closed heading, handle geometry (m, rad)."""

    hinge: tuple[float, float]
    closed_heading: float
    handle_radius: float
    handle_offset: float = 0.0
    lever_length: float = 0.0

    def _local(self, handle_angles: FloatArray) -> FloatArray:
        along = self.handle_radius - self.lever_length * np.cos(handle_angles)
        return np.stack([along, np.full_like(along, self.handle_offset)], -1)

    def handle_points(self, hinge_angles: FloatArray, handle_angles: FloatArray) -> FloatArray:
        """World handle points ``p_h(phi, beta)``, shape ``(T, 2)``."""
        turn = rotation(self.closed_heading + hinge_angles)
        points: FloatArray = np.asarray(self.hinge) + np.einsum("tij,tj->ti", turn, self._local(handle_angles))
        return points

    def handle_jacobians(self, hinge_angles: FloatArray, handle_angles: FloatArray) -> FloatArray:
        """``[dp_h/dphi, dp_h/dbeta]``, shape ``(T, 2, 2)``."""
        turn = rotation(self.closed_heading + hinge_angles)
        d_turn = rotation(self.closed_heading + hinge_angles + 0.5 * np.pi)
        d_local = np.stack(
            [self.lever_length * np.sin(handle_angles), np.zeros_like(handle_angles)], -1
        )
        d_hinge = np.einsum("tij,tj->ti", d_turn, self._local(handle_angles))
        d_handle = np.einsum("tij,tj->ti", turn, d_local)
        return np.stack([d_hinge, d_handle], -1)


@dataclass(frozen=True)
class TrajectoryShape:
    """``n`` waypoints of ``m`` DOF (for building row-major Jacobian columns)."""

    n_waypoints: int
    n_dof: int

    @property
    def n_columns(self) -> int:
        """Columns of a full-trajectory Jacobian."""
        return self.n_waypoints * self.n_dof


@dataclass(frozen=True)
class HandOnHandle:
    """Closed-chain rows ``p(theta_t) - p_h(phi_t, beta_t) = 0`` at ``waypoints``.

    DOF layout per waypoint: arm joints ``0..L-1``, hinge ``L``, handle
    ``L+1`` if ``has_handle_dof`` (else the handle angle is 0).
    """

    chain: PlanarChain
    door: PlanarDoor
    shape: TrajectoryShape
    waypoints: IntArray
    has_handle_dof: bool

    @property
    def size(self) -> int:
        """Two rows per constrained waypoint."""
        return 2 * self.waypoints.size

    @property
    def _columns_per_row(self) -> int:
        return self.chain.n_joints + 1 + int(self.has_handle_dof)

    def _split(self, trajectory: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        rows = trajectory[self.waypoints]
        joints = self.chain.n_joints
        handle = rows[:, joints + 1] if self.has_handle_dof else np.zeros(rows.shape[0])
        return rows[:, :joints], rows[:, joints], handle

    def value(self, trajectory: FloatArray) -> FloatArray:
        """Hand minus handle position, stacked ``(x, y)`` per waypoint."""
        arm, hinge, handle = self._split(trajectory)
        gap = self.chain.hand_positions(arm) - self.door.handle_points(hinge, handle)
        return gap.reshape(-1)

    def _indices(self) -> tuple[IntArray, IntArray]:
        width = self._columns_per_row
        rows = np.repeat(np.arange(self.size), width)
        columns = self.waypoints[:, None, None] * self.shape.n_dof + np.arange(width)
        columns = np.broadcast_to(columns, (self.waypoints.size, 2, width)).reshape(-1)
        return rows, columns

    def jacobian(self, trajectory: FloatArray) -> sp.csr_matrix:
        """``[dp/dtheta, -dp_h/dphi, -dp_h/dbeta]`` blocks, sparse."""
        arm, hinge, handle = self._split(trajectory)
        door = -self.door.handle_jacobians(hinge, handle)
        door = door if self.has_handle_dof else door[:, :, :1]
        blocks = np.concatenate([self.chain.hand_jacobians(arm), door], axis=2)
        rows, columns = self._indices()
        matrix_shape = (self.size, self.shape.n_columns)
        return sp.csr_matrix((blocks.reshape(-1), (rows, columns)), shape=matrix_shape)

    def pattern(self) -> sp.csr_matrix:
        """Structural non-zeros (the fixed blocks of :meth:`jacobian`)."""
        rows, columns = self._indices()
        ones = np.ones(rows.size, dtype=bool)
        return sp.csr_matrix((ones, (rows, columns)), shape=(self.size, self.shape.n_columns))

    def as_constraint(self, name: str) -> Constraint:
        """Wrap as an equality :class:`Constraint`."""
        return Constraint(
            name, ConstraintKind.EQUALITY, self.size, self.value, self.jacobian, self.pattern()
        )


@dataclass(frozen=True)
class JointValue:
    """Linear rows ``q_t[dof] - target = 0`` for ``t`` in ``waypoints``."""

    shape: TrajectoryShape
    waypoints: IntArray
    dof: int
    target: float

    def value(self, trajectory: FloatArray) -> FloatArray:
        """Deviation of the DOF from its target at each waypoint."""
        deviation: FloatArray = trajectory[self.waypoints, self.dof] - self.target
        return deviation

    def jacobian(self, trajectory: FloatArray) -> sp.csr_matrix:
        """Constant selection rows."""
        del trajectory
        return self.pattern().astype(np.float64)

    def pattern(self) -> sp.csr_matrix:
        """One non-zero per row."""
        rows = np.arange(self.waypoints.size)
        columns = self.waypoints * self.shape.n_dof + self.dof
        ones = np.ones(rows.size, dtype=bool)
        return sp.csr_matrix((ones, (rows, columns)), shape=(rows.size, self.shape.n_columns))

    def as_constraint(self, name: str) -> Constraint:
        """Wrap as an equality :class:`Constraint`."""
        return Constraint(
            name,
            ConstraintKind.EQUALITY,
            self.waypoints.size,
            self.value,
            self.jacobian,
            self.pattern(),
        )


@dataclass(frozen=True)
class BenchmarkCase:
    """A problem, its linear-interpolation initial guess and a label."""

    name: str
    problem: TrajectoryProblem
    initial_guess: FloatArray


DOOR_ARC_CHAIN = PlanarChain((0.45, 0.40, 0.20))
DOOR_ARC_DOOR = PlanarDoor(hinge=(0.8, -0.35), closed_heading=0.5 * np.pi, handle_radius=0.6)
DOOR_ARC_LIMITS = JointLimits(
    lower=np.array([-2.8, -2.8, -2.8, -0.1]), upper=np.array([2.8, 2.8, 2.8, 1.6])
)


def door_arc_case(
    n_waypoints: int = 30,
    opening: float = np.deg2rad(40.0),
    limits: JointLimits = DOOR_ARC_LIMITS,
    posture: PostureCost | None = None,
) -> BenchmarkCase:
    """Planar 3-link arm pulling a door open by ``opening`` rad (``m = 4``).

    Constraints: ``hand_on_handle`` (2 rows per free waypoint) and
    ``door_opening`` (final hinge angle).  The guess interpolates linearly
    from the grasp pose to the closed-form IK pose at the opened handle, so
    its middle waypoints leave the handle arc.
    """
    shape = TrajectoryShape(n_waypoints, DOOR_ARC_CHAIN.n_joints + 1)
    start = door_arc_pose(0.0)
    goal = door_arc_pose(opening)
    free = np.arange(1, n_waypoints, dtype=np.int64)
    constraints = (
        HandOnHandle(DOOR_ARC_CHAIN, DOOR_ARC_DOOR, shape, free, False).as_constraint(
            "hand_on_handle"
        ),
        JointValue(shape, np.array([n_waypoints - 1]), 3, float(opening)).as_constraint(
            "door_opening"
        ),
    )
    problem = TrajectoryProblem(
        n_waypoints=n_waypoints,
        start=start,
        limits=limits,
        smoothness=SmoothnessSpec(),
        posture=posture,
        constraints=constraints,
        dof_names=("shoulder", "elbow", "wrist", "door_hinge"),
    )
    return BenchmarkCase("door_arc", problem, problem.linear_interpolation(goal))


def door_arc_pose(hinge_angle: float) -> FloatArray:
    """Arm + hinge configuration with the hand on the handle, palm facing the door."""
    handle = DOOR_ARC_DOOR.handle_points(np.array([hinge_angle]), np.zeros(1))[0]
    arm = DOOR_ARC_CHAIN.three_link_ik(handle, heading=hinge_angle, elbow=-1.0)
    return np.append(arm, hinge_angle)


SEED_CHAIN = PlanarChain((0.25, 0.20, 0.18, 0.15, 0.12, 0.10, 0.08))
SEED_DOOR = PlanarDoor(
    hinge=(0.7, -0.45),
    closed_heading=0.5 * np.pi,
    handle_radius=0.75,
    handle_offset=0.06,
    lever_length=0.10,
)
SEED_REST_ARM = (-0.6, 0.5, 0.4, 0.3, 0.3, 0.2, 0.1)


@dataclass(frozen=True)
class SeedPhases:
    """Waypoint windows ``[first, stop)`` of [Zucker 2013]'s door opening (Fig. 3 rows).

    Reach and grasp with the hinge fixed (46 waypoints), then the door swing
    with the handle held turned (55), the hand on the handle over 40
    waypoints (2 rows each: 80).
    """

    hinge_fixed: tuple[int, int] = (1, 47)
    handle_turned: tuple[int, int] = (47, 102)
    grasp: tuple[int, int] = (22, 62)

    @staticmethod
    def waypoints(window: tuple[int, int]) -> IntArray:
        """Return the waypoint indices of a window."""
        return np.arange(*window, dtype=np.int64)


def seed000_sized_case(
    handle_turn: float = np.deg2rad(45.0), final_opening: float = np.deg2rad(40.0)
) -> BenchmarkCase:
    """[Zucker 2013] size: ``n = 104`` free waypoints, ``m = 9``, ``k = 181``.

    DOF: seven planar arm joints, door hinge (7), door handle (8).  Both end
    poses are fixed ([Zucker 2013]'s ``q(0)``, ``q(n+1)``) and the smoothness is
    [Zucker 2013]'s interior acceleration metric.  The guess is the straight line
    between the end poses, as [Banerjee 2015]'s default.
    """
    n_waypoints, n_dof = 106, 9
    shape = TrajectoryShape(n_waypoints, n_dof)
    start = np.array((*SEED_REST_ARM, 0.0, 0.0))
    end = np.array((*SEED_REST_ARM, final_opening, 0.0))
    phases = SeedPhases()
    constraints = (
        JointValue(shape, phases.waypoints(phases.hinge_fixed), 7, 0.0).as_constraint(
            "hinge_fixed"
        ),
        JointValue(shape, phases.waypoints(phases.handle_turned), 8, handle_turn).as_constraint(
            "handle_turned"
        ),
        HandOnHandle(
            SEED_CHAIN, SEED_DOOR, shape, phases.waypoints(phases.grasp), True
        ).as_constraint("hand_on_handle"),
    )
    limits = JointLimits(
        lower=np.array([-2.6] * 7 + [-0.2, -0.2]), upper=np.array([2.6] * 7 + [1.6, 1.2])
    )
    problem = TrajectoryProblem(
        n_waypoints=n_waypoints,
        start=start,
        end=end,
        limits=limits,
        smoothness=SmoothnessSpec(at_rest=False),
        constraints=constraints,
        dof_names=(*(f"arm_{i}" for i in range(7)), "door_hinge", "door_handle"),
    )
    return BenchmarkCase("seed000_sized", problem, problem.linear_interpolation(end))
