"""The detection debug image, without ROS: the frame with the estimate drawn on it."""

from __future__ import annotations

import cv2
import numpy as np

from door_contract.converters.camera_info import CameraIntrinsics
from door_detection.estimate import DetectedDoor

__all__ = ["HANDLE_COLOUR", "LEAF_COLOUR", "draw_estimate"]

HANDLE_COLOUR = (255, 0, 0)
"""RGB of the circle (8 px radius) drawn at the handle."""
LEAF_COLOUR = (0, 255, 0)
"""RGB of the leaf's outline (its four corners), drawn when the edges were measured."""


def draw_estimate(rgb: np.ndarray, intrinsics: CameraIntrinsics, estimate: DetectedDoor) -> np.ndarray:
    """A copy of ``rgb`` (H×W×3, uint8) with the handle circled and, when every corner is
    known, the leaf outlined; the estimate is in the camera's optical frame."""
    overlay = np.ascontiguousarray(rgb.copy())
    corners = np.asarray(estimate.corners, dtype=float)
    points = [estimate.handle_position] + ([] if np.isnan(corners).any() else list(corners))
    pixels = intrinsics.project(np.array(points)).astype(int)
    cv2.circle(overlay, tuple(int(v) for v in pixels[0]), 8, HANDLE_COLOUR, 2)
    if len(pixels) == 5:
        cv2.polylines(overlay, [pixels[1:].reshape(-1, 1, 2)], True, LEAF_COLOUR, 2)
    return overlay
