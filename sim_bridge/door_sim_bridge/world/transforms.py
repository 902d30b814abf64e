"""4×4 homogeneous transforms ↔ PyBullet's (position, quaternion x y z w) pairs."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from scipy.spatial.transform import Rotation

__all__ = ["invert", "is_rigid", "pose_matrix", "position_quaternion", "translation"]


def pose_matrix(position: Sequence[float], quaternion: Sequence[float]) -> np.ndarray:
    """4×4 transform of a PyBullet position and unit (x, y, z, w) quaternion.

    Written out rather than through scipy: it runs several times per physics step.
    """
    x, y, z, w = quaternion
    transform = np.array([
        [1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - z * w), 2.0 * (x * z + y * w), position[0]],
        [2.0 * (x * y + z * w), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - x * w), position[1]],
        [2.0 * (x * z - y * w), 2.0 * (y * z + x * w), 1.0 - 2.0 * (x * x + y * y), position[2]],
        [0.0, 0.0, 0.0, 1.0]])
    return transform


def position_quaternion(transform: np.ndarray) -> tuple[list[float], list[float]]:
    """PyBullet (position, x y z w quaternion) of a 4×4 transform."""
    matrix = np.asarray(transform, dtype=float)
    return matrix[:3, 3].tolist(), Rotation.from_matrix(matrix[:3, :3]).as_quat().tolist()


def invert(transform: np.ndarray) -> np.ndarray:
    """Inverse of a rigid transform."""
    inverse = np.eye(4)
    rotation = transform[:3, :3]
    inverse[:3, :3] = rotation.T
    inverse[:3, 3] = -rotation.T @ transform[:3, 3]
    return inverse


def translation(offset: Sequence[float]) -> np.ndarray:
    """4×4 pure translation."""
    transform = np.eye(4)
    transform[:3, 3] = offset
    return transform


def is_rigid(transform: np.ndarray, tolerance: float = 1e-6) -> bool:
    """Finite 4×4 with an orthonormal, right-handed rotation and last row (0, 0, 0, 1)."""
    matrix = np.asarray(transform, dtype=float)
    if matrix.shape != (4, 4) or not np.all(np.isfinite(matrix)):
        return False
    rotation = matrix[:3, :3]
    return (np.allclose(rotation.T @ rotation, np.eye(3), atol=tolerance)
            and abs(np.linalg.det(rotation) - 1.0) < tolerance
            and np.allclose(matrix[3], (0.0, 0.0, 0.0, 1.0), atol=tolerance))
