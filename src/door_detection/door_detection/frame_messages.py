"""One camera frame from its four messages (colour, depth, CameraInfo, camera pose), through
the contract's converters: what the detector node hands the core.

No rclpy here: the messages are plain ROS message objects, matched by stamp beforehand
(:mod:`door_detection.frame_sync`).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from door_contract.converters.camera_info import camera_info_to_intrinsics, check_matches_image
from door_contract.converters.image import depth_to_metres, image_to_array
from door_contract.converters.pose import pose_to_matrix
from door_contract.errors import ContractError
from door_detection.detector import CameraFrame, DetectorCamera

__all__ = ["decode_frame"]


def decode_frame(camera: DetectorCamera, stamp: float, parts: Mapping[str, Any]) -> CameraFrame:
    """The frame's messages as arrays; :class:`ContractError` saying what is wrong with them
    (another camera's frames, a colour image that is not rgb8, CameraInfo of another size)."""
    problem = camera.frame_problem({stream: parts[stream].header.frame_id for stream in ("color", "depth", "info")},
                                   parts["pose"].header.frame_id)
    if problem:
        raise ContractError(problem)
    rgb = image_to_array(parts["color"])
    if parts["color"].encoding != "rgb8":
        raise ContractError(f"colour must be rgb8, got {parts['color'].encoding!r}")
    intrinsics = camera_info_to_intrinsics(parts["info"])
    check_matches_image(intrinsics, rgb.shape[1], rgb.shape[0])
    return CameraFrame(stamp, rgb, depth_to_metres(parts["depth"]), intrinsics, pose_to_matrix(parts["pose"].pose))
