"""4×4 transforms ↔ ``geometry_msgs/TransformStamped`` and ``tf2_msgs/TFMessage`` (/tf, /tf_static).

``tf2_msgs`` is not on PyPI: set-up builds it where it is missing (``interfaces/``), a real
ROS install has it. It is imported only when a TFMessage is made or read, so the rest of the
contract works without it; :func:`tf_messages_available` says whether it is there.
"""

from __future__ import annotations

import importlib.util
from collections.abc import Iterable

import numpy as np
from geometry_msgs.msg import Pose, Transform, TransformStamped

from door_contract.converters.pose import matrix_to_pose, pose_to_matrix
from door_contract.frames import FrameTransform
from door_contract.stamps import Stamp, to_time_msg


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


def tf_message(frames: Iterable[FrameTransform], stamp: Stamp):  # -> tf2_msgs.msg.TFMessage
    """One TFMessage holding every transform of ``frames``, all stamped ``stamp`` (s)."""
    from tf2_msgs.msg import TFMessage

    return TFMessage(transforms=[frame_transform_to_msg(frame, stamp) for frame in frames])


def tf_message_frames(msg) -> list[FrameTransform]:
    """The transforms of a TFMessage (``msg.transforms``)."""
    return [msg_to_frame_transform(transform) for transform in msg.transforms]
