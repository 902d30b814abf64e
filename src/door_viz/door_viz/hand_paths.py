"""Where the hands go along a proposed joint trajectory (ROS-free): forward kinematics of each
waypoint through Pinocchio (:mod:`door_robot.kinematics`).

Waypoint ``k``'s configuration is the robot's measured configuration with the trajectory's
joints set to ``positions[k]``; the tool-centre point of each hand is
``odom_T_tcp = odom_T_base · base_T_tcp(q_k)`` with the base pose measured when the proposal
arrived (the base stands still while the arms move).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from door_contract.converters.trajectory import JointPath
from door_robot.kinematics import RobotKinematics

__all__ = ["hand_paths", "waypoint_configurations"]


def waypoint_configurations(kinematics: RobotKinematics, measured: Mapping[str, float],
                            path: JointPath) -> np.ndarray:
    """(T, nq) configurations; joints the model does not have are ignored (e.g. the door's)."""
    known = set(kinematics.joint_names)
    q0 = kinematics.configuration({name: value for name, value in measured.items() if name in known})
    columns = [(k, int(kinematics.joint_indices([name])[0])) for k, name in enumerate(path.joint_names) if name in known]
    trajectory = np.repeat(q0[None, :], len(path.times), axis=0)
    for column, index in columns:
        trajectory[:, index] = path.positions[:, column]
    return trajectory


def hand_paths(kinematics: RobotKinematics, measured: Mapping[str, float], path: JointPath,
               base_pose: np.ndarray) -> dict[str, np.ndarray]:
    """(T, 3) positions in odom of each hand's TCP along ``path``, by side name."""
    trajectory = waypoint_configurations(kinematics, measured, path)
    paths = {}
    for side in kinematics.profile.arms:
        poses = kinematics.frame_poses(trajectory, kinematics.profile.tcp_frame(side))
        paths[side.value] = (np.asarray(base_pose) @ poses)[:, :3, 3]
    return paths
