"""Helpers of the sim-bridge tests: damped-least-squares IK through Pinocchio, reaching the handle.

The tests place the hand with the project's own kinematics (door_robot.kinematics), as the
trajectory optimiser will: a few damped-least-squares iterations on the torso + arm chain,
q <- q + J^T (J J^T + lambda^2 I)^-1 e, for a full 6-D pose error (position, rotation vector)
or, with ``approach_only``, position plus the direction of the TCP's z axis.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

from door_contract.vocabulary import Side
from door_robot.kinematics import RobotKinematics
from door_sim_bridge.execution import ExecutionResult, TrajectoryExecution
from door_sim_bridge.world import DoorPart, DoorWorld, StanceConfig

GRASP_STANCE = StanceConfig(distance=0.6, lateral_offset=-0.15)
"""Where TALOS reaches the default (left-hinged) door's handle with its right hand."""


def current_q(world: DoorWorld, kinematics: RobotKinematics) -> np.ndarray:
    positions = world.joint_positions()
    return kinematics.configuration({name: positions[name] for name in kinematics.joint_names})


def solve_ik(world: DoorWorld, kinematics: RobotKinematics, side: Side, target: np.ndarray,
             q: np.ndarray | None = None, approach_only: bool = False, iterations: int = 300,
             damping: float = 0.05) -> tuple[list[str], np.ndarray]:
    """Arm joint names and a full configuration putting the ``side`` TCP at ``target`` (odom)."""
    q = (current_q(world, kinematics) if q is None else q).copy()
    indices = kinematics.arm_indices(side)
    base = world.base_pose()
    frame = kinematics.profile.tcp_frame(side)
    for _ in range(iterations):
        tcp = base @ kinematics.frame_pose(q, frame)
        rotation_error = (np.cross(tcp[:3, 2], target[:3, 2]) if approach_only
                          else Rotation.from_matrix(target[:3, :3] @ tcp[:3, :3].T).as_rotvec())
        error = np.concatenate([target[:3, 3] - tcp[:3, 3], rotation_error])
        if np.linalg.norm(error) < 1e-7:
            break
        jacobian = kinematics.frame_jacobian(q, frame)[:, indices]
        jacobian = np.vstack([base[:3, :3] @ jacobian[:3], base[:3, :3] @ jacobian[3:]])
        step = jacobian.T @ np.linalg.solve(jacobian @ jacobian.T + damping**2 * np.eye(6), error)
        q[indices] = np.clip(q[indices] + step, kinematics.lower_limits[indices] + 1e-3,
                             kinematics.upper_limits[indices] - 1e-3)
    return [kinematics.joint_names[i] for i in indices], q


def approach_pose(world: DoorWorld, offset: np.ndarray | None = None) -> np.ndarray:
    """The handle grasp point (+ offset, odom) with the TCP's z axis along the door normal
    towards the robot, i.e. the fingers pointing at the door."""
    grasp = world.handle_grasp_pose()
    normal = grasp[:3, 0]
    pose = np.eye(4)
    pose[:3, :3] = np.column_stack([np.cross([0.0, 0.0, 1.0], normal), [0.0, 0.0, 1.0], normal])
    pose[:3, 3] = grasp[:3, 3] + (np.zeros(3) if offset is None else offset)
    return pose


def move_arm_to(world: DoorWorld, names: list[str], q: np.ndarray, indices: np.ndarray,
                duration: float = 2.0) -> ExecutionResult:
    return TrajectoryExecution(world, [duration], names, [q[indices]]).run()


def reach_handle(world: DoorWorld, kinematics: RobotKinematics, side: Side,
                 offset: np.ndarray | None = None) -> ExecutionResult:
    """Move the ``side`` TCP to the handle grasp point (+ offset) and settle."""
    names, q = solve_ik(world, kinematics, side, approach_pose(world, offset), approach_only=True)
    return move_arm_to(world, names, q, kinematics.arm_indices(side))


def turned_grasp_target(world: DoorWorld, grasp_then: np.ndarray, tcp_in_grasp: np.ndarray,
                        handle_turn: float, door_turn: float = 0.0) -> np.ndarray:
    """Where a hand fixed to the lever is once the handle turned by ``handle_turn`` and the leaf
    by ``door_turn`` from the state in which the lever's grasp frame was ``grasp_then``."""
    handle = world.door.link_pose(DoorPart.HANDLE)
    handle_axis = handle[:3, :3] @ world.door.geometry.handle_axis
    truth = world.door_ground_truth()
    turn = _rotation_about(handle[:3, 3], handle_axis, handle_turn)
    swing = _rotation_about(truth.hinge_point, truth.hinge_axis, door_turn)
    return swing @ turn @ grasp_then @ tcp_in_grasp


def _rotation_about(point: np.ndarray, axis: np.ndarray, angle: float) -> np.ndarray:
    transform = np.eye(4)
    transform[:3, :3] = Rotation.from_rotvec(np.asarray(axis) * angle).as_matrix()
    transform[:3, 3] = point - transform[:3, :3] @ point
    return transform
