"""``trajectory_msgs/JointTrajectory`` ↔ (times, joint names, positions)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from builtin_interfaces.msg import Duration
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

from door_contract.converters._checks import require_finite
from door_contract.errors import ShapeError

__all__ = ["JointPath", "joint_path_to_msg", "msg_to_joint_path"]


@dataclass(frozen=True, eq=False)
class JointPath:
    """A time-parameterised joint trajectory: ``positions[i]`` is reached at ``times[i]`` (s)."""

    times: np.ndarray  # (T,) seconds from the start, strictly increasing
    joint_names: tuple[str, ...]
    positions: np.ndarray  # (T, K) rad
    velocities: np.ndarray | None = None  # (T, K) rad/s

    def __post_init__(self) -> None:
        times = require_finite(self.times, "trajectory times")
        positions = require_finite(self.positions, "trajectory positions")
        if times.ndim != 1 or times.size == 0:
            raise ShapeError(f"trajectory times must be a non-empty vector, got shape {times.shape}")
        if positions.shape != (times.size, len(self.joint_names)):
            raise ShapeError(f"positions have shape {positions.shape}, expected "
                             f"{(times.size, len(self.joint_names))}")
        if np.any(np.diff(times) <= 0.0) or times[0] < 0.0:
            raise ShapeError("trajectory times must be ≥ 0 and strictly increasing")
        if len(set(self.joint_names)) != len(self.joint_names):
            raise ShapeError("trajectory joint names are not unique")
        if self.velocities is not None:
            velocities = require_finite(self.velocities, "trajectory velocities")
            if velocities.shape != positions.shape:
                raise ShapeError("velocities and positions differ in shape")


def _duration(seconds: float) -> Duration:
    whole = int(seconds // 1)
    return Duration(sec=whole, nanosec=int(round((seconds - whole) * 1e9)) % 1_000_000_000)


def joint_path_to_msg(path: JointPath, frame_id: str = "") -> JointTrajectory:
    msg = JointTrajectory()
    msg.header.frame_id = frame_id
    msg.joint_names = list(path.joint_names)
    for i, t in enumerate(path.times):
        point = JointTrajectoryPoint()
        point.positions = path.positions[i].astype(float).tolist()
        if path.velocities is not None:
            point.velocities = path.velocities[i].astype(float).tolist()
        point.time_from_start = _duration(float(t))
        msg.points.append(point)
    return msg


def msg_to_joint_path(msg: JointTrajectory) -> JointPath:
    """Validated :class:`JointPath`; raises ShapeError / NonFiniteError on bad input."""
    if not msg.points:
        raise ShapeError("trajectory has no points")
    count = len(msg.joint_names)
    if any(len(p.positions) != count for p in msg.points):
        raise ShapeError(f"every point needs {count} positions (one per joint name)")
    times = np.array([p.time_from_start.sec + p.time_from_start.nanosec * 1e-9 for p in msg.points])
    positions = np.array([list(p.positions) for p in msg.points], dtype=float)
    has_velocities = all(len(p.velocities) == count for p in msg.points)
    velocities = np.array([list(p.velocities) for p in msg.points]) if has_velocities else None
    return JointPath(times, tuple(msg.joint_names), positions, velocities)
