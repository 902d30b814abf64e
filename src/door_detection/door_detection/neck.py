"""The neck's pan and tilt joints, found in the robot's URDF (through Pinocchio).

A robot profile names the head camera frame, not the neck; the neck is every revolute
joint that moves the camera frame but belongs to no arm chain (TALOS's torso joints belong
to its arm chains). With J the camera frame's Jacobian at the walking posture
(LOCAL_WORLD_ALIGNED, base axes), a joint's angular column ω is its axis in the base frame:
the **pan** joint is the one nearest the camera with ω within 15° of ±z (sign = sign ω_z:
turning about +z looks left), the **tilt** joint the one with ω within 15° of ±y (turning
about +y looks down: R_y(θ)·x = (cos θ, 0, −sin θ)). Position and speed limits are the
URDF's.

On TALOS this gives pan = ``head_2_joint`` (axis z, ±1.31 rad) and tilt = ``head_1_joint``
(axis y, −0.26 … 0.79 rad) — the reverse of what their numbering suggests — both at 1 rad/s.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from door_detection.view_search import Neck, NeckAxis

if TYPE_CHECKING:  # Pinocchio is imported only by the caller that builds the kinematics
    from door_robot.kinematics import RobotKinematics

__all__ = ["neck_of"]

AXIS_TOLERANCE_DEG = 15.0
"""Largest angle between a neck joint's axis and the base's z (pan) or y (tilt)."""


def neck_of(kinematics: RobotKinematics) -> Neck:
    """The :class:`Neck` of a :class:`door_robot.kinematics.RobotKinematics`."""
    profile = kinematics.profile
    q = kinematics.walking_q
    jacobian = kinematics.frame_jacobian(q, profile.head_camera_frame)
    arm_joints = {joint for arm in profile.arms.values() for joint in arm.joints}
    candidates = [name for name in kinematics.joint_names if name not in arm_joints]
    indices = kinematics.joint_indices(candidates) if candidates else np.zeros(0, dtype=int)
    columns = {name: jacobian[3:, index] for name, index in zip(candidates, indices)}
    moving = {name: axis for name, axis in columns.items() if np.linalg.norm(axis) > 0.5}
    nearest_first = sorted(moving, key=lambda name: -int(kinematics.joint_indices([name])[0]))
    return Neck(_axis(kinematics, moving, nearest_first, 2), _axis(kinematics, moving, nearest_first, 1))


def _axis(kinematics: RobotKinematics, axes: dict[str, np.ndarray], names: list[str], component: int) -> NeckAxis | None:
    limit = math.cos(math.radians(AXIS_TOLERANCE_DEG))
    for name in names:
        axis = axes[name] / np.linalg.norm(axes[name])
        if abs(float(axis[component])) >= limit:
            index = int(kinematics.joint_indices([name])[0])
            return NeckAxis(name, float(kinematics.lower_limits[index]), float(kinematics.upper_limits[index]),
                            math.copysign(1.0, float(axis[component])), float(kinematics.velocity_limits[index]))
    return None
