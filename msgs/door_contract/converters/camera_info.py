"""``sensor_msgs/CameraInfo`` ↔ pinhole intrinsics."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from sensor_msgs.msg import CameraInfo

from door_contract.converters._checks import require_finite
from door_contract.errors import ShapeError
from door_contract.stamps import Stamp, to_time_msg

__all__ = ["CameraIntrinsics", "camera_info_to_intrinsics", "check_matches_image", "intrinsics_to_camera_info"]


@dataclass(frozen=True)
class CameraIntrinsics:
    """Pinhole model of an undistorted image: u = fx·x/z + cx, v = fy·y/z + cy (pixels)."""

    width: int
    height: int
    fx: float
    fy: float
    cx: float
    cy: float

    @property
    def matrix(self) -> np.ndarray:
        return np.array([[self.fx, 0.0, self.cx], [0.0, self.fy, self.cy], [0.0, 0.0, 1.0]])

    def back_project(self, u: np.ndarray, v: np.ndarray, depth: np.ndarray) -> np.ndarray:
        """Points (N×3, optical frame, metres) of pixels (u, v) at depth z."""
        z = np.asarray(depth, dtype=float)
        return np.stack([(u - self.cx) * z / self.fx, (v - self.cy) * z / self.fy, z], axis=-1)

    def project(self, points: np.ndarray) -> np.ndarray:
        """Pixels (N×2) of optical-frame points (N×3)."""
        p = np.asarray(points, dtype=float)
        return np.stack([self.fx * p[:, 0] / p[:, 2] + self.cx,
                         self.fy * p[:, 1] / p[:, 2] + self.cy], axis=-1)


def camera_info_to_intrinsics(msg: CameraInfo) -> CameraIntrinsics:
    """Intrinsics from K; rejects empty sizes, non-finite or non-positive focal lengths."""
    k = require_finite(np.asarray(msg.k, dtype=float), "CameraInfo.k").reshape(3, 3)
    if msg.width == 0 or msg.height == 0:
        raise ShapeError(f"CameraInfo has an empty image size ({msg.width}×{msg.height})")
    if k[0, 0] <= 0.0 or k[1, 1] <= 0.0:
        raise ShapeError(f"CameraInfo focal lengths must be > 0, got fx={k[0, 0]}, fy={k[1, 1]}")
    return CameraIntrinsics(int(msg.width), int(msg.height), float(k[0, 0]), float(k[1, 1]),
                            float(k[0, 2]), float(k[1, 2]))


def intrinsics_to_camera_info(intrinsics: CameraIntrinsics, frame_id: str = "",
                              stamp: Stamp | None = None) -> CameraInfo:
    msg = CameraInfo()
    msg.header.frame_id = frame_id
    if stamp is not None:
        msg.header.stamp = to_time_msg(stamp)
    msg.width, msg.height = intrinsics.width, intrinsics.height
    msg.distortion_model = "plumb_bob"
    msg.d = [0.0] * 5
    msg.k = intrinsics.matrix.ravel().tolist()
    msg.r = np.eye(3).ravel().tolist()
    projection = np.zeros((3, 4))
    projection[:, :3] = intrinsics.matrix
    msg.p = projection.ravel().tolist()
    return msg


def check_matches_image(intrinsics: CameraIntrinsics, width: int, height: int) -> None:
    """Raise :class:`ShapeError` when CameraInfo and the image disagree on size."""
    if (intrinsics.width, intrinsics.height) != (width, height):
        raise ShapeError(f"CameraInfo is {intrinsics.width}×{intrinsics.height} "
                         f"but the image is {width}×{height}")
