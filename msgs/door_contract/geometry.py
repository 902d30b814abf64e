"""Planar pose helpers shared by the contract's converters and the ROS-free cores."""

from __future__ import annotations

import math

import numpy as np

__all__ = ["planar_pose", "yaw_of"]


def planar_pose(x: float, y: float, yaw: float, z: float = 0.0) -> np.ndarray:
    """4×4 transform of a pose in the ground plane (rotation about z by ``yaw``)."""
    transform = np.eye(4)
    c, s = math.cos(yaw), math.sin(yaw)
    transform[:2, :2] = [[c, -s], [s, c]]
    transform[:3, 3] = (x, y, z)
    return transform


def yaw_of(transform: np.ndarray) -> float:
    """Heading of a transform's x axis in the ground plane (rad)."""
    return math.atan2(transform[1, 0], transform[0, 0])
