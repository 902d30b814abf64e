"""Two arm problems that a peer optimiser (tesseract's TrajOpt) solves as well, and one scorer.

Issue 15's peer benchmark: the arm joints of one side (the profile's arm chain without the
joints both arms share, i.e. TALOS's 7 arm joints with the torso still), ``T = 100``
waypoints, waypoint 0 fixed at the nominal posture, the URDF joint limits, and the cost

.. math::

    c(q) = \\sum_{t=1}^{T-1} \\lVert q_t - q_{t-1} \\rVert^2,

TrajOpt's joint-velocity cost ([Banerjee 2015] ``Q1``; the project's VELOCITY smoothness with
weight 2, since that one is ``1/2 w sum``). Constraints, both 6-D TCP pose equalities
``(p - p*, log(R R*^T)) = 0``:

* **reach**: the TCP at a pose at the last waypoint (the pose of a configuration between
  the nominal posture and the middle of the joint ranges, so it is reachable);
* **door arc**: the TCP holds a handle while the leaf turns ``arc_angle`` about a vertical
  hinge ``hinge_distance`` to the hand's outer side: 40 poses, evenly spread over the
  waypoints and evenly along the arc (240 equalities).

Every solver starts from the same stationary guess (all waypoints at the start: TrajOpt's
``STATIONARY`` initialisation), and every solution is scored by :func:`score` through
Pinocchio, whichever kinematics the solver used.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from door_contract.vocabulary import Side
from door_robot.kinematics import RobotKinematics
from door_trajopt.chain import ArmChain
from door_trajopt.door_model import rotation_about_up, rotation_vector
from door_trajopt.ik import pose_error
from door_trajopt.problem import ConstraintKind, Derivative, JointLimits, SmoothnessSpec, TrajectoryProblem
from door_trajopt.waypoint_constraints import WaypointFunction, WaypointValue, waypoint_constraint

__all__ = ["ARC_POSES", "PeerProblem", "Score", "arm_chain", "door_arc_problem", "own_arm_joints", "peer_problems",
           "reach_problem", "score", "trajectory_problem"]

WAYPOINTS = 100
ARC_POSES = 40  # 240 equalities
ARC_ANGLE = 0.3  # rad the leaf turns while the hand holds it
HINGE_DISTANCE = 0.6  # m from the hand to the hinge axis, to its outer side
REACH_BLEND = 0.35  # the reach goal: this far from the nominal posture to the ranges' middle


@dataclass(frozen=True)
class PeerProblem:
    """One arm problem: the chain, its start, and TCP targets (waypoint, 4×4 in the base frame)."""

    name: str
    chain: ArmChain
    start: np.ndarray
    targets: tuple[tuple[int, np.ndarray], ...]
    n_waypoints: int = WAYPOINTS

    @property
    def equality_rows(self) -> int:
        return 6 * len(self.targets)

    def stationary_guess(self) -> np.ndarray:
        """(T, k): every waypoint at the start."""
        return np.tile(self.start, (self.n_waypoints, 1))


@dataclass(frozen=True)
class Score:
    """What :func:`score` measures on a solution (one evaluator for every solver)."""

    cost: float  # Σ ||q_t − q_{t−1}||² (rad²)
    position_error: float  # m, worst TCP target
    rotation_error: float  # rad, worst TCP target
    limit_violation: float  # rad beyond a joint limit
    start_error: float  # rad, waypoint 0 against the start


def own_arm_joints(kinematics: RobotKinematics, side: Side) -> tuple[str, ...]:
    """The side's chain joints that the other arm's chain does not share (no torso)."""
    profile = kinematics.profile
    shared = set(profile.arm(side.other).joints)
    return tuple(name for name in profile.arm(side).joints if name not in shared)


def arm_chain(kinematics: RobotKinematics, side: Side = Side.RIGHT) -> ArmChain:
    """The arm alone, the rest of the body at the nominal posture."""
    return ArmChain(kinematics, side, kinematics.nominal_q.copy(), own_arm_joints(kinematics, side))


def reach_problem(kinematics: RobotKinematics, side: Side = Side.RIGHT) -> PeerProblem:
    chain = arm_chain(kinematics, side)
    start = chain.chain_of(chain.body_q)
    goal = start + REACH_BLEND * (0.5 * (chain.lower + chain.upper) - start)
    return PeerProblem("reach", chain, start, ((WAYPOINTS - 1, chain.tcp_pose(goal)),))


def door_arc_problem(kinematics: RobotKinematics, side: Side = Side.RIGHT) -> PeerProblem:
    """The TCP pose turned about a vertical axis beside the hand: T(α) = R_z(α) about h."""
    chain = arm_chain(kinematics, side)
    start = chain.chain_of(chain.body_q)
    hand = chain.tcp_pose(start)
    outward = np.array([0.0, 1.0 if hand[1, 3] > 0 else -1.0, 0.0])
    hinge = hand[:3, 3] + HINGE_DISTANCE * outward
    sign = 1.0 if outward[1] < 0 else -1.0  # the hand swings forward, away from the body
    targets = []
    for i in range(1, ARC_POSES + 1):
        waypoint = int(round(i * (WAYPOINTS - 1) / ARC_POSES))
        turn = rotation_about_up(sign * ARC_ANGLE * waypoint / (WAYPOINTS - 1))
        pose = np.eye(4)
        pose[:3, :3] = turn @ hand[:3, :3]
        pose[:3, 3] = hinge + turn @ (hand[:3, 3] - hinge)
        targets.append((waypoint, pose))
    return PeerProblem("door arc", chain, start, tuple(targets))


def peer_problems(kinematics: RobotKinematics, side: Side = Side.RIGHT) -> tuple[PeerProblem, PeerProblem]:
    return reach_problem(kinematics, side), door_arc_problem(kinematics, side)


def _tcp_pose_error(chain: ArmChain, target: np.ndarray) -> WaypointFunction:
    """Waypoint function (p − p*, log(R R*ᵀ)) and its Jacobian, the TCP's (world-aligned)."""
    def function(q: np.ndarray, need_jacobian: bool) -> WaypointValue:
        error = -pose_error(chain.tcp_pose(q), target)
        return error, (chain.tcp_jacobian(q) if need_jacobian else None)
    return function


def trajectory_problem(peer: PeerProblem) -> TrajectoryProblem:
    """The project's :class:`TrajectoryProblem` of ``peer`` (both backends solve it)."""
    k, n = peer.chain.size, peer.n_waypoints
    constraints = tuple(
        waypoint_constraint(f"tcp_pose_{t}", ConstraintKind.EQUALITY, _tcp_pose_error(peer.chain, pose), 6, [t], k, n)
        for t, pose in peer.targets)
    return TrajectoryProblem(
        n_waypoints=n, start=peer.start, limits=JointLimits(peer.chain.lower, peer.chain.upper),
        smoothness=SmoothnessSpec(Derivative.VELOCITY, at_rest=False, weights=np.full(k, 2.0)),
        constraints=constraints, dof_names=peer.chain.joint_names)


def score(peer: PeerProblem, trajectory: np.ndarray) -> Score:
    """Cost, worst TCP errors and limit violation of a (T, k) solution, through Pinocchio."""
    trajectory = np.asarray(trajectory, dtype=float)
    chain = peer.chain
    position, rotation = 0.0, 0.0
    for t, target in peer.targets:
        pose = chain.tcp_pose(trajectory[t])
        position = max(position, float(np.linalg.norm(pose[:3, 3] - target[:3, 3])))
        rotation = max(rotation, float(np.linalg.norm(rotation_vector(pose[:3, :3] @ target[:3, :3].T))))
    beyond = np.maximum(trajectory - chain.upper, chain.lower - trajectory)
    return Score(cost=float(np.sum(np.diff(trajectory, axis=0) ** 2)), position_error=position,
                 rotation_error=rotation, limit_violation=float(max(0.0, beyond.max())),
                 start_error=float(np.abs(trajectory[0] - peer.start).max()))
