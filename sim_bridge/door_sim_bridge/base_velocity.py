"""The base's velocity for /odom, without ROS: finite differences of its pose in simulated time."""

from __future__ import annotations

import numpy as np

__all__ = ["BaseVelocity"]


class BaseVelocity:
    """Linear velocity (m/s, ``odom``) of the base between two publications of its pose:
    v = (p(t) − p(t′)) / (t − t′), p the origin of the 4×4 pose. None before the second pose
    and when simulated time has not advanced."""

    def __init__(self) -> None:
        self._previous: tuple[float, np.ndarray] | None = None

    def update(self, now: float, base: np.ndarray) -> np.ndarray | None:
        """The velocity since the previous pose, and ``base`` at ``now`` remembered for the next."""
        previous, self._previous = self._previous, (now, np.array(base[:3, 3], dtype=float))
        if previous is None or now <= previous[0]:
            return None
        velocity: np.ndarray = (self._previous[1] - previous[1]) / (now - previous[0])
        return velocity
