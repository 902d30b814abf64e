"""Error measures shared by the door-detection tests."""

from __future__ import annotations

import math

import numpy as np


def handle_error(estimated: np.ndarray, truth: np.ndarray) -> float:
    """Distance between two handle points (m)."""
    return float(np.linalg.norm(np.asarray(estimated) - np.asarray(truth)))


def angle_deg(a: np.ndarray, b: np.ndarray) -> float:
    """Angle between two unit vectors (deg)."""
    return math.degrees(math.acos(float(np.clip(np.asarray(a) @ np.asarray(b), -1.0, 1.0))))
