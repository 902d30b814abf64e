"""The door motion library as optimisation problems ([Banerjee 2015] Sec. IV, [Zucker 2013] Sec. III).

State of every problem: the arm chain's joints (torso + arm of one side) followed by the
door's hinge angle θ and handle angle φ ([Zucker 2013]'s m = 9 = arm + hip yaw + hinge + handle;
here the chain is the profile's). Constraints:

* **closed chain** while grasping: TCP pose = :meth:`DoorModel.grasp_pose` (θ_t, φ_t) at every
  waypoint, with a 6-vector mask ([Banerjee 2015]'s diag(c1..c6));
* **key poses**: pregrasp (the hand ``pregrasp_offset`` back along the normal, [Banerjee 2015]
  Sec. II: "the hand needs to move forward around 4 cm") and grasp at the end of the approach;
* **door path**: φ reaches the handle turn, θ the opening angle at the last waypoint;
* **CoM inside the support polygon** (half-planes of the feet's rectangle, [Banerjee 2015] Sec. IV);
* **wall clearance**: a hinge loss on the elbow's signed distance to the door plane.

Costs: accelerations ([Zucker 2013]'s A = KᵀK; [Banerjee 2015]'s joint displacement Q1 for velocity),
posture deviation from the nominal posture (Q2).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import Protocol

import numpy as np

from door_contract.geometry import planar_pose, yaw_of
from door_contract.ranges import FieldRange, check_in_range
from door_contract.vocabulary import Motion, Side
from door_trajopt.chain import ArmChain
from door_trajopt.door_model import UP, DoorModel, rotation_vector
from door_trajopt.ik import IkOptions, IkResult, solve_ik, solve_ik_batch
from door_trajopt.problem import (
    Constraint,
    ConstraintKind,
    JointLimits,
    PostureCost,
    SmoothnessSpec,
    TrajectoryProblem,
    TrajoptError,
)
from door_trajopt.validation import check_ranges
from door_trajopt.waypoint_constraints import WaypointFunction, WaypointValue, fixed_dof, waypoint_constraint

__all__ = ["HANDLE_RANGE", "HINGE_RANGE", "DoorStateOutOfRange", "ExtraConstraints", "MotionOptions", "MotionProblem",
           "MotionSetup", "WallRelaxation", "anchored_to_hand", "build_motion", "check_start_door", "levelling",
           "minimum_duration", "option_range", "start_door_for", "support_polygon"]

FULL_MASK = np.ones(6)
POSITION_MASK = np.array([1.0, 1.0, 1.0, 0.0, 0.0, 0.0])
ROTATION_MASK = np.array([0.0, 0.0, 0.0, 1.0, 1.0, 1.0])
HINGE_RANGE = FieldRange(0.0, 1.75, "rad")
"""The hinge angle θ between closed and the door stop."""
HANDLE_RANGE = FieldRange(0.0, 1.0, "rad")
"""The handle angle φ between rest and the handle stop."""


class DoorStateOutOfRange(TrajoptError):
    """A door state (hinge θ, handle φ) outside the door's stops: no motion can start there."""


def check_start_door(start_door: tuple[float, float]) -> None:
    """Raise :class:`DoorStateOutOfRange` unless θ ∈ HINGE_RANGE and φ ∈ HANDLE_RANGE.

    Outside them the problem is unsolvable, and not cheaply so: a turn_handle at
    θ = 1e6 rad put the grasp pose anywhere on the circle, every IK and every initial
    guess ran to its budget, and the optimiser was blocked for 80 s.
    """
    check_in_range("door hinge angle", float(start_door[0]), HINGE_RANGE, DoorStateOutOfRange)
    check_in_range("door handle angle", float(start_door[1]), HANDLE_RANGE, DoorStateOutOfRange)


@dataclass(frozen=True)
class MotionOptions:
    """Motion-library settings (SI units). Validated; errors name the field and range."""

    waypoints: int = 10
    handle_turn: float = 0.8  # rad; [Banerjee 2015] turned ~80°, the DRC-like sim handle stops at 1.0 rad
    push_angle: float = 0.2  # rad the arm pushes the door open (the body pushes it further)
    pull_angle: float = 0.35  # rad (~20°; [Banerjee 2015]: ~40°): the gap the other hand blocks through
    pregrasp_offset: float = 0.04  # m, [Banerjee 2015] Sec. II
    grasp_clearance: float = 0.01  # m the approach stops short of the grasp point along the normal:
    # TALOS's fingertips reach within ~1 cm of the leaf at the grasp point, and a door estimate
    # ~1 cm deep made the physical arm press 100 N into a latched door (the grasp closes within 2 cm)
    com_margin: float = 0.02  # m inside the support polygon
    wall_clearance: float = 0.04  # m, elbow in front of the door plane
    lever_standoff: float = 0.06  # m, door face behind the grasp point
    block_inset: float = 0.10  # m from the free edge where the other hand blocks the door
    block_entry: float = 0.10  # m beyond the free edge where the blocking hand comes first
    block_standoff: float = 0.14  # m from the leaf's robot-side face to the blocking TCP, behind it
    # (leaf 0.04 m thick + the gripper's body: at 0.11 m the gripper pressed on the leaf)
    post_inset: float = 0.022  # m, the latch-side post's face inside the leaf's free edge (0.87 m clear)
    forearm_clearance: float = 0.06  # m, forearm radius + margin to the post
    head_clearance: float = 0.15  # m from the head camera to a pulled leaf's plane (head radius + margin)
    posture_weight: float = 0.05
    door_stop_lateral: float = 0.10  # m from the base's centreline (hand's side) of the hand stopping a pushed door
    release_retreat: float = 0.08  # m the hand backs off a pulled door's lever before it swings to walking posture
    tuck_duration: float = 2.0  # s, at least, for the blocking arm's tuck: the leaf follows the hand
    doorway_arm_margin: float = 0.16  # m from the latch-side post's face to the arm's joints, a
    # sideways robot's released arm on a pushed leaf (at 0.10 the elbow struck the post in 4 of 8 doors)

    def __post_init__(self) -> None:
        check_ranges(self, _MOTION_RANGES)


_MOTION_RANGES: dict[str, FieldRange] = {
    "waypoints": FieldRange(4, 200, "waypoints"),
    "handle_turn": replace(HANDLE_RANGE, low=0.1), "push_angle": replace(HINGE_RANGE, low=0.05),
    "pull_angle": replace(HINGE_RANGE, low=0.05),
    "pregrasp_offset": FieldRange(0.0, 0.2, "m"), "grasp_clearance": FieldRange(0.0, 0.02, "m"),
    "com_margin": FieldRange(0.0, 0.1, "m"), "wall_clearance": FieldRange(0.0, 0.3, "m"),
    "lever_standoff": FieldRange(0.0, 0.2, "m"), "block_inset": FieldRange(0.0, 0.5, "m"),
    "block_entry": FieldRange(0.0, 0.5, "m"), "block_standoff": FieldRange(0.0, 0.5, "m"),
    "posture_weight": FieldRange(0.0, 100.0, ""), "post_inset": FieldRange(0.0, 0.2, "m"),
    "forearm_clearance": FieldRange(0.0, 0.3, "m"), "head_clearance": FieldRange(0.0, 0.5, "m"),
    "door_stop_lateral": FieldRange(0.0, 0.3, "m"), "release_retreat": FieldRange(0.0, 0.3, "m"),
    "tuck_duration": FieldRange(0.0, 10.0, "s"), "doorway_arm_margin": FieldRange(0.0, 0.5, "m"),
}


def option_range(name: str) -> FieldRange:
    """The allowed interval of :class:`MotionOptions` field ``name``: what a node parameter
    configuring that option takes as its range."""
    return _MOTION_RANGES[name]


@dataclass(frozen=True)
class MotionSetup:
    """What a motion is planned from: the chain (at the measured posture) and the door. The
    CoM is held over the feet in the *levelled* base frame (``level``, :func:`levelling`): the
    physical robot's base is never quite upright, and 2.7° of pitch moves the CoM's projection
    4.7 cm against the soles' (a pull door's tuck, Monte-Carlo seed 5 trial 13: the base frame's
    box put the CoM 2.1 cm ahead of the feet, infeasible in four repeats; levelled, 1.9 cm inside)."""

    chain: ArmChain
    door: DoorModel
    door_width: float
    support_polygon: np.ndarray  # (4,) x_min, x_max, y_min, y_max of the feet, levelled base frame
    start_door: tuple[float, float] = (0.0, 0.0)  # θ, φ
    hand_in_grasp: np.ndarray | None = None  # measured TCP in the door's grasp frame while holding
    level: np.ndarray = field(default_factory=lambda: np.eye(3))  # 3×3, base frame → levelled base frame

    @classmethod
    def measured(cls, chain: ArmChain, door: DoorModel, door_width: float, base_orientation: np.ndarray,
                 start_door: tuple[float, float] = (0.0, 0.0)) -> MotionSetup:
        """The set-up of a robot whose base has ``base_orientation`` (3×3, in a frame with z up,
        e.g. ``odom``): its support polygon and CoM compared in the levelled base frame."""
        level = levelling(base_orientation)
        return cls(chain, door, door_width, support_polygon(chain, level), start_door, level=level)


def levelling(base_orientation: np.ndarray) -> np.ndarray:
    """R_level = R_z(ψ)ᵀ·R, ψ the base's yaw (the heading of its x axis): base-frame vectors in
    the frame that has the base's heading and z vertical, where "over the feet" is horizontal."""
    rotation = np.asarray(base_orientation, dtype=float)[:3, :3]
    level: np.ndarray = planar_pose(0.0, 0.0, yaw_of(rotation))[:3, :3].T @ rotation
    return level


@dataclass(frozen=True)
class MotionProblem:
    problem: TrajectoryProblem
    initial_guess: np.ndarray  # (n, m)
    chain: ArmChain


# --------------------------------------------------------------------- waypoint functions
ExtraConstraints = Callable[[int, int], list[Constraint]]
"""A motion's constraints beyond the closed chain, for m DOFs and n waypoints."""


class _Target(Protocol):
    """A TCP target pose (odom) that may depend on the door state (θ, φ), and ∂(p, ω)/∂(θ, φ) (6×2)."""

    def pose(self, theta: float, phi: float) -> np.ndarray: ...

    def derivatives(self, theta: float, phi: float) -> np.ndarray: ...


def _tcp_target_error(chain: ArmChain, target_of: _Target, mask: np.ndarray) -> WaypointFunction:
    """Waypoint function: masked TCP pose error to a target that may depend on (θ, φ)."""
    rows = mask.astype(bool)
    k = chain.size

    def function(q: np.ndarray, need_jacobian: bool) -> WaypointValue:
        pose, tcp_jacobian = chain.tcp_pose_and_jacobian(q[:k]) if need_jacobian else (chain.tcp_pose(q[:k]), None)
        target = target_of.pose(q[k], q[k + 1])
        error = np.concatenate([pose[:3, 3] - target[:3, 3], rotation_vector(pose[:3, :3] @ target[:3, :3].T)])
        if tcp_jacobian is None:
            return error[rows], None
        jacobian = np.hstack([tcp_jacobian, -target_of.derivatives(q[k], q[k + 1])])
        return error[rows], jacobian[rows]
    return function


@dataclass(frozen=True)
class _GraspTarget:
    """The TCP target on the door at (θ, φ) and its derivatives ∂(p, ω)/∂(θ, φ)."""

    door: DoorModel
    tcp_in_grasp: np.ndarray

    def pose(self, theta: float, phi: float) -> np.ndarray:
        pose: np.ndarray = self.door.grasp_pose(theta, phi) @ self.tcp_in_grasp
        return pose

    def derivatives(self, theta: float, phi: float) -> np.ndarray:
        return self.door.pose_derivatives(theta, phi)


@dataclass(frozen=True)
class _FixedTarget:
    target: np.ndarray

    def pose(self, theta: float, phi: float) -> np.ndarray:
        return self.target

    def derivatives(self, theta: float, phi: float) -> np.ndarray:
        return np.zeros((6, 2))


def _grasp_target(setup: MotionSetup, tcp_in_grasp: np.ndarray) -> _GraspTarget:
    return _GraspTarget(setup.door, tcp_in_grasp)


def _fixed_target(pose: np.ndarray) -> _FixedTarget:
    return _FixedTarget(pose)


def _com_in_polygon(setup: MotionSetup, margin: float) -> WaypointFunction:
    """g = [x_min − c_x, c_x − x_max, y_min − c_y, c_y − y_max] + margin ≤ 0, c the CoM in the
    levelled base frame (R_level·c_base; its Jacobian R_level·J)."""
    x_min, x_max, y_min, y_max = setup.support_polygon
    k = setup.chain.size
    level = setup.level[:2]
    signs = np.array([[-1.0, 0.0], [1.0, 0.0], [0.0, -1.0], [0.0, 1.0]])
    bounds = np.array([-x_min, x_max, -y_min, y_max])

    def function(q: np.ndarray, need_jacobian: bool) -> WaypointValue:
        if not need_jacobian:
            return signs @ (level @ setup.chain.com(q[:k])) - bounds + margin, None
        com, jacobian = setup.chain.com_and_jacobian(q[:k])
        value = signs @ (level @ com) - bounds + margin
        return value, np.hstack([signs @ (level @ jacobian), np.zeros((4, 2))])
    return function


def _elbow_clearance(setup: MotionSetup, options: MotionOptions) -> WaypointFunction:
    """g = clearance − (p_elbow − p_door)·n ≤ 0, the door face ``lever_standoff`` behind the grasp."""
    k, frame = setup.chain.size, setup.chain.elbow_frame
    normal = setup.door.normal
    face = setup.door.grasp_point - options.lever_standoff * normal

    def function(q: np.ndarray, need_jacobian: bool) -> WaypointValue:
        if not need_jacobian:
            return np.array([options.wall_clearance - (setup.chain.point(q[:k], frame) - face) @ normal]), None
        point, jacobian = setup.chain.point_and_jacobian(q[:k], frame)
        value = np.array([options.wall_clearance - (point - face) @ normal])
        return value, np.hstack([-(normal @ jacobian)[None, :], np.zeros((1, 2))])
    return function


def _doorway_clearance(setup: MotionSetup, options: MotionOptions) -> WaypointFunction:
    """The forearm passes the doorway clear of the latch-side post (collision hinge loss).

    For each forearm point p, with s = (p − p_hinge)·u its distance along the closed door
    from the hinge and d = (p − p_face)·n its distance in front of the wall:
    g = s − (s_post − margin) − slope·max(0, d − d₀) ≤ 0 — the post only constrains points
    that are at (or past) the wall plane; in front of it the bound relaxes linearly.
    """
    normal = setup.door.normal
    face = setup.door.grasp_point - options.lever_standoff * normal
    limit = setup.door_width - options.post_inset - options.forearm_clearance
    return _along_wall_below(setup, setup.chain.forearm_frames, limit, WallRelaxation(face, normal))


def _head_clearance(setup: MotionSetup, options: MotionOptions) -> WaypointFunction:
    """A pulled leaf swings towards the head (bent over a low handle, TALOS's head met the
    leaf and the grasp slipped): g = clearance − (p_head − p_hinge)·n(θ) ≤ 0, with
    n(θ) = R(θ)n the leaf's robot-side normal at the waypoint's hinge angle θ, and
    ∂n/∂θ = s·(z × n(θ)) (s the hinge sign). Conservative beyond the free edge: it keeps
    the head off the leaf's whole plane."""
    k, frame = setup.chain.size, setup.chain.kinematics.profile.head_camera_frame
    door = setup.door

    def function(q: np.ndarray, need_jacobian: bool) -> WaypointValue:
        normal = door.leaf_rotation(q[k]) @ door.normal
        if not need_jacobian:
            return np.array([options.head_clearance - (setup.chain.point(q[:k], frame) - door.hinge_point) @ normal]), None
        point, jacobian = setup.chain.point_and_jacobian(q[:k], frame)
        offset = point - door.hinge_point
        value = np.array([options.head_clearance - offset @ normal])
        d_normal = door.hinge_sign * np.cross(UP, normal)
        return value, np.concatenate([-(normal @ jacobian), [-(offset @ d_normal), 0.0]])[None, :]
    return function


def _pull_head_clearance(setup: MotionSetup, options: MotionOptions, m: int, n: int) -> list[Constraint]:
    """The head clearance at every moving waypoint, for pull doors only."""
    if setup.door.push:
        return []
    return [waypoint_constraint("head_clearance", ConstraintKind.INEQUALITY, _head_clearance(setup, options), 1,
                                range(1, n), m, n)]


# --------------------------------------------------------------------- problem assembly
def _limits(setup: MotionSetup, door_moves: tuple[bool, bool], start_chain: np.ndarray,
            pinned: tuple[str, ...] = ()) -> JointLimits:
    chain = setup.chain
    lower = [*chain.lower, HINGE_RANGE.low, HANDLE_RANGE.low]
    upper = [*chain.upper, HINGE_RANGE.high, HANDLE_RANGE.high]
    for index, name in enumerate(chain.joint_names):
        if name in pinned:  # e.g. the torso while the other hand holds the door
            lower[index] = upper[index] = float(start_chain[index])
    for dof, moves in enumerate(door_moves):
        if not moves:  # a door DOF that does not move is pinned by its bounds
            lower[chain.size + dof] = upper[chain.size + dof] = setup.start_door[dof]
    return JointLimits(np.array(lower), np.array(upper))


def _problem(setup: MotionSetup, start_chain: np.ndarray, options: MotionOptions, door_moves: tuple[bool, bool],
             constraints: Sequence[Constraint], end: np.ndarray | None = None,
             pinned: tuple[str, ...] = ()) -> TrajectoryProblem:
    chain = setup.chain
    m = chain.size + 2
    start = np.concatenate([start_chain, setup.start_door])
    nominal = np.concatenate([chain.chain_of(chain.kinematics.nominal_q), setup.start_door])
    posture_weights = np.concatenate([np.full(chain.size, options.posture_weight), [0.0, 0.0]])
    common = [waypoint_constraint("support_polygon", ConstraintKind.INEQUALITY,
                                  _com_in_polygon(setup, options.com_margin), 4,
                                  range(1, options.waypoints), m, options.waypoints)]
    return TrajectoryProblem(
        n_waypoints=options.waypoints, start=start, limits=_limits(setup, door_moves, start_chain, pinned), end=end,
        smoothness=SmoothnessSpec(), posture=PostureCost(nominal, posture_weights),
        constraints=tuple(constraints) + tuple(common),
        dof_names=(*chain.joint_names, "door_hinge", "door_handle"))


def _tcp_in_grasp(setup: MotionSetup, start_chain: np.ndarray) -> np.ndarray:
    """TCP relative to the grasp frame: fingers into the door, closing vertically, as the
    profile's ``grasp_axes`` of the hand say, or its ``grasp_axes_beside`` when the door runs
    along the robot's side (:class:`door_robot.profile.GraspAxes`; TALOS's
    grippers point their fingers along −z of the TCP and close along y: z_tcp = x_grasp, the
    normal, y_tcp = z_grasp, up, x_tcp = y_grasp). While the hand holds the handle, the
    transform measured at the start (:func:`anchored_to_hand`) replaces this nominal one: the
    grasp locked the hand wherever it closed (a few mm off, a degree turned), and the closed
    chain must keep exactly that.
    """
    if setup.hand_in_grasp is not None:
        return setup.hand_in_grasp
    beside = abs(setup.door.along[1]) < DOOR_ACROSS_FRONT
    tcp = np.eye(4)
    tcp[:3, :3] = setup.chain.kinematics.profile.arm(setup.chain.side).grasp_axes_for(beside).rotation_in_grasp()
    return tcp


def build_motion(motion: Motion, setup: MotionSetup, start_chain: np.ndarray,
                 options: MotionOptions = MotionOptions()) -> MotionProblem:
    """The optimisation problem of ``motion`` and its initial guess (IK key poses)."""
    # measured joints can sit a hair outside their limits (position control overshoot)
    start_chain = np.clip(start_chain, setup.chain.lower, setup.chain.upper)
    builder = {Motion.APPROACH_HANDLE: _approach, Motion.TURN_HANDLE: _turn, Motion.PUSH_DOOR: _swing,
               Motion.PULL_DOOR: _swing, Motion.BLOCK_DOOR: _block, Motion.READY_TO_WALK: _ready,
               Motion.TUCK_ARM: _tuck}[motion]
    return builder(setup, start_chain, options)


def _approach(setup: MotionSetup, start_chain: np.ndarray, options: MotionOptions) -> MotionProblem:
    n, m = options.waypoints, setup.chain.size + 2
    offset = _tcp_in_grasp(setup, start_chain)
    grasp = setup.door.grasp_pose(*setup.start_door) @ offset
    grasp[:3, 3] += options.grasp_clearance * setup.door.normal
    pregrasp = grasp.copy()
    pregrasp[:3, 3] += options.pregrasp_offset * setup.door.normal
    t_pre = max(1, int(round(0.7 * (n - 1))))
    constraints = [
        waypoint_constraint("pregrasp_pose", ConstraintKind.EQUALITY,
                            _tcp_target_error(setup.chain, _fixed_target(pregrasp), FULL_MASK), 6, [t_pre], m, n),
        waypoint_constraint("grasp_pose", ConstraintKind.EQUALITY,
                            _tcp_target_error(setup.chain, _fixed_target(grasp), FULL_MASK), 6, [n - 1], m, n),
        waypoint_constraint("wall_clearance", ConstraintKind.INEQUALITY, _elbow_clearance(setup, options), 1,
                            range(1, n), m, n),
    ]
    problem = _problem(setup, start_chain, options, (False, False), constraints)
    q_pre = _ik(setup.chain, pregrasp, start_chain)
    q_grasp = solve_ik(setup.chain, grasp, q_pre).chain_q
    guess = _through_keys(problem, [(0, start_chain), (t_pre, q_pre), (n - 1, q_grasp)], setup.start_door)
    return MotionProblem(problem, guess, setup.chain)


def _closed_chain(setup: MotionSetup, start_chain: np.ndarray, options: MotionOptions,
                  door_path: np.ndarray, door_moves: tuple[bool, bool], extra: ExtraConstraints) -> MotionProblem:
    """Every waypoint holds the handle; the door follows ``door_path`` (n, 2) in the guess."""
    n, m = options.waypoints, setup.chain.size + 2
    target = _grasp_target(setup, _tcp_in_grasp(setup, start_chain))
    constraints = [waypoint_constraint("closed_chain", ConstraintKind.EQUALITY,
                                       _tcp_target_error(setup.chain, target, FULL_MASK), 6, range(1, n), m, n),
                   *extra(m, n)]
    problem = _problem(setup, start_chain, options, door_moves, constraints)
    chain_path = _continuation_ik(setup.chain, [target.pose(*door_path[t]) for t in range(n)], start_chain)
    return MotionProblem(problem, np.hstack([chain_path, door_path]), setup.chain)


def _turn(setup: MotionSetup, start_chain: np.ndarray, options: MotionOptions) -> MotionProblem:
    n = options.waypoints
    theta, phi = setup.start_door
    path = np.column_stack([np.full(n, theta), np.linspace(phi, options.handle_turn, n)])
    def extra(m: int, n: int) -> list[Constraint]:
        return [fixed_dof("handle_turned", setup.chain.size + 1, {n - 1: options.handle_turn}, m, n),
                waypoint_constraint("wall_clearance", ConstraintKind.INEQUALITY,
                                    _elbow_clearance(setup, options), 1, range(1, n), m, n)]
    return _closed_chain(setup, start_chain, options, path, (False, True), extra)


def _swing(setup: MotionSetup, start_chain: np.ndarray, options: MotionOptions) -> MotionProblem:
    """Push or pull: the hinge follows a fixed schedule θ_t = θ₀ + (θ_goal − θ₀)·t/(n−1)
    ([Banerjee 2015] Sec. IV: "rotate ~40° about the door hinge") and the arm's redundancy is
    optimised around it. Left free, the hinge DOF let the optimum swing the door out to
    0.27–0.42 rad and pull it back; past ~0.3 rad TALOS's forearm meets the post."""
    n = options.waypoints
    theta, phi = setup.start_door
    angle = options.push_angle if setup.door.push else options.pull_angle
    path = np.column_stack([np.linspace(theta, angle, n), np.full(n, phi)])

    def extra(m: int, n: int) -> list[Constraint]:
        schedule = {t: float(path[t, 0]) for t in range(1, n)}
        constraints = [fixed_dof("door_schedule", setup.chain.size, schedule, m, n)]
        if setup.door.push:  # the forearm goes through the doorway with the door
            constraints.append(waypoint_constraint("doorway_clearance", ConstraintKind.INEQUALITY,
                                                   _doorway_clearance(setup, options), 2, range(1, n), m, n))
        return constraints + _pull_head_clearance(setup, options, m, n)
    return _closed_chain(setup, start_chain, options, path, (True, False), extra)


def _block(setup: MotionSetup, start_chain: np.ndarray, options: MotionOptions) -> MotionProblem:
    """The other hand goes behind the opened leaf near its free edge ([Banerjee 2015] Sec. IV-4:
    "a target position behind the door which can be defined according to the position of
    the door handle"; position only). It first comes to ``block_entry`` beyond the free
    edge, level with its final place, and slides in behind the leaf from there: straight
    from the start, the gripper met the leaf's edge."""
    n, m = options.waypoints, setup.chain.size + 2
    door = setup.door
    leaf = door.leaf_rotation(setup.start_door[0])
    behind = leaf @ (-door.normal) * options.block_standoff  # the side the door closes towards

    def beside_leaf(along: float) -> np.ndarray:
        target = np.eye(4)
        target[:3, 3] = door.hinge_point + leaf @ (along * door.along) + behind
        return target
    entry = beside_leaf(setup.door_width + options.block_entry)
    target = beside_leaf(setup.door_width - options.block_inset)
    t_entry = max(1, int(round(0.6 * (n - 1))))
    constraints = [waypoint_constraint(name, ConstraintKind.EQUALITY,
                                       _tcp_target_error(setup.chain, _fixed_target(pose), POSITION_MASK), 3, [t], m, n)
                   for name, pose, t in (("block_entry", entry, t_entry), ("block_position", target, n - 1))]
    # the other hand still holds the handle: joints both arms share (the torso) must not move,
    # and so the head (on the torso) and the door stay where PULL left them, clear of each other
    pinned = _shared_with_other_arm(setup.chain)
    problem = _problem(setup, start_chain, options, (False, False), constraints, pinned=pinned)
    q_entry = _within_limits(problem, _ik(setup.chain, entry, start_chain, POSITION_MASK))
    q_end = _within_limits(problem, solve_ik(setup.chain, target, q_entry, mask=POSITION_MASK).chain_q)
    guess = _through_keys(problem, [(0, start_chain), (t_entry, q_entry), (n - 1, q_end)], setup.start_door)
    return MotionProblem(problem, guess, setup.chain)


def _ready(setup: MotionSetup, start_chain: np.ndarray, options: MotionOptions) -> MotionProblem:
    """The posture to walk through in. Push doors: :func:`_door_stop`. Pull doors: the
    released hand backs off the lever along the leaf's normal (``release_retreat``), then the
    arm goes to the profile's walking posture. The other hand blocks the door, so the joints
    both arms share (the torso) stay where they are: moving them would move the block."""
    if setup.door.push:
        return _door_stop(setup, start_chain, options)
    n, m = options.waypoints, setup.chain.size + 2
    pinned, end_chain, end = _to_walking_posture(setup, start_chain)
    retreat = setup.chain.tcp_pose(start_chain)
    leaf_normal = setup.door.leaf_rotation(setup.start_door[0]) @ setup.door.normal
    retreat[:3, 3] += options.release_retreat * leaf_normal
    t_back = max(1, (n - 1) // 3)
    constraints = [waypoint_constraint("release_retreat", ConstraintKind.EQUALITY,
                                       _tcp_target_error(setup.chain, _fixed_target(retreat), POSITION_MASK),
                                       3, [t_back], m, n)]
    problem = _problem(setup, start_chain, options, (False, False), constraints, end=end, pinned=pinned)
    q_back = _within_limits(problem, solve_ik(setup.chain, retreat, start_chain, IkOptions(max_iterations=60),
                                              mask=POSITION_MASK).chain_q)
    guess = _through_keys(problem, [(0, start_chain), (t_back, q_back), (n - 1, end_chain)], setup.start_door)
    return MotionProblem(problem, guess, setup.chain)


def _tuck(setup: MotionSetup, start_chain: np.ndarray, options: MotionOptions) -> MotionProblem:
    """A pull door's blocking arm, the robot in the doorway sideways, from the leaf to the
    walking posture (:mod:`footstep_planner.pull_passage`): the leaf follows the hand and comes
    to rest on the front of the body, far from its axis. The joints both arms share (the
    torso) stay where they are; the CoM stays over the feet. No door constraint: the leaf is
    not held (its push on the hand is what the stabiliser feeds forward). Without a posture
    cost the smoothest path is the straight line in joint space (the acceleration cost's
    minimum between fixed ends): on the passage rig the posture-weighted path left the wrist
    0.12-0.17 rad off its goal under the leaf in 5 of 10 doors, the straight one 0.07 in 3."""
    pinned, end_chain, end = _to_walking_posture(setup, start_chain)
    straight = replace(options, posture_weight=0.0)  # no pull towards the nominal posture: the path stays straight
    problem = _problem(setup, start_chain, straight, (False, False), [], end=end, pinned=pinned)
    guess = _through_keys(problem, [(0, start_chain), (options.waypoints - 1, end_chain)], setup.start_door)
    return MotionProblem(problem, guess, setup.chain)


def _to_walking_posture(setup: MotionSetup, start_chain: np.ndarray) -> tuple[tuple[str, ...], np.ndarray, np.ndarray]:
    """Where an arm ends that goes to the walking posture while the other arm still holds or
    blocks the door: (the pinned joints both arms share, the chain's end, the end state with
    the door where it is). The pinned joints (the torso) stay where they start."""
    pinned = _shared_with_other_arm(setup.chain)
    walking = setup.chain.chain_of(setup.chain.kinematics.walking_q)
    end_chain = np.array([start_chain[i] if name in pinned else walking[i]
                          for i, name in enumerate(setup.chain.joint_names)])
    return pinned, end_chain, np.concatenate([end_chain, setup.start_door])


def minimum_duration(motion: Motion, options: MotionOptions) -> float:
    """The shortest a ``motion`` may take (s): the tuck's ``tuck_duration``, else 0 (the
    joints' velocity and acceleration limits alone time it)."""
    return options.tuck_duration if motion is Motion.TUCK_ARM else 0.0


def _shared_with_other_arm(chain: ArmChain) -> tuple[str, ...]:
    """Joints of this chain that the other arm's chain also has (the torso)."""
    other = chain.kinematics.profile.arm(chain.side.other).joints
    return tuple(name for name in chain.joint_names if name in other)


def _door_stop(setup: MotionSetup, start_chain: np.ndarray, options: MotionOptions) -> MotionProblem:
    """Push doors: the released hand stays on the leaf, which the closer presses against the
    fingers, so the hand stops the door and the door never closes on the latch.

    Facing the door (the leaf runs across the base's y axis): the hand slides along the leaf
    to straight ahead of the body (:func:`_door_stop_ahead`). Sideways, the back to the hinge
    (the stance of :mod:`footstep_planner.push_passage`): :func:`_door_stop_beside`.
    """
    if abs(setup.door.along[1]) < DOOR_ACROSS_FRONT:
        return _door_stop_beside(setup, start_chain, options)
    return _door_stop_ahead(setup, start_chain, options)


DOOR_ACROSS_FRONT = 0.7
"""|y| of the closed door's unit direction (hinge to latch) in the base frame above which the
door runs across the robot's front (facing it, within 45°); below, along its side (sideways)."""


def _door_stop_ahead(setup: MotionSetup, start_chain: np.ndarray, options: MotionOptions) -> MotionProblem:
    """Facing a push door: the released hand slides along the leaf to straight ahead of the body.

    Held where it grasped (a few cm from the latch-side post) it would meet the post as the
    robot walks, while straight ahead of the base it passes the opening's middle and pushes the
    leaf open as the robot walks (the body pushes it further). The TCP keeps its
    orientation and its distance from the face: every waypoint is on the straight line
    along the leaf to ``door_stop_lateral`` from the base's centreline on the hand's side
    (:func:`_door_stop_offset`; reaching across the chest moved the CoM out).
    """
    n, m = options.waypoints, setup.chain.size + 2
    start_tcp = setup.chain.tcp_pose(start_chain)
    lateral = float(np.copysign(options.door_stop_lateral, start_tcp[1, 3]))
    offset = _door_stop_offset(setup.door, setup.start_door[0], start_tcp[:3, 3], lateral)
    targets = []
    for t in range(n):
        target = start_tcp.copy()
        target[:3, 3] += offset * t / (n - 1)
        targets.append(target)
    constraints = [waypoint_constraint(f"along_leaf_{t}", ConstraintKind.EQUALITY,
                                       _tcp_target_error(setup.chain, _fixed_target(targets[t]), FULL_MASK),
                                       6, [t], m, n) for t in range(1, n)]
    problem = _problem(setup, start_chain, options, (False, False), constraints)
    chain_path = _continuation_ik(setup.chain, targets, start_chain)
    return MotionProblem(problem, np.hstack([chain_path, np.tile(setup.start_door, (n, 1))]), setup.chain)


def _door_stop_beside(setup: MotionSetup, start_chain: np.ndarray, options: MotionOptions) -> MotionProblem:
    """Sideways at a push door: the hand that pushed it stays on the leaf (its distance from
    the leaf's plane and its orientation held at every waypoint, free to slide along it) and
    ends with every arm joint inside the doorway, ``doorway_arm_margin`` from the latch-side
    post along the wall: g = (p − p_hinge)·u − (W − post_inset − margin) ≤ 0.

    The robot side-steps through next, the hand and then the back pushing the leaf open. The
    approach turned the torso ~80° towards the door, and the elbow then stood 6 cm beyond the
    post's face and struck it; where the arm ends (torso turned back or not) is the optimiser's.
    """
    n, m = options.waypoints, setup.chain.size + 2
    start_tcp = setup.chain.tcp_pose(start_chain)
    leaf_normal = setup.door.leaf_rotation(setup.start_door[0]) @ setup.door.normal
    face_distance = float((start_tcp[:3, 3] - setup.door.hinge_point) @ leaf_normal)
    shared = len(_shared_with_other_arm(setup.chain))
    frames = tuple(setup.chain.body_frame(i) for i in range(shared, setup.chain.size)) + (setup.chain.tcp_frame,)
    limit = setup.door_width - options.post_inset - options.doorway_arm_margin
    waypoints = range(1, n)
    constraints = [
        waypoint_constraint("on_leaf", ConstraintKind.EQUALITY, _leaf_plane_distance(setup, face_distance),
                            1, waypoints, m, n),
        waypoint_constraint("hand_orientation", ConstraintKind.EQUALITY,
                            _tcp_target_error(setup.chain, _fixed_target(start_tcp), ROTATION_MASK), 3, waypoints, m, n),
        waypoint_constraint("arm_in_doorway", ConstraintKind.INEQUALITY, _along_wall_below(setup, frames, limit),
                            len(frames), [n - 1], m, n)]
    problem = _problem(setup, start_chain, options, (False, False), constraints)
    guess = _beside_guess(setup, start_chain, start_tcp, frames, limit, n)
    return MotionProblem(problem, np.hstack([guess, np.tile(setup.start_door, (n, 1))]), setup.chain)


BESIDE_SLIDES = ((0.20, 0.10), (0.30, 0.15), (0.35, 0.20), (0.40, 0.25))
"""(along the leaf towards the hinge, up) m the initial guess slides the hand, tried in turn
(the optimiser's own answer on the benchmark's door: 0.31 m along, 0.16 m up)."""


def _beside_guess(setup: MotionSetup, start_chain: np.ndarray, start_tcp: np.ndarray,
                  frames: tuple[str, ...], limit: float, n: int) -> np.ndarray:
    """(n, k) initial guess of :func:`_door_stop_beside`: the torso turned and raised back to
    the nominal posture while the hand slides along the leaf (towards the hinge and up, its
    orientation and distance from the leaf held: the arm alone solves each waypoint's IK from
    the previous one). Every waypoint then meets the equalities and the end the doorway bound,
    and the optimiser only polishes: with the torso left where the push left it (pitched
    0.79 rad towards the door) no slide brought the shoulder inside the doorway, the guess
    held still 0.21 m outside it, and the SQP took 28 iterations (207 ms CPU against the
    100 ms target) while CHOMP failed. The first of :data:`BESIDE_SLIDES` whose IK converges
    and whose end is inside; the arm held still when none is. The slides are solved together,
    waypoint by waypoint (:func:`solve_ik_batch` with a target per slide: the arm chain is the
    same for all, the torso being interpolated alike; one by one, three slides took 14 ms)."""
    towards_hinge = -(setup.door.leaf_rotation(setup.start_door[0]) @ setup.door.along)
    inside = _along_wall_below(setup, frames, limit)
    shared = len(_shared_with_other_arm(setup.chain))
    torso_start, torso_end = start_chain[:shared], setup.chain.chain_of(setup.chain.kinematics.nominal_q)[:shared]
    slides = np.array([along * towards_hinge + np.array([0.0, 0.0, up]) for along, up in BESIDE_SLIDES])
    paths = np.tile(start_chain, (len(slides), n, 1))  # (slide, waypoint, chain joint)
    converged = np.ones(len(slides), dtype=bool)
    for t in range(1, n):
        fraction = t / (n - 1)
        targets = np.tile(start_tcp, (len(slides), 1, 1))
        targets[:, :3, 3] += fraction * slides
        paths[:, t, :shared] = torso_start + fraction * (torso_end - torso_start)
        arm = ArmChain(setup.chain.kinematics, setup.chain.side, setup.chain.full(paths[0, t]),
                       setup.chain.joint_names[shared:])  # (the arm's own joints of the body are replaced)
        solutions = solve_ik_batch(arm, targets, list(paths[:, t - 1, shared:]), IkOptions(max_iterations=60))
        paths[:, t, shared:] = [solution.chain_q for solution in solutions]
        converged &= [solution.converged for solution in solutions]
    for slide, slide_converged in enumerate(converged):
        if slide_converged and np.max(inside(np.concatenate([paths[slide, -1], setup.start_door]), False)[0]) <= 0.0:
            guess: np.ndarray = paths[slide]
            return guess
    return np.tile(start_chain, (n, 1))


def _leaf_plane_distance(setup: MotionSetup, distance: float) -> WaypointFunction:
    """h = (p_tcp − p_hinge)·n(θ) − distance = 0, n(θ) = R(θ)n the leaf's robot-side normal at
    the waypoint's hinge angle (the door does not move here: θ is pinned)."""
    k, door = setup.chain.size, setup.door

    def function(q: np.ndarray, need_jacobian: bool) -> WaypointValue:
        point = setup.chain.tcp_pose(q[:k])[:3, 3]
        normal = door.leaf_rotation(q[k]) @ door.normal
        value = np.array([(point - door.hinge_point) @ normal - distance])
        if not need_jacobian:
            return value, None
        return value, np.concatenate([normal @ setup.chain.tcp_jacobian(q[:k])[:3], [0.0, 0.0]])[None, :]
    return function


@dataclass(frozen=True)
class WallRelaxation:
    """Where a bound along the wall stops applying: in front of the wall's face (a point
    ``face`` on it, robot-side unit ``normal``) it relaxes by ``slope``·max(0, d − ``free``),
    d = (p − face)·n, so only points at (or past) the wall plane are held by it."""

    face: np.ndarray
    normal: np.ndarray
    slope: float = 3.0
    free: float = 0.03  # m in front of the face where the bound still holds in full


def _along_wall_below(setup: MotionSetup, frames: tuple[str, ...], limit: float,
                      relaxation: WallRelaxation | None = None) -> WaypointFunction:
    """g_i = (p_i − p_hinge)·u − limit − r_i ≤ 0 for each frame's origin p_i (u along the
    closed door from the hinge towards the latch; r_i the :class:`WallRelaxation`, 0 without)."""
    k, along, hinge = setup.chain.size, setup.door.along, setup.door.hinge_point

    def function(q: np.ndarray, need_jacobian: bool) -> WaypointValue:
        values, rows = np.empty(len(frames)), np.zeros((len(frames), k + 2)) if need_jacobian else None
        for index, frame in enumerate(frames):
            if rows is None:
                point = setup.chain.point(q[:k], frame)
            else:
                point, jacobian = setup.chain.point_and_jacobian(q[:k], frame)
            values[index], gradient = (point - hinge) @ along - limit, along
            if relaxation is not None:
                ahead = (point - relaxation.face) @ relaxation.normal - relaxation.free
                if ahead > 0.0:
                    values[index] -= relaxation.slope * ahead
                    gradient = along - relaxation.slope * relaxation.normal
            if rows is not None:
                rows[index, :k] = gradient @ jacobian
        return values, rows
    return function


def _door_stop_offset(door: DoorModel, theta: float, hand: np.ndarray, lateral: float) -> np.ndarray:
    """Displacement along the leaf at θ that brings ``hand`` to base y = ``lateral``:
    d = a·R(θ)u with a = (lateral − hand_y)/(R(θ)u)_y (u = ``along``; the leaf is across
    the base's y axis, so the divisor is far from 0 for any reachable door)."""
    direction = door.leaf_rotation(theta) @ door.along
    if abs(direction[1]) < 0.2:
        raise TrajoptError(f"the leaf at {theta:.2f} rad does not cross the robot's front")
    offset: np.ndarray = (lateral - hand[1]) / direction[1] * direction
    return offset


def _continuation_ik(chain: ArmChain, targets: list[np.ndarray], start_chain: np.ndarray) -> np.ndarray:
    """(n, k) joint path through TCP ``targets`` (the first is where the chain already is):
    each waypoint's IK starts from the previous solution, so the path stays on one branch."""
    path, q = [start_chain], start_chain
    for target in targets[1:]:
        q = solve_ik(chain, target, q, IkOptions(max_iterations=60)).chain_q
        path.append(q)
    return np.array(path)


def _within_limits(problem: TrajectoryProblem, chain_q: np.ndarray) -> np.ndarray:
    """``chain_q`` clipped to the problem's joint bounds (pinned joints included)."""
    k = chain_q.size
    return np.clip(chain_q, problem.limits.lower[:k], problem.limits.upper[:k])


def _ik(chain: ArmChain, target: np.ndarray, seed: np.ndarray, mask: np.ndarray | None = None) -> np.ndarray:
    """A key pose: the first IK solution (from ``seed``, the nominal posture, then
    :data:`KEY_POSE_RANDOM_SEEDS` random seeds) that keeps :data:`KEY_POSE_MARGIN` from every
    joint limit (:func:`_limit_margin`), else the converged one farthest from them, else the
    closest. The first converged one had been taken: on the sideways push stance with the
    lever at 0.87-0.88 m it put the shoulder roll at its limit and the torso pitch 0.05 rad
    from its stop, and no turn of the handle was feasible from that grasp. There no solution
    keeps the margin, so the choice is among the converged ones: with 6 random seeds the left
    hand found the branch that turns and the right hand (mirrored doors) did not; with 24
    both do. The seeds are solved together (:func:`solve_ik_batch`, with the same choice as one
    by one: the 26 seeds one by one took 42 ms of the sideways approach's 58 ms guess)."""
    rng = np.random.default_rng(0)
    seeds = [seed, chain.chain_of(chain.kinematics.nominal_q)] + [rng.uniform(chain.lower, chain.upper)
                                                                  for _ in range(KEY_POSE_RANDOM_SEEDS)]

    def keeps_margin(solution: IkResult) -> bool:
        return solution.converged and _limit_margin(chain, solution.chain_q) >= KEY_POSE_MARGIN
    solutions = solve_ik_batch(chain, target, seeds, mask=mask, accept=keeps_margin)
    if keeps_margin(solutions[-1]):
        return solutions[-1].chain_q
    converged = [solution.chain_q for solution in solutions if solution.converged]
    if converged:
        return max(converged, key=lambda q: _limit_margin(chain, q))
    return min(solutions, key=lambda solution: solution.miss).chain_q


KEY_POSE_MARGIN = 0.05
"""rad from every joint limit that makes an IK key pose good enough to take at once."""

KEY_POSE_RANDOM_SEEDS = 24
"""Random IK seeds a key pose may try after the given seed and the nominal posture."""


def _limit_margin(chain: ArmChain, chain_q: np.ndarray) -> float:
    """The smallest distance (rad) of any chain joint from either of its limits."""
    return float(np.min(np.minimum(chain_q - chain.lower, chain.upper - chain_q)))


def _through_keys(problem: TrajectoryProblem, keys: list[tuple[int, np.ndarray]],
                  door: tuple[float, float]) -> np.ndarray:
    """Piecewise-linear interpolation through key waypoints ([Zucker 2013] Sec. III)."""
    times = [t for t, _ in keys]
    values = np.array([np.concatenate([q, door]) for _, q in keys])
    all_t = np.arange(problem.n_waypoints)
    return np.column_stack([np.interp(all_t, times, values[:, j]) for j in range(values.shape[1])])


def anchored_to_hand(setup: MotionSetup, start_chain: np.ndarray) -> MotionSetup:
    """The set-up with the hand-in-grasp transform measured from the arm's posture.

    At the start of a handle-holding motion the hand is locked to the handle, so the
    door's grasp frame at (θ₀, φ₀) and the TCP (forward kinematics of the measured joints)
    fix the transform between them: T = G(θ₀, φ₀)⁻¹ · T_tcp(q₀).
    """
    grasp = setup.door.grasp_pose(*setup.start_door)
    tcp = setup.chain.tcp_pose(np.clip(start_chain, setup.chain.lower, setup.chain.upper))
    return replace(setup, hand_in_grasp=np.linalg.inv(grasp) @ tcp)


STOP_TOLERANCE = 0.01
"""rad a measured hinge angle may lie beyond a door stop and be taken as on it (a leaf resting
on its stop reads 1.7500005 rad)."""


def start_door_for(motion: Motion, door_angle: float, options: MotionOptions) -> tuple[float, float]:
    """(θ, φ) at the start of ``motion``: the handle stays turned while the door swings. A
    measured θ within :data:`STOP_TOLERANCE` beyond a stop is on the stop; one farther out is
    kept (and refused by :func:`check_start_door`)."""
    turned = motion in (Motion.PUSH_DOOR, Motion.PULL_DOOR)
    low, high = HINGE_RANGE.low, HINGE_RANGE.high
    if low - STOP_TOLERANCE <= door_angle <= high + STOP_TOLERANCE:
        door_angle = min(max(door_angle, low), high)
    return (door_angle, options.handle_turn if turned else 0.0)


def support_polygon(chain: ArmChain, level: np.ndarray | None = None) -> np.ndarray:
    """x/y bounds of the rectangle covering both soles in the measured posture, in the base
    frame levelled by ``level`` (:func:`levelling`; None: the base frame, the base upright)."""
    kinematics = chain.kinematics
    walking = kinematics.profile.walking
    rotation = level if level is not None else np.eye(3)
    corners = []
    for side in Side:
        sole = kinematics.frame_pose(chain.body_q, kinematics.profile.feet[side])
        for dx in (-walking.foot_length / 2, walking.foot_length / 2):
            for dy in (-walking.foot_width / 2, walking.foot_width / 2):
                corners.append((rotation @ (sole @ np.array([dx, dy, 0.0, 1.0]))[:3])[:2])
    xy = np.array(corners)
    return np.array([xy[:, 0].min(), xy[:, 0].max(), xy[:, 1].min(), xy[:, 1].max()])
