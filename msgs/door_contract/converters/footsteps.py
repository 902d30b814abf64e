"""``nav_msgs/Path`` ↔ footsteps.

Convention of ``/footstep_plan`` and ``/footstep_planner/plan``: every pose is a sole pose in
``odom`` (x, y on the ground, yaw about z); **even indices are the left foot, odd indices
the right foot**. A plan whose first real step is with the right foot starts with the left
foot's current pose (a step in place).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from nav_msgs.msg import Path

from door_contract.converters._checks import require_finite
from door_contract.converters.pose import matrix_to_pose_stamped, pose_to_matrix
from door_contract.errors import ShapeError
from door_contract.frames import Frame
from door_contract.geometry import planar_pose, yaw_of
from door_contract.stamps import Stamp, to_time_msg
from door_contract.vocabulary import Foot

__all__ = ["FootPlacement", "foot_of_index", "footsteps_to_path", "path_to_footsteps"]


@dataclass(frozen=True)
class FootPlacement:
    """Where one sole lands: position (m) and yaw (rad) in ``odom``."""

    foot: Foot
    x: float
    y: float
    yaw: float


def foot_of_index(index: int) -> Foot:
    return Foot.LEFT if index % 2 == 0 else Foot.RIGHT


def footsteps_to_path(steps: Sequence[FootPlacement], stamp: Stamp | None = None) -> Path:
    """A Path in the alternation convention; raises ShapeError if feet do not alternate L, R, …"""
    path = Path()
    path.header.frame_id = Frame.ODOM.value
    if stamp is not None:
        path.header.stamp = to_time_msg(stamp)
    for index, step in enumerate(steps):
        if step.foot != foot_of_index(index):
            raise ShapeError(f"step {index} is the {step.foot.value} foot; the path convention "
                             f"needs the {foot_of_index(index).value} foot there")
        require_finite(np.array([step.x, step.y, step.yaw]), f"footstep {index}")
        pose = matrix_to_pose_stamped(planar_pose(step.x, step.y, step.yaw), Frame.ODOM.value, stamp)
        path.poses.append(pose)
    return path


def path_to_footsteps(path: Path) -> list[FootPlacement]:
    """Footsteps of a Path; rejects frames other than odom and non-finite poses."""
    if path.header.frame_id not in ("", Frame.ODOM.value):
        raise ShapeError(f"footstep plans must be in {Frame.ODOM.value!r}, got {path.header.frame_id!r}")
    steps = []
    for index, pose_stamped in enumerate(path.poses):
        transform = pose_to_matrix(pose_stamped.pose)
        steps.append(FootPlacement(foot_of_index(index), float(transform[0, 3]),
                                   float(transform[1, 3]), yaw_of(transform)))
    return steps
