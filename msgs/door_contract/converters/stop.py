"""Stopping every execution with standard messages, as ros2_control does.

An empty ``JointTrajectory`` (no points) holds the arm where it is; an empty ``Path`` (no
poses) ends a walk at its next stable stance. The supervisor sends both; the sim bridge
reads either as a stop (:func:`is_stop`).
"""

from __future__ import annotations

from builtin_interfaces.msg import Time
from nav_msgs.msg import Path
from trajectory_msgs.msg import JointTrajectory

from door_contract.frames import Frame

__all__ = ["is_stop", "stop_messages"]


def stop_messages(stamp: Time) -> tuple[JointTrajectory, Path]:
    """The empty trajectory and the empty footstep path (in ``odom``) that stop all motion."""
    trajectory, path = JointTrajectory(), Path()
    trajectory.header.stamp, path.header.stamp, path.header.frame_id = stamp, stamp, Frame.ODOM.value
    return trajectory, path


def is_stop(command: JointTrajectory | Path) -> bool:
    """Whether ``command`` is a stop rather than motion (no points, no poses)."""
    return not (command.points if isinstance(command, JointTrajectory) else command.poses)
