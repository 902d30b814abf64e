"""What both planner nodes listen to: the robot's odometry and the door estimates.

Each message is validated as it arrives (a NaN pose or malformed estimate is logged and
dropped) and the node's heartbeat reports the stamps it holds, so a client can wait until
a planner has its inputs instead of racing them.
"""

from __future__ import annotations

import numpy as np
from nav_msgs.msg import Odometry, Path
from rclpy.node import Node
from std_msgs.msg import String

from door_contract.converters.footsteps import FootPlacement, path_to_footsteps
from door_contract.converters.pose import pose_to_matrix
from door_contract.door_estimates import DoorEstimateHistory
from door_contract.errors import ContractError
from door_contract.node_support import Heartbeat, create_contract_subscription
from door_contract.payloads import DoorEstimate, decode
from door_contract.topics import Topics

__all__ = ["PlannerInputs"]


class PlannerInputs:
    def __init__(self, node: Node, heartbeat: Heartbeat) -> None:
        self._node, self._heartbeat = node, heartbeat
        self.base_pose: np.ndarray | None = None  # base in odom, 4×4
        self.doors = DoorEstimateHistory()
        self.feet: list[FootPlacement] | None = None  # [left, right] where the soles stand
        create_contract_subscription(node, Topics.ODOM, self._on_odom)
        create_contract_subscription(node, Topics.FOOT_POSES, self._on_feet)
        create_contract_subscription(node, Topics.DOOR_ESTIMATE, self._on_door)

    def _on_odom(self, msg: Odometry) -> None:
        try:
            self.base_pose = pose_to_matrix(msg.pose.pose)
        except ContractError as error:
            self.base_pose = None
            self._node.get_logger().warning(f"odometry rejected: {error}")
        stamp = f"{msg.header.stamp.sec}.{msg.header.stamp.nanosec:09d}"
        self._heartbeat.values["odom"] = "" if self.base_pose is None else stamp

    def _on_feet(self, msg: Path) -> None:
        try:
            feet = path_to_footsteps(msg)
        except ContractError as error:
            self._node.get_logger().warning(f"foot poses rejected: {error}")
            return
        self.feet = feet if len(feet) == 2 else None

    def _on_door(self, msg: String) -> None:
        try:
            self.doors.add(decode(DoorEstimate, msg.data))
        except ContractError as error:
            self._node.get_logger().warning(f"door estimate rejected: {error}")
        latest = self.doors.latest
        self._heartbeat.values["door"] = "" if latest is None else f"{latest.stamp:.3f}"
