"""4×4 transforms ↔ ``geometry_msgs/TransformStamped`` and ``tf2_msgs/TFMessage`` (/tf, /tf_static).

``tf2_msgs`` is not on PyPI: set-up builds it where it is missing (``interfaces/``), a real
ROS install has it. It is imported only when a TFMessage is made or read, so the rest of the
contract works without it; :func:`tf_messages_available` says whether it is there.
"""

from __future__ import annotations

import importlib.util
from collections.abc import Iterable
from typing import Any

import numpy as np
from geometry_msgs.msg import Pose, Transform, TransformStamped
from scipy.spatial.transform import Rotation

from door_contract.converters._checks import require_finite
from door_contract.converters.pose import matrix_to_pose, pose_to_matrix
from door_contract.errors import ShapeError
from door_contract.frames import FrameTransform
from door_contract.stamps import Stamp, to_time_msg

__all__ = ["TfMessageBuffer", "frame_transform_to_msg", "matrix_to_transform", "msg_to_frame_transform", "tf_message",
           "tf_message_frames", "tf_messages_available", "transform_to_matrix"]


def tf_messages_available() -> bool:
    """True when ``tf2_msgs`` can be imported (built by set-up, or the system's)."""
    return importlib.util.find_spec("tf2_msgs") is not None


def matrix_to_transform(matrix: np.ndarray) -> Transform:
    """``geometry_msgs/Transform`` of a finite rigid 4×4 (rejects NaN/inf like the pose converter)."""
    pose = matrix_to_pose(matrix)
    transform = Transform()
    transform.translation.x, transform.translation.y, transform.translation.z = (
        pose.position.x, pose.position.y, pose.position.z)
    transform.rotation = pose.orientation
    return transform


def transform_to_matrix(transform: Transform) -> np.ndarray:
    """4×4 of a ``geometry_msgs/Transform`` (NaN/inf and zero quaternions rejected)."""
    pose = Pose()
    pose.position.x, pose.position.y, pose.position.z = (
        transform.translation.x, transform.translation.y, transform.translation.z)
    pose.orientation = transform.rotation
    return pose_to_matrix(pose)


def frame_transform_to_msg(frame: FrameTransform, stamp: Stamp) -> TransformStamped:
    msg = TransformStamped()
    msg.header.frame_id, msg.child_frame_id = frame.parent, frame.child
    msg.header.stamp = to_time_msg(stamp)
    msg.transform = matrix_to_transform(frame.matrix)
    return msg


def msg_to_frame_transform(msg: TransformStamped) -> FrameTransform:
    return FrameTransform(msg.header.frame_id, msg.child_frame_id, transform_to_matrix(msg.transform))


def _checked_stack(frames: list[FrameTransform]) -> tuple[np.ndarray, list[list[float]]]:
    """The frames' matrices (N, 4, 4), checked finite and 4×4, and their (x, y, z, w) quaternions."""
    matrices = require_finite(np.array([frame.matrix for frame in frames], dtype=float), "transforms")
    if frames and matrices.shape[1:] != (4, 4):
        raise ShapeError(f"transforms must be 4×4, got {matrices.shape[1:]}")
    return matrices, (Rotation.from_matrix(matrices[:, :3, :3]).as_quat().tolist() if frames else [])


def _write(msg: TransformStamped, time_msg: Any, matrix: np.ndarray, quaternion: list[float]) -> None:
    """Stamp and numbers of one TransformStamped, set in place (frames unchanged)."""
    msg.header.stamp = time_msg
    translation, rotation = msg.transform.translation, msg.transform.rotation
    translation.x, translation.y, translation.z = matrix[:3, 3].tolist()
    rotation.x, rotation.y, rotation.z, rotation.w = quaternion


def tf_message(frames: Iterable[FrameTransform], stamp: Stamp) -> Any:  # tf2_msgs.msg.TFMessage, imported lazily
    """One TFMessage holding every transform of ``frames``, all stamped ``stamp`` (s).

    One finiteness check and one rotation → quaternion conversion for the whole stack; each
    TransformStamped is filled in place (nested message constructors cost more than the maths).
    """
    from tf2_msgs.msg import TFMessage

    frames = list(frames)
    matrices, quaternions = _checked_stack(frames)
    time_msg = to_time_msg(stamp)
    transforms = []
    for frame, matrix, quaternion in zip(frames, matrices, quaternions):
        msg = TransformStamped(child_frame_id=frame.child)
        msg.header.frame_id = frame.parent
        _write(msg, time_msg, matrix, quaternion)
        transforms.append(msg)
    return TFMessage(transforms=transforms)


class TfMessageBuffer:
    """One TFMessage reused at every /tf publication: while the frames stay the same, only
    stamps and numbers are rewritten (rclpy serialises a message when it is published, so
    reusing it is safe). A fresh message when the frames change."""

    def __init__(self) -> None:
        self._message: Any = None  # tf2_msgs.msg.TFMessage
        self._frames: tuple[tuple[str, str], ...] = ()

    def message(self, frames: Iterable[FrameTransform], stamp: Stamp) -> Any:  # tf2_msgs.msg.TFMessage
        frames = list(frames)
        names = tuple((frame.parent, frame.child) for frame in frames)
        if self._message is None or names != self._frames:
            self._message, self._frames = tf_message(frames, stamp), names
            return self._message
        matrices, quaternions = _checked_stack(frames)
        time_msg = to_time_msg(stamp)
        for msg, matrix, quaternion in zip(self._message.transforms, matrices, quaternions):
            _write(msg, time_msg, matrix, quaternion)
        return self._message


def tf_message_frames(msg: Any) -> list[FrameTransform]:
    """The transforms of a TFMessage (``msg.transforms``)."""
    return [msg_to_frame_transform(transform) for transform in msg.transforms]
