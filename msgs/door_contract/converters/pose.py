"""``geometry_msgs/Pose(Stamped)`` ↔ 4×4 homogeneous transforms (quaternions are x, y, z, w)."""

from __future__ import annotations

import numpy as np
from geometry_msgs.msg import Pose, PoseStamped
from scipy.spatial.transform import Rotation

from door_contract.converters._checks import require_finite
from door_contract.errors import NonFiniteError, ShapeError
from door_contract.stamps import Stamp, to_time_msg

__all__ = ["matrix_to_pose", "matrix_to_pose_stamped", "pose_stamped_to_matrix", "pose_to_matrix"]


def pose_to_matrix(pose: Pose) -> np.ndarray:
    """4×4 transform; rejects NaN/inf and zero quaternions (normalises the others)."""
    p, q = pose.position, pose.orientation
    values = require_finite(np.array([p.x, p.y, p.z, q.x, q.y, q.z, q.w]), "pose")
    quaternion = values[3:]
    if np.linalg.norm(quaternion) < 1e-9:
        raise NonFiniteError("pose orientation is a zero quaternion")
    transform = np.eye(4)
    transform[:3, :3] = Rotation.from_quat(quaternion / np.linalg.norm(quaternion)).as_matrix()
    transform[:3, 3] = values[:3]
    return transform


def matrix_to_pose(transform: np.ndarray) -> Pose:
    matrix = require_finite(transform, "transform")
    if matrix.shape != (4, 4):
        raise ShapeError(f"transform must be 4×4, got {matrix.shape}")
    pose = Pose()
    pose.position.x, pose.position.y, pose.position.z = (float(v) for v in matrix[:3, 3])
    x, y, z, w = Rotation.from_matrix(matrix[:3, :3]).as_quat()
    pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w = (
        float(x), float(y), float(z), float(w))
    return pose


def pose_stamped_to_matrix(msg: PoseStamped) -> np.ndarray:
    return pose_to_matrix(msg.pose)


def matrix_to_pose_stamped(transform: np.ndarray, frame_id: str,
                           stamp: Stamp | None = None) -> PoseStamped:
    msg = PoseStamped()
    msg.header.frame_id = frame_id
    if stamp is not None:
        msg.header.stamp = to_time_msg(stamp)
    msg.pose = matrix_to_pose(transform)
    return msg
